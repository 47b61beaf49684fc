// Delays and sampling (MuJoCo 3.5's history buffers): actuators and sensors with
// nsample > 0 keep their last nsample samples in d.history, each buffer laid out as
//
//   [user, cursor, times(n), values(n x dim)]
//
// a ring whose slot `cursor` holds the newest sample. An actuator's user number is
// unused; a sensor's is the time of its last tick when it is sampled at an interval.
//
//   reset:    times spaced one timestep (or one period, on the timestep grid) apart,
//             ending before time 0, values zero.
//   record:   at the start of each integration (MuJoCo's mj_advance), before time moves,
//             ctrl and the sensors' values are written at d.time.
//   read:     a delayed ctrl or sensor is the buffer's value at time - delay: held
//             (zoh), linear or cubic (Catmull-Rom slopes, flat at the ends) between
//             samples, the oldest or newest value outside them.
//   interval: a sensor ticks when its last tick + period is reached; between ticks it
//             reads its buffer (so holds its last tick's value when it has no delay).
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/engine.h"
#include "engine/sensor.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

enum Interp { kInterpHold = 0, kInterpLinear = 1, kInterpCubic = 2 };

// One history buffer seen through its layout. `age` counts samples from the oldest
// (0) to the newest (n - 1); `slot` is where a sample sits in the ring.
template <typename Number>
struct Ring {
  Number* buf;
  int n;
  int dim;

  int Cursor() const { return static_cast<int>(buf[1]); }
  Number* Times() const { return buf + 2; }
  Number* Values() const { return buf + 2 + n; }
  int Slot(int age) const { return (Cursor() + 1 + age) % n; }
  double TimeAt(int age) const { return Times()[Slot(age)]; }
  Number* ValueAt(int age) const { return Values() + static_cast<size_t>(Slot(age)) * dim; }

  // The first age whose time is at or after t: 0 when t is at or before the oldest
  // sample, n when it is after the newest (bisection over the ring).
  int FirstAtOrAfter(double t) const {
    if (t <= TimeAt(0)) return 0;
    if (t > TimeAt(n - 1)) return n;
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      int mid = (lo + hi) / 2;
      if (TimeAt(mid) < t) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    return hi;
  }
};

Ring<double> ActuatorRing(const Model& m, Data& d, int i) {
  return {&d.history[m.actuator_historyadr[i]], m.actuator_history[2 * i], 1};
}
Ring<const double> ActuatorRing(const Model& m, const Data& d, int i) {
  return {&d.history[m.actuator_historyadr[i]], m.actuator_history[2 * i], 1};
}
Ring<double> SensorRing(const Model& m, Data& d, int i) {
  return {&d.history[m.sensor_historyadr[i]], m.sensor_history[2 * i], m.sensor_dim[i]};
}
Ring<const double> SensorRing(const Model& m, const Data& d, int i) {
  return {&d.history[m.sensor_historyadr[i]], m.sensor_history[2 * i], m.sensor_dim[i]};
}

// The slot for a sample at time t, kept in time order: the slot of an equal time, the
// oldest slot for a time before every sample, a new newest slot (dropping the oldest)
// for a time after them, otherwise the older samples shift down to make room.
double* InsertSample(Ring<double> ring, double t) {
  int n = ring.n, dim = ring.dim;
  int age = ring.FirstAtOrAfter(t);
  if (age < n && std::abs(t - ring.TimeAt(age)) < kMinVal) return ring.ValueAt(age);
  if (age == 0) {
    ring.Times()[ring.Slot(0)] = t;
    return ring.ValueAt(0);
  }
  if (age == n) {
    // The oldest slot becomes the newest.
    int newest = ring.Slot(0);
    ring.buf[1] = newest;
    ring.Times()[newest] = t;
    return ring.Values() + static_cast<size_t>(newest) * dim;
  }
  for (int k = 0; k + 1 < age; k++) {
    ring.Times()[ring.Slot(k)] = ring.TimeAt(k + 1);
    std::copy_n(ring.ValueAt(k + 1), dim, ring.ValueAt(k));
  }
  ring.Times()[ring.Slot(age - 1)] = t;
  return ring.ValueAt(age - 1);
}

// The Catmull-Rom slope of one component at sample `age`, from its neighbours `before`
// and `after`; 0 at the ends of the buffer.
double Slope(Ring<const double> ring, int before, int after, int component, bool at_end) {
  if (at_end) return 0;
  double dv = ring.ValueAt(after)[component] - ring.ValueAt(before)[component];
  return dv / (ring.TimeAt(after) - ring.TimeAt(before));
}

