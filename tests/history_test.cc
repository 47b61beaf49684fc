// Delays and sampling (history buffers), shown directly on tests/sensors/history_sensors.xml
// (whose whole rollouts agree with MuJoCo in the sensor conformance cases): a delayed
// sensor reads the undelayed one's value from `delay` seconds earlier (or between two
// of its samples, interpolated), an interval sensor holds between its ticks, a delayed
// actuator's force follows ctrl `delay` seconds late while d.ctrl stays the input; plus
// the public reading / initializing functions and the loader's checks.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

const std::string kModel = std::string(SIMLAB_SOURCE_DIR) + "/tests/sensors/history_sensors.xml";

// The steps of a rollout: time and what each named sensor read after Forward at it.
struct Sample {
  double time;
  std::map<std::string, std::vector<double>> sensor;
  std::vector<double> ctrl, force;
};

// Steps with a smooth control on every actuator, recording each Forward's outputs.
std::vector<Sample> Rollout(const Model& m, Data& d, int steps) {
  std::vector<Sample> out;
  for (int k = 0; k < steps; k++) {
    for (int u = 0; u < m.nu; u++) d.ctrl[u] = 0.8 * std::sin(20 * d.time + u);
    Forward(m, d);
    Sample s{d.time, {}, {d.ctrl.begin(), d.ctrl.end()},
             {d.actuator_force.begin(), d.actuator_force.end()}};
    for (int i = 0; i < m.nsensor; i++) {
      auto data = SensorData(m, d, m.sensor_names[i]);
      s.sensor[m.sensor_names[i]] = {data.begin(), data.end()};
    }
    out.push_back(s);
    Step(m, d);
  }
  return out;
}

class History : public ::testing::Test {
 protected:
  void SetUp() override {
    m = LoadXml(kModel);
    d = MakeData(m);
    steps = Rollout(m, d, 150);
  }
  // The number of whole steps in `seconds`.
  int Steps(double seconds) const { return static_cast<int>(std::lround(seconds / m.opt.timestep)); }
  Model m;
  Data d;
  std::vector<Sample> steps;
};

TEST_F(History, DelayedSensorReadsTheValueFromDelayAgo) {
  // zoh_whole: delay 0.012 = 3 steps, exactly the undelayed value 3 steps back (zero,
  // the reset samples, before time 0.012).
  int lag = Steps(0.012);
  double moved = 0;
  for (size_t k = 0; k < steps.size(); k++) {
    double expect = k >= static_cast<size_t>(lag) ? steps[k - lag].sensor["now"][0] : 0.0;
    EXPECT_EQ(steps[k].sensor["zoh_whole"][0], expect) << "t=" << steps[k].time;
    moved = std::max(moved, std::abs(steps[k].sensor["now"][0] - expect));
  }
  EXPECT_GT(moved, 1e-3);  // the delay is visible
}

TEST_F(History, DelayBetweenSamplesHoldsOrInterpolates) {
  // delay 0.01 = 2.5 steps: zoh holds the older neighbour (3 steps back), linear is the
  // mean of the neighbours 3 and 2 steps back.
  for (size_t k = 3; k < steps.size(); k++) {
    double older = steps[k - 3].sensor["now"][0], newer = steps[k - 2].sensor["now"][0];
    EXPECT_EQ(steps[k].sensor["zoh_between"][0], older);
    EXPECT_NEAR(steps[k].sensor["linear_between"][0], 0.5 * (older + newer), 1e-13);
    // cubic: Hermite midpoint with Catmull-Rom slopes from the neighbours' neighbours.
    if (k < 4) continue;
    double before = steps[k - 4].sensor["now"][0], after = steps[k - 1].sensor["now"][0];
    double cubic = 0.5 * (older + newer) + 0.125 * ((newer - before) - (after - older)) / 2;
    EXPECT_NEAR(steps[k].sensor["cubic_between"][0], cubic, 1e-13) << "t=" << steps[k].time;
  }
}

