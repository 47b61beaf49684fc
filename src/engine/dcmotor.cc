// The DC motor actuator (MuJoCo 3.7, its controller as redesigned in 3.12):
//
//   electrical:  te i' = V / R - (K / R) l' - i     (current i, when te = L / R > 0)
//   torque:      p = K i, or without inductance p = (K / R)(V - K l')
//   voltage:     V = ctrl (input "voltage"), or from the torque-space controller
//                tau = kp (qref - l) + kd (vref - l') + ki x + ff, V = (R / K) tau + K l'
//                (clamped to vmax), plus a raw voltage input when there is one
//   resistance:  R (1 + alpha (T + Tambient - T0)) with the winding's temperature rise T,
//                C T' = R i^2 - T / RT
//   mechanics:   cogging A sin(Np l + phase) and LuGre friction sigma0 z + sigma1 z',
//                z' = l' - sigma0 |l'| z / g(l'), added after the force clamp
//
// Its states, each present when its parameter is set, in this order: the slew-limited
// setpoint, the position error's integral, the temperature rise, the bristle deflection
// z and the current (always last). Parameters: gainprm = [R K alpha T0 kp ki kd vmax],
// dynprm = [te di/dt_max RT C Tambient sigma0 sigma1 slewmax imax], biasprm = [A Np
// phase Fcoulomb Fstatic vstribeck].
#include <algorithm>
#include <cmath>

#include "engine/engine.h"
#include "engine/servo.h"

