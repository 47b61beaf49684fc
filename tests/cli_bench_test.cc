// `simlab bench`: testspeed's control noise (Halton sequence, ranges), the start
// keyframe, the report's counts (checked against the same rollout run here) and its
// profiler, and the profiler's timers in Data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "bench.h"
#include "cli.h"
#include "simlab/simlab.h"

namespace simlab::apps {
namespace {

std::string Source(const std::string& relative) {
  return std::string(SIMLAB_SOURCE_DIR) + "/" + relative;
}

// The number after `label :` in a report.
double Value(const std::string& report, const std::string& label) {
  std::smatch match;
  std::regex pattern(label + R"( +: +(-?[0-9.]+))");
  EXPECT_TRUE(std::regex_search(report, match, pattern)) << label << " in\n" << report;
  return match.empty() ? -1 : std::stod(match[1]);
}

TEST(Bench, HaltonSequence) {
  EXPECT_EQ(Halton(0, 2), 0.0);
  EXPECT_EQ(Halton(1, 2), 0.5);
  EXPECT_EQ(Halton(2, 2), 0.25);
  EXPECT_EQ(Halton(3, 2), 0.75);
  EXPECT_DOUBLE_EQ(Halton(1, 3), 1.0 / 3);
  EXPECT_DOUBLE_EQ(Halton(5, 3), 2.0 / 3 + 1.0 / 9);
}

// The noise process of MuJoCo 3.12's testspeed: step 0 at the centre (the middle of the
// range; 0 when unlimited; the keyframe's control when one is given), then each step
// relaxes towards the centre at the rate and adds the scaled Halton noise, clamped to
// the range.
TEST(Bench, ControlNoiseIsTestspeedsProcess) {
  Model m = LoadXmlString(R"(<mujoco><option timestep="0.01"/><worldbody><body>
    <joint name="j"/><geom size=".1"/></body></worldbody><actuator>
    <motor joint="j" ctrlrange="1 3"/><motor joint="j"/></actuator>
    <keyframe><key ctrl="2.5 -4"/></keyframe></mujoco>)");
  NoiseOptions noise{0.5, 0.05};
  const double r = std::exp(-0.01 / 0.05), scale = 0.5 * std::sqrt(1 - r * r);
  std::vector<double> ctrl = ControlNoise(m, 4, noise, -1);
  ASSERT_EQ(ctrl.size(), 8u);
  EXPECT_DOUBLE_EQ(ctrl[0], 2 + scale * (2 * Halton(0, 2) - 1));
  EXPECT_DOUBLE_EQ(ctrl[1], 0 + scale * (2 * Halton(0, 3) - 1));
  for (int s = 1; s < 4; s++) {
    double limited = r * ctrl[2 * (s - 1)] + (1 - r) * 2 + scale * (2 * Halton(s, 2) - 1);
    EXPECT_DOUBLE_EQ(ctrl[2 * s], std::clamp(limited, 1.0, 3.0));
    EXPECT_DOUBLE_EQ(ctrl[2 * s + 1], r * ctrl[2 * s - 1] + scale * (2 * Halton(s, 3) - 1));
  }
  // From the keyframe: its controls are the centres (the range still scales the noise).
  std::vector<double> keyed = ControlNoise(m, 2, noise, 0);
  EXPECT_DOUBLE_EQ(keyed[0], 2.5 + scale * (2 * Halton(0, 2) - 1));
  EXPECT_DOUBLE_EQ(keyed[1], -4 + scale * (2 * Halton(0, 3) - 1));
  EXPECT_DOUBLE_EQ(keyed[3], r * keyed[1] + (1 - r) * -4 + scale * (2 * Halton(1, 3) - 1));
}

// The report's solver iterations, contacts and rows per step are the rollout's, from
// keyframe "test", and equal MuJoCo testspeed's.
TEST(Bench, ReportsTheRolloutsCounts) {
  const std::string model = Source("tests/conformance/contact/models/humanoid.xml");
  BenchOptions options;
  options.model = model;
  options.steps = 300;
  std::ostringstream out;
  ASSERT_EQ(RunBench(options, out), kExitOk);
  const std::string report = out.str();

  Model m = LoadXml(model);
  Data d = MakeData(m);
  int key = m.NameToId(kObjKey, "test");
  if (key >= 0) ResetDataKeyframe(m, d, key);
  std::vector<double> ctrl = ControlNoise(m, 300, NoiseOptions{}, key);
  double contacts = 0, rows = 0, iterations = 0;
  for (int s = 0; s < 300; s++) {
    std::copy_n(ctrl.begin() + s * m.nu, m.nu, d.ctrl.begin());
    Step(m, d);
    contacts += d.ncon;
    rows += d.nefc;
    iterations += static_cast<double>(d.solver_niter) / std::max(1, d.nisland);
  }
  EXPECT_NEAR(Value(report, "Newton iters / step"), iterations / 300, 0.005);
  // MuJoCo 3.12.1's own testspeed on this model and workload (`testspeed humanoid.xml
  // --nstep=300`) prints 2.10 iterations, 7.33 contacts and 26.42 constraints per step.
  EXPECT_NEAR(Value(report, "Newton iters / step"), 2.10, 0.005);
  EXPECT_NEAR(Value(report, "Contacts per step"), 7.33, 0.005);
  EXPECT_NEAR(Value(report, "Constraints per step"), 26.42, 0.005);
  EXPECT_NEAR(Value(report, "Contacts per step"), contacts / 300, 0.005);
  EXPECT_NEAR(Value(report, "Constraints per step"), rows / 300, 0.005);
  EXPECT_EQ(Value(report, "Degrees of freedom"), m.nv);
  EXPECT_GT(Value(report, "Steps per second"), 0);
  // The profile: the step's stages, the position stage's parts.
  for (const char* stage : {"step", "forward", "position", "velocity", "actuation",
                            "constraint", "advance", "other", "position total",
                            "kinematics", "inertia", "collision", "broadphase",
                            "narrowphase", "make", "project"}) {
    EXPECT_GE(Value(report, stage), 0) << stage;
  }
}

TEST(Bench, ThreadsReportTheirTotal) {
  std::ostringstream out, err;
  const std::string model = Source("models/actuator_bench.xml");
  const char* argv[] = {"simlab", "bench", model.c_str(), "--steps", "200", "--threads", "2"};
  ASSERT_EQ(RunSimlab(7, argv, out, err), kExitOk) << err.str();
  EXPECT_GT(Value(out.str(), "Total steps per second"), 0);
}

// --no-profiler: the same rollout with no stage timers, so no profile in the report.
TEST(Bench, NoProfilerLeavesTheProfileOut) {
  std::ostringstream out, err;
  const std::string model = Source("models/actuator_bench.xml");
  const char* argv[] = {"simlab", "bench", model.c_str(), "--steps", "200", "--no-profiler"};
  ASSERT_EQ(RunSimlab(6, argv, out, err), kExitOk) << err.str();
  EXPECT_GT(Value(out.str(), "Steps per second"), 0);
  EXPECT_EQ(out.str().find("Internal profiler"), std::string::npos) << out.str();
}

TEST(Bench, BadKeyframeIsOneLine) {
  std::ostringstream out, err;
  const std::string model = Source("models/actuator_bench.xml");
  const char* argv[] = {"simlab", "bench", model.c_str(), "--key", "99"};
  EXPECT_EQ(RunSimlab(5, argv, out, err), kExitError);
  EXPECT_NE(err.str().find("bench: keyframe 99 does not exist"), std::string::npos) << err.str();
}

// Without a clock the timers stay at zero; with one, every step counts once.
TEST(Profiler, TimersCountWithAClockOnly) {
  Model m = LoadXml(Source("models/gantry_gripper.xml"));
  Data d = MakeData(m);
  Step(m, d);
  EXPECT_EQ(d.timer[kTimerStep].number, 0);
  d.timer_clock = [] { return 1.0; };
  for (int i = 0; i < 5; i++) Step(m, d);
  EXPECT_EQ(d.timer[kTimerStep].number, 5);
  EXPECT_EQ(d.timer[kTimerPosition].number, 5);
  EXPECT_EQ(d.timer[kTimerAdvance].number, 5);
  EXPECT_EQ(d.timer[kTimerStep].duration, 0);
  ResetData(m, d);
  EXPECT_EQ(d.timer[kTimerStep].number, 0);
}

// MuJoCo's 22 humanoids (594 dofs, sparse rows) under testspeed's workload: the row
// count rises and falls by a few rows at a time for hundreds of steps, and every efc
// array keeps room for the rows in use. (The rows' arrays once grew out of step with each
// other here, and step 268 wrote past the end of efc_KBIP.)
TEST(Bench, RowArraysKeepRoomOnTwentyTwoHumanoids) {
  Model m = LoadXml(Source("../shared/corpus/mujoco/model/humanoid/22_humanoids.xml"));
  Data d = MakeData(m);
  std::vector<double> ctrl = ControlNoise(m, 400, NoiseOptions{}, -1);
  for (int s = 0; s < 400; s++) {
    std::copy_n(ctrl.begin() + static_cast<size_t>(s) * m.nu, m.nu, d.ctrl.begin());
    Step(m, d);
#define SIMLAB_X(type, name, cols) \
    ASSERT_GE(d.name.size(), static_cast<size_t>(d.nefc) * (cols)) << #name << ", step " << s;
    SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
    ASSERT_GE(d.efc_J.size(), static_cast<size_t>(d.nJ));
  }
  EXPECT_EQ(d.warning[kWarnEngineError].number, 0);
}

}  // namespace
}  // namespace simlab::apps