TEST_F(History, IntervalSensorHoldsBetweenTicks) {
  // clock_sampled (period 0.01, timestep 0.004) ticks at the first step at or after each
  // multiple of the period and holds that step's time until the next tick.
  double next_tick = 0, held = -1;
  int ticks = 0;
  for (const Sample& s : steps) {
    double value = s.sensor.at("clock_sampled")[0];
    if (s.time + 1e-12 >= next_tick) {
      EXPECT_NEAR(value, s.time, 1e-15);
      held = value;
      next_tick += 0.01;
      ticks++;
    } else {
      EXPECT_EQ(value, held) << "t=" << s.time;
    }
  }
  EXPECT_GT(ticks, 50);

  // tip_sampled (framepos, period 0.03) is constant between its ticks.
  for (size_t k = 1; k < steps.size(); k++) {
    double t = steps[k].time;
    bool tick = std::floor(t / 0.03 + 1e-9) != std::floor(steps[k - 1].time / 0.03 + 1e-9);
    if (!tick) EXPECT_EQ(steps[k].sensor["tip_sampled"], steps[k - 1].sensor["tip_sampled"]);
  }
}

TEST_F(History, DelayedActuatorUsesOldCtrlAndReportsCurrentCtrl) {
  // m_zoh: motor, gear 3, ctrlrange [-1, 1], delay 0.012 = 3 steps: its force is the
  // ctrl of 3 steps ago; d.ctrl is still what was written this step.
  int id = NameToId(m, kObjActuator, "m_zoh");
  int lag = Steps(0.012);
  for (size_t k = 0; k < steps.size(); k++) {
    double old_ctrl = k >= static_cast<size_t>(lag) ? steps[k - lag].ctrl[id] : 0.0;
    EXPECT_EQ(steps[k].force[id], old_ctrl);
    EXPECT_EQ(steps[k].ctrl[id], 0.8 * std::sin(20 * steps[k].time + id));
  }
  // m_buffer_only keeps a buffer but has no delay: its force is this step's ctrl.
  int now = NameToId(m, kObjActuator, "m_buffer_only");
  for (const Sample& s : steps) EXPECT_EQ(s.force[now], s.ctrl[now]);
}

TEST_F(History, ReadFunctions) {
  // After the rollout d holds the state after the last Step; its buffers hold samples
  // up to the last Forward's time.
  const Sample& last = steps.back();
  int zoh = NameToId(m, kObjActuator, "m_zoh");
  EXPECT_EQ(ReadCtrl(m, d, zoh, last.time), steps[steps.size() - 1 - Steps(0.012)].ctrl[zoh]);
  // Explicit linear interpolation halfway between two samples.
  double mid = ReadCtrl(m, d, zoh, last.time + 0.012 - 0.002, 1);
  EXPECT_NEAR(mid, 0.5 * (last.ctrl[zoh] + steps[steps.size() - 2].ctrl[zoh]), 1e-13);

  // A buffer without delay: the value at any recorded time.
  int buffered = SensorId(m, "buffer_only");
  double value = 0;
  ReadSensor(m, d, buffered, steps[steps.size() - 3].time, &value);
  EXPECT_EQ(value, steps[steps.size() - 3].sensor["buffer_only"][0]);
  // No buffer: the current sensordata.
  ReadSensor(m, d, SensorId(m, "now"), -5, &value);
  EXPECT_EQ(value, SensorData(m, d, "now")[0]);
  EXPECT_THROW(ReadSensor(m, d, m.nsensor, 0, &value), Error);
  EXPECT_THROW(ReadCtrl(m, d, -1, 0), Error);
}