// Between samples lo = age - 1 and hi = age: linear or cubic Hermite interpolation.
void Interpolate(Ring<const double> ring, int age, double t, int interp, double* out) {
  int lo = age - 1, hi = age;
  double span = ring.TimeAt(hi) - ring.TimeAt(lo);
  double s = (t - ring.TimeAt(lo)) / span;
  const double* vlo = ring.ValueAt(lo);
  const double* vhi = ring.ValueAt(hi);
  if (interp == kInterpLinear) {
    for (int k = 0; k < ring.dim; k++) out[k] = vlo[k] + s * (vhi[k] - vlo[k]);
    return;
  }
  // Hermite basis on [lo, hi].
  double s2 = s * s, s3 = s2 * s;
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
  double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  for (int k = 0; k < ring.dim; k++) {
    double slope_lo = Slope(ring, lo - 1, hi, k, lo == 0);
    double slope_hi = Slope(ring, lo, hi + 1, k, hi == ring.n - 1);
    out[k] = h00 * vlo[k] + h10 * span * slope_lo + h01 * vhi[k] + h11 * span * slope_hi;
  }
}

// The buffer's value at time t into out (dim numbers).
void ReadRing(Ring<const double> ring, double t, int interp, double* out) {
  const double* sample = nullptr;
  if (t <= ring.TimeAt(0) + kMinVal) {
    sample = ring.ValueAt(0);
  } else if (t >= ring.TimeAt(ring.n - 1) - kMinVal) {
    sample = ring.ValueAt(ring.n - 1);
  } else {
    int age = ring.FirstAtOrAfter(t);
    if (std::abs(t - ring.TimeAt(age)) < kMinVal) {
      sample = ring.ValueAt(age);
    } else if (interp == kInterpHold) {
      sample = ring.ValueAt(age - 1);
    } else {
      return Interpolate(ring, age, t, interp, out);
    }
  }
  std::copy_n(sample, ring.dim, out);
}

// Times and values given by the caller; times must increase strictly. The cursor
// points at the last slot again.
void InitRing(Ring<double> ring, const double* times, const double* values, double user) {
  for (int k = 0; k + 1 < ring.n; k++) {
    if (times[k + 1] - times[k] < kMinVal) {
      throw Error("history times must be strictly increasing, got times[" + std::to_string(k) +
                  "]=" + std::to_string(times[k]) + " >= times[" + std::to_string(k + 1) +
                  "]=" + std::to_string(times[k + 1]));
    }
  }
  ring.buf[0] = user;
  ring.buf[1] = ring.n - 1;
  if (times != ring.Times()) std::copy_n(times, ring.n, ring.Times());
  if (values) std::copy_n(values, static_cast<size_t>(ring.n) * ring.dim, ring.Values());
}

void CheckId(int id, int count, const char* what) {
  if (id < 0 || id >= count) throw Error(std::string("invalid ") + what + " id " + std::to_string(id));
}

// An interval sensor's first tick: at time 0 without a phase, else at phase + period.
double FirstTickBase(double period, double phase) { return phase == 0 ? -period : phase; }

// Whether an interval sensor's next tick has come.
bool TickDue(const Model& m, const Data& d, int i) {
  return d.history[m.sensor_historyadr[i]] + m.sensor_interval[2 * i] <= d.time;
}

// Sample times before time 0: one timestep apart, or for an interval sensor one period
// apart from its tick base, each rounded up to the timestep grid.
void ResetTimes(double* times, int n, double dt, double period, double phase) {
  for (int j = 0; j < n; j++) {
    if (period > 0) {
      double tick = FirstTickBase(period, phase) - (n - 1 - j) * period;
      times[j] = std::ceil(tick / dt) * dt;
    } else {
      times[j] = -(n - j) * dt;
    }
  }
}

// A buffer's user number, its cursor at the last slot and zero values.
void ClearRing(Ring<double> ring, double user) {
  ring.buf[0] = user;
  ring.buf[1] = ring.n - 1;
  std::fill_n(ring.Values(), static_cast<size_t>(ring.n) * ring.dim, 0.0);
}