namespace simlab {

namespace {

// A slot index of each state, -1 when absent.
struct DcmotorSlots {
  int slew = -1, integral = -1, temperature = -1, bristle = -1, current = -1;
};

DcmotorSlots SlotsOf(const Model& m, int i) {
  const double* dyn = &m.actuator_dynprm[kNDyn * i];
  const double* gain = &m.actuator_gainprm[kNGain * i];
  DcmotorSlots s;
  int n = 0;
  if (dyn[7] > 0) s.slew = n++;
  if (gain[5] > 0) s.integral = n++;
  if (dyn[2] > 0) s.temperature = n++;
  if (dyn[5] > 0) s.bristle = n++;
  if (dyn[0] > 0) s.current = n++;
  return s;
}

// The Stribeck curve: friction from Coulomb (fast) to static (slow) level.
double Stribeck(const double* biasprm, double velocity) {
  double ratio = velocity / std::max(kMinVal, biasprm[5]);
  return biasprm[3] + (biasprm[4] - biasprm[3]) * std::exp(-ratio * ratio);
}

// The bristle's decay rate at this velocity: z' = rate z + velocity.
double BristleRate(const Model& m, int i, double velocity) {
  double sigma0 = m.actuator_dynprm[kNDyn * i + 5];
  return -sigma0 * std::abs(velocity) /
         std::max(kMinVal, Stribeck(&m.actuator_biasprm[kNBias * i], velocity));
}

// The terminal voltage from the inputs (packed pos, vel, ff, voltage; absent ones 0): the
// controller's torque made voltage (back-EMF compensated, clamped to vmax), plus the raw
// voltage input.
double Voltage(const Model& m, int i, const double* u, double length, double velocity,
               double integral) {
  int spec = m.actuator_ctrlspec[i];
  double in[4];
  int k = 0;
  for (int bit = 0; bit < 4; bit++) in[bit] = (spec & (1 << bit)) ? u[k++] : 0;
  const double* g = &m.actuator_gainprm[kNGain * i];
  double voltage = 0;
  if (spec & (kInputPos | kInputVel | kInputFf)) {
    double torque = g[4] * (in[0] - length) + g[6] * (in[1] - velocity) + g[5] * integral + in[2];
    voltage = g[0] / g[1] * torque + g[1] * velocity;
    if (g[7] > 0) voltage = std::clamp(voltage, -g[7], g[7]);
  }
  return voltage + in[3];
}

// R at the winding's temperature (the nominal R without a thermal state).
double Resistance(const Model& m, const Data& d, int i, const DcmotorSlots& s) {
  const double* g = &m.actuator_gainprm[kNGain * i];
  double r = g[0];
  if (s.temperature >= 0) {
    double rise = d.act[m.actuator_actadr[i] + s.temperature];
    r *= 1 + g[2] * (rise + m.actuator_dynprm[kNDyn * i + 4] - g[3]);
  }
  return r;
}

}  // namespace

void DcmotorActivation(const Model& m, Data& d, int i, double* ctrl) {
  const double* dyn = &m.actuator_dynprm[kNDyn * i];
  const double* g = &m.actuator_gainprm[kNGain * i];
  DcmotorSlots s = SlotsOf(m, i);
  int first = m.actuator_actadr[i], last = first + m.actuator_actnum[i] - 1;
  int o = m.actuator_outadr[i], u = m.actuator_ctrladr[i];
  double h = m.opt.timestep, l = d.actuator_length[o], velocity = d.actuator_velocity[o];
  double r = g[0], k = g[1], te = dyn[0];

  // The setpoint moves at most slewmax per second; the local ctrl keeps the limited one.
  if (s.slew >= 0) {
    ctrl[u] = SlewLimit(ctrl[u], d.act[first + s.slew], dyn[7], h, &d.act_dot[first + s.slew]);
  }
  // The integral of the position error stops growing past imax.
  double integral = 0;
  if (s.integral >= 0) {
    integral = d.act[first + s.integral];
    d.act_dot[first + s.integral] = IntegralRate(ctrl[u] - l, integral, dyn[8]);
  }
  double voltage = Voltage(m, i, ctrl + u, l, velocity, integral);
  // The winding heats by R i^2 and cools through RT.
  if (s.temperature >= 0) {
    double rise = d.act[first + s.temperature];
    r *= 1 + g[2] * (rise + dyn[4] - g[3]);
    double current = te > 0 ? d.act[last] : (voltage - k * velocity) / r;
    d.act_dot[first + s.temperature] = (r * current * current - rise / dyn[2]) / dyn[3];
  }
  if (s.bristle >= 0) {
    int z = first + s.bristle;
    d.act_dot[z] = BristleRate(m, i, velocity) * d.act[z] + velocity;
  }
  if (s.current >= 0) {
    double rate = (voltage / r - k / r * velocity - d.act[last]) / te;
    if (dyn[1] > 0) rate = std::clamp(rate, -dyn[1], dyn[1]);
    d.act_dot[last] = rate;
  }
}

double DcmotorForce(const Model& m, const Data& d, int i, double* ctrl) {
  const double* g = &m.actuator_gainprm[kNGain * i];
  DcmotorSlots s = SlotsOf(m, i);
  int first = m.actuator_actadr[i], o = m.actuator_outadr[i], u = m.actuator_ctrladr[i];
  double te = m.actuator_dynprm[kNDyn * i], k = g[1];
  double gain = te > 0 ? k : k / std::max(kMinVal, Resistance(m, d, i, s));
  // A controller (or a raw voltage beside it) turns the inputs into the voltage.
  int ctrlnum = m.actuator_ctrlnum[i];
  if (m.actuator_ctrlspec[i] != kInputVoltage && ctrlnum > 0) {
    double integral = s.integral >= 0 ? d.act[first + s.integral] : 0;
    ctrl[u] = Voltage(m, i, ctrl + u, d.actuator_length[o], d.actuator_velocity[o], integral);
  }
  if (te > 0) {
    int last = first + m.actuator_actnum[i] - 1;
    return gain * NextActivation(m, d, i, last, d.act_dot[last]);
  }
  double input = ctrlnum ? ctrl[u] : 0;
  double bias = 0 - gain * k * d.actuator_velocity[o];
  return gain * input + bias;
}

void DcmotorMechanics(const Model& m, Data& d, int i) {
  const double* b = &m.actuator_biasprm[kNBias * i];
  const double* dyn = &m.actuator_dynprm[kNDyn * i];
  int o = m.actuator_outadr[i];
  if (b[0] != 0) d.actuator_force[o] += b[0] * std::sin(b[1] * d.actuator_length[o] + b[2]);
  if (dyn[5] > 0) {
    int z = m.actuator_actadr[i] + SlotsOf(m, i).bristle;
    d.actuator_force[o] -= dyn[5] * d.act[z] + dyn[6] * d.act_dot[z];
  }
}

double DcmotorNextActivation(const Model& m, const Data& d, int i, int act_adr, double act_dot) {
  const double* dyn = &m.actuator_dynprm[kNDyn * i];
  DcmotorSlots s = SlotsOf(m, i);
  int slot = act_adr - m.actuator_actadr[i];
  double act = d.act[act_adr], h = m.opt.timestep;
  // The current relaxes exactly over the step; the bristle follows its linear ODE exactly
  // for the velocity held (zero-order hold); the rest step by Euler, the integral clamped.
  if (slot == s.current) {
    double te = std::max(kMinVal, dyn[0]);
    return act + act_dot * te * (1 - std::exp(-h / te));
  }
  if (slot == s.bristle) {
    double velocity = d.actuator_velocity[m.actuator_outadr[i]];
    double rate = BristleRate(m, i, velocity);
    double decay = std::exp(rate * h);
    double input = std::abs(rate) > kMinVal ? (decay - 1) / rate : h;
    return decay * act + input * velocity;
  }
  act = act + act_dot * h;
  if (slot == s.integral && dyn[8] > 0) act = std::clamp(act, -dyn[8], dyn[8]);
  return act;
}

double DcmotorDampingDerivative(const Model& m, int i) {
  const double* dyn = &m.actuator_dynprm[kNDyn * i];
  const double* g = &m.actuator_gainprm[kNGain * i];
  double te = dyn[0], k = g[1], r = std::max(kMinVal, g[0]);
  double slope = 0;
  // Back-EMF without inductance; the controller's damping through the voltage (nominal R,
  // vmax ignored); LuGre's micro-damping.
  if (te <= 0) slope -= k * k / r;
  double dvdw = 0;
  if (m.actuator_ctrlspec[i] & (kInputPos | kInputVel | kInputFf)) dvdw = -g[6] * r / k + k;
  if (te > 0) {
    slope += k * (dvdw - k) * (1 - std::exp(-m.opt.timestep / te)) / r;
  } else if (dvdw != 0) {
    slope += k * dvdw / r;
  }
  if (dyn[6] > 0) slope -= dyn[6];
  return slope;
}

}  // namespace simlab