TEST(HistoryInit, InitializedBuffersAreRead) {
  Model m = LoadXml(kModel);
  Data d = MakeData(m);
  // m_linear: 6 samples, delay 0.01, linear. Times 0..0.05, values 0..5.
  int id = NameToId(m, kObjActuator, "m_linear");
  std::vector<double> times = {0, 0.01, 0.02, 0.03, 0.04, 0.05}, values = {0, 1, 2, 3, 4, 5};
  InitCtrlHistory(m, d, id, times.data(), values.data());
  EXPECT_NEAR(ReadCtrl(m, d, id, 0.035), 2.5, 1e-12);  // reads time 0.025
  EXPECT_EQ(ReadCtrl(m, d, id, 0.035, 0), 2);          // held
  EXPECT_EQ(ReadCtrl(m, d, id, 1), 5);                 // after the newest
  EXPECT_EQ(ReadCtrl(m, d, id, -1), 0);                // before the oldest
  d.time = 0.035;
  Forward(m, d);
  EXPECT_EQ(d.actuator_force[id], 1.0);  // 2.5 clamped to its ctrlrange

  // Sensor buffer: new values (keeping its times), then times that do not increase.
  int s = SensorId(m, "buffer_only");
  std::vector<double> four = {7, 8, 9, 10};
  InitSensorHistory(m, d, s, nullptr, four.data(), 0);
  double value = 0;
  ReadSensor(m, d, s, -0.004, &value);  // reset times: -0.016 .. -0.004
  EXPECT_EQ(value, 10);
  std::vector<double> flat = {0, 0, 1, 2};
  EXPECT_THROW(InitSensorHistory(m, d, s, flat.data(), nullptr, 0), Error);

  // An actuator without a buffer: ReadCtrl is ctrl itself, it has nothing to initialize.
  Model plain = LoadXmlString(
      "<mujoco><worldbody><body><joint name=\"j\"/><geom size=\".1\"/></body></worldbody>"
      "<actuator><motor joint=\"j\"/></actuator></mujoco>");
  Data pd = MakeData(plain);
  pd.ctrl[0] = 0.25;
  EXPECT_EQ(ReadCtrl(plain, pd, 0, -3), 0.25);
  EXPECT_THROW(InitCtrlHistory(plain, pd, 0, nullptr, nullptr), Error);
}

TEST(HistoryErrors, LoaderChecksDelaysWithFileAndLine) {
  std::string head =
      "<mujoco>\n<worldbody>\n<body>\n<joint name=\"j\" axis=\"0 1 0\"/>\n"
      "<geom size=\".1\"/>\n</body>\n</worldbody>\n";
  test_util::ExpectMessageParts(
      test_util::XmlLoadError(head + "<actuator>\n<motor joint=\"j\" delay=\"0.1\"/>\n</actuator>\n</mujoco>\n"),
      {"bad.xml:9:", "<motor>", "delay > 0 without a history buffer"}, "actuator delay");
  test_util::ExpectMessageParts(
      test_util::XmlLoadError(head + "<actuator>\n<motor joint=\"j\" nsample=\"2\" interp=\"spline\"/>\n"
                                     "</actuator>\n</mujoco>\n"),
      {"bad.xml:9:", "interp"}, "bad interp");
  test_util::ExpectMessageParts(
      test_util::XmlLoadError(head + "<sensor>\n<jointpos joint=\"j\" nsample=\"2\" interval=\"0.1 -0.2\"/>\n"
                                     "</sensor>\n</mujoco>\n"),
      {"bad.xml:9:", "phase must be greater than -period"}, "phase");
  // The model's numbers: interp and the buffer layout, actuators first.
  Model m = LoadXml(kModel);
  int linear = NameToId(m, kObjActuator, "m_linear");
  EXPECT_EQ(m.actuator_history[2 * linear], 6);  // from the default class
  EXPECT_EQ(m.actuator_history[2 * linear + 1], 1);
  EXPECT_EQ(m.actuator_delay[linear], 0.01);
  EXPECT_EQ(m.actuator_historyadr[0], 0);
  EXPECT_EQ(m.actuator_historyadr[1], 2 + 2 * 8);
}

}  // namespace
}  // namespace simlab