// One sensor's sample at d.time, written when the integration starts.
void RecordSensor(const Model& m, Data& d, int i) {
  Ring<double> ring = SensorRing(m, d, i);
  double period = m.sensor_interval[2 * i];
  bool delayed = m.sensor_delay[i] > 0;
  if (period > 0) {
    if (!TickDue(m, d, i)) return;
    ring.buf[0] += period;  // ticks stay on the exact period, not the timestep grid
  }
  double* slot = InsertSample(ring, d.time);
  if (delayed) {
    // sensordata holds the delayed value: compute the current one.
    ComputeSensor(m, d, i, slot);
  } else {
    const double* now = &d.sensordata[m.sensor_adr[i]];
    std::copy_n(now, ring.dim, slot);
  }
}

}  // namespace

// ---------------------------------------------------------------- engine hooks

void ResetHistory(const Model& m, Data& d) {
  double dt = m.opt.timestep;
  if (m.nhistory && dt <= 0) {
    throw Error("history buffers require a positive timestep, got " + std::to_string(dt));
  }
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_history[2 * i] <= 0) continue;
    Ring<double> ring = ActuatorRing(m, d, i);
    ClearRing(ring, 0);
    ResetTimes(ring.Times(), ring.n, dt, 0, 0);
  }
  for (int i = 0; i < m.nsensor; i++) {
    if (m.sensor_history[2 * i] <= 0) continue;
    Ring<double> ring = SensorRing(m, d, i);
    double period = m.sensor_interval[2 * i], phase = m.sensor_interval[2 * i + 1];
    ClearRing(ring, period > 0 ? FirstTickBase(period, phase) : -dt);
    ResetTimes(ring.Times(), ring.n, dt, period, phase);
  }
}

void RecordHistory(const Model& m, Data& d) {
  if (m.nhistory == 0) return;
  // (an actuator with a history reads one control)
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_history[2 * i] <= 0) continue;
    *InsertSample(ActuatorRing(m, d, i), d.time) = d.ctrl[m.actuator_ctrladr[i]];
  }
  for (int i = 0; i < m.nsensor; i++) {
    if (m.sensor_history[2 * i] > 0) RecordSensor(m, d, i);
  }
}

double ActuatorInput(const Model& m, const Data& d, int i) {
  return m.actuator_delay[i] != 0 ? ReadCtrl(m, d, i, d.time) : d.ctrl[m.actuator_ctrladr[i]];
}

void ComputeOrReadSensor(const Model& m, Data& d, int i, double* out) {
  // Delayed: always the buffer. Interval: computed on a tick, else the buffer.
  bool sampled = m.sensor_history[2 * i] > 0;
  bool read = sampled && (m.sensor_delay[i] > 0 ||
                          (m.sensor_interval[2 * i] > 0 && !TickDue(m, d, i)));
  if (read) {
    ReadSensor(m, d, i, d.time, out);
  } else {
    ComputeSensor(m, d, i, out);
  }
}

// ---------------------------------------------------------------- public functions

double ReadCtrl(const Model& m, const Data& d, int id, double time, int interp) {
  CheckId(id, m.nactuator, "actuator");
  if (m.actuator_history[2 * id] <= 0) return d.ctrl[m.actuator_ctrladr[id]];
  if (interp < 0) interp = m.actuator_history[2 * id + 1];
  double value = 0;
  ReadRing(ActuatorRing(m, d, id), time - m.actuator_delay[id], interp, &value);
  return value;
}

void ReadSensor(const Model& m, const Data& d, int id, double time, double* out, int interp) {
  CheckId(id, m.nsensor, "sensor");
  if (m.sensor_history[2 * id] <= 0) {
    const double* now = &d.sensordata[m.sensor_adr[id]];
    std::copy_n(now, m.sensor_dim[id], out);
    return;
  }
  if (interp < 0) interp = m.sensor_history[2 * id + 1];
  ReadRing(SensorRing(m, d, id), time - m.sensor_delay[id], interp, out);
}

void InitCtrlHistory(const Model& m, Data& d, int id, const double* times, const double* values) {
  CheckId(id, m.nactuator, "actuator");
  if (m.actuator_history[2 * id] <= 0) {
    throw Error("actuator " + std::to_string(id) + " has no history buffer");
  }
  Ring<double> ring = ActuatorRing(m, d, id);
  InitRing(ring, times ? times : ring.Times(), values, ring.buf[0]);
}

void InitSensorHistory(const Model& m, Data& d, int id, const double* times, const double* values,
                       double phase) {
  CheckId(id, m.nsensor, "sensor");
  if (m.sensor_history[2 * id] <= 0) {
    throw Error("sensor " + std::to_string(id) + " has no history buffer");
  }
  Ring<double> ring = SensorRing(m, d, id);
  InitRing(ring, times ? times : ring.Times(), values, phase);
}

}  // namespace simlab
