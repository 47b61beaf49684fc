// The pid actuator (MuJoCo 3.12) on small models: its control layout (several inputs per
// actuator, so nu, nactuator and nout differ), a pid with a zero velocity setpoint being
// the position servo to the bit, each input's part of the force, the integral's soft
// stop at imax, the slew limit, class defaults, and the loader's checks. Whole rollouts
// are compared with native MuJoCo in tests/conformance/actuators312.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/named.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A model of hinges `n` (named j0, j1, ...) on capsules, with `actuators` and `options`.
std::string Hinges(int n, const std::string& actuators, const std::string& options = "") {
  std::string bodies;
  for (int k = 0; k < n; k++) {
    bodies += "<body pos='0 " + std::to_string(0.3 * k) + " 1'><joint name='j" +
              std::to_string(k) + "' axis='0 1 0'/>" +
              "<geom type='capsule' size='.02' fromto='0 0 0 .3 0 0'/></body>";
  }
  return "<mujoco><compiler autolimits='true'/><option timestep='0.002' " + options +
         "/><worldbody>" + bodies + "</worldbody><actuator>" + actuators +
         "</actuator></mujoco>";
}

// Both servos see the same ramp target; the pid's velocity setpoint stays 0.
TEST(Pid, ZeroVelocitySetpointIsThePositionServoToTheBit) {
  Model m = LoadXmlString(Hinges(2,
                                 "<position joint='j0' kp='10' dampratio='1'/>"
                                 "<pid joint='j1' kp='10' dampratio='1'/>",
                                 "integrator='implicitfast'"));
  ASSERT_EQ(m.nactuator, 2);
  ASSERT_EQ(m.nu, 3);
  ASSERT_EQ(m.nout, 2);
  EXPECT_EQ(m.actuator_ctrlnum[1], 2);
  EXPECT_EQ(m.actuator_biasprm[kNBias + 2], m.actuator_biasprm[2]);  // dampratio alike
  Data d = MakeData(m);
  for (int k = 0; k < 1500; k++) {
    d.ctrl[0] = d.ctrl[1] = 0.8 * d.time;
    d.ctrl[2] = 0;
    Step(m, d);
    ASSERT_EQ(d.qpos[0], d.qpos[1]) << "step " << k;
    ASSERT_EQ(d.actuator_force[0], d.actuator_force[1]) << "step " << k;
  }
  EXPECT_GT(d.qpos[0], 1.0);
}

// Feedforward passes straight into the force at rest.
TEST(Pid, FeedforwardIsAddedAsItIs) {
  Model m = LoadXmlString(Hinges(1, "<pid joint='j0' kp='1' kv='1' input='pos vel ff'/>"));
  EXPECT_EQ(m.nu, 3);
  EXPECT_EQ(m.actuator_ctrlspec[0], kInputPos | kInputVel | kInputFf);
  Data d = MakeData(m);
  d.ctrl[2] = 1.25;
  Forward(m, d);
  EXPECT_EQ(d.actuator_force[0], 1.25);
}

// Input subsets: pos alone is a position servo, vel alone a velocity servo, and an
// absent setpoint counts as zero (kp still pulls toward 0, kv still damps).
TEST(Pid, InputSubsetsAgreeWithTheServos) {
  Model m = LoadXmlString(Hinges(5,
                                 "<pid joint='j0' kp='7' input='pos'/>"
                                 "<position joint='j1' kp='7'/>"
                                 "<pid joint='j2' kv='3' input='vel'/>"
                                 "<velocity joint='j3' kv='3'/>"
                                 "<pid joint='j4' kp='5' kv='2' input='pos ff'/>"));
  ASSERT_EQ(m.nu, 6);
  ASSERT_EQ(m.nout, 5);
  EXPECT_EQ(m.actuator_ctrladr[4], 4);
  Data d = MakeData(m);
  const double q[5] = {0.2, 0.2, -0.3, -0.3, 0.1}, v[5] = {0.5, 0.5, -0.4, -0.4, 0.7};
  for (int k = 0; k < 5; k++) d.qpos[k] = q[k], d.qvel[k] = v[k];
  const double ctrl[6] = {0.6, 0.6, -0.8, -0.8, 0.3, 0.9};
  for (int k = 0; k < 6; k++) d.ctrl[k] = ctrl[k];
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], d.actuator_force[1]);
  EXPECT_DOUBLE_EQ(d.actuator_force[2], d.actuator_force[3]);
  EXPECT_DOUBLE_EQ(d.actuator_force[4], 5 * (0.3 - 0.1) - 2 * 0.7 + 0.9);
}

// The integral stops growing once past imax, so it may pass it by one step's growth
// (MuJoCo: a soft stop, not a clamp). The force is too weak to reach the target.
TEST(Pid, IntegralStopsGrowingPastImax) {
  Model m = LoadXmlString(Hinges(1, "<pid joint='j0' kp='0.5' kv='0.5' ki='20' imax='0.3' input='pos' forcerange='-0.001 0.001'/>"));
  ASSERT_EQ(m.na, 1);
  Data d = MakeData(m);
  d.ctrl[0] = 1;
  double largest = 0;
  for (int k = 0; k < 3000; k++) {
    Step(m, d);
    largest = std::max(largest, std::abs(d.act[0]));
  }
  EXPECT_GT(largest, 0.3);
  EXPECT_LT(largest, 0.3 + m.opt.timestep * 2);
}

// The slew limit: the effective setpoint (the state) moves at most slewmax per second.
TEST(Pid, SlewLimitsTheSetpointsRate) {
  Model m = LoadXmlString(Hinges(1, "<pid joint='j0' kp='50' kv='5' slewmax='0.5' input='pos'/>",
                                 "gravity='0 0 0'"));
  ASSERT_EQ(m.na, 1);
  Data d = MakeData(m);
  d.ctrl[0] = 1;
  for (int k = 0; k < 1500; k++) {
    Step(m, d);
    ASSERT_LE(d.act[0], 0.5 * d.time + 1e-9);
  }
  for (int k = 0; k < 2000; k++) Step(m, d);
  EXPECT_NEAR(d.act[0], 1, 1e-9);
  EXPECT_NEAR(d.qpos[0], 1, 0.01);
}

// A class passes its gains, integral, ranges and inputs to the pid that uses it.
TEST(Pid, ClassDefaultsReachTheInstance) {
  Model m = LoadXmlString(
      "<mujoco><default><default class='arm'><pid kp='7' ki='3' imax='1.5' velrange='-2 2' "
      "input='pos vel ff'/></default></default><worldbody><body><joint name='s' type='slide'/>"
      "<geom size='.1'/></body></worldbody><actuator><pid class='arm' joint='s'/></actuator>"
      "</mujoco>");
  EXPECT_EQ(m.nu, 3);
  EXPECT_EQ(m.na, 1);
  EXPECT_EQ(m.actuator_gainprm[0], 3);
  EXPECT_EQ(m.actuator_biasprm[1], -7);
  EXPECT_EQ(m.actuator_dynprm[0], 1.5);
  EXPECT_EQ(m.actuator_dyntype[0], kDynPid);
  EXPECT_EQ(m.actuator_ctrlrange[2], -2);
  EXPECT_EQ(m.actuator_ctrlrange[3], 2);
  EXPECT_EQ(m.actuator_ctrllimited[1], 1);
  EXPECT_EQ(m.actuator_ctrllimited[2], 0);
}

// Keyframes carry nu controls; the named view slices an actuator's inputs.
TEST(Pid, KeyframesAndViewsCountControls) {
  std::string xml = Hinges(2, "<motor joint='j0'/><pid joint='j1' kp='3' input='pos vel ff'/>");
  xml.replace(xml.find("</mujoco>"), 9, "<keyframe><key ctrl='1 2 3 4'/></keyframe></mujoco>");
  Model m = LoadXmlString(xml);
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  EXPECT_EQ(d.ctrl[3], 4);
  Named pid = DataObject(m, d, kObjActuator, 1);
  EXPECT_EQ(pid["ctrl"].size(), 3u);
  EXPECT_EQ(pid["ctrl"][0], 2);
  EXPECT_EQ(pid["force"].size(), 1u);
  xml.replace(xml.find("ctrl='1 2 3 4'"), 14, "ctrl='1 2 3 4 5'");
  test_util::ExpectMessageParts(test_util::XmlLoadError(xml), {"ctrl"}, xml);
}

// The loader's checks, each with its reason.
TEST(Pid, BadParametersAreClearErrors) {
  struct Bad {
    std::string actuator, says;
  };
  const Bad cases[] = {
      {"<pid joint='j0' input='none'/>", "subset"},
      {"<pid joint='j0' input='voltage'/>", "subset"},
      {"<pid joint='j0' input='vel pos'/>", "order"},
      {"<pid joint='j0' input='pos pos'/>", "order"},
      {"<pid joint='j0' input='torque'/>", "unknown input"},
      {"<pid joint='j0' ki='1' slewmax='1'/>", "not both"},
      {"<pid joint='j0' ki='1' input='vel'/>", "pos input"},
      {"<pid joint='j0' kv='1' dampratio='1'/>", "kv and dampratio"},
      {"<pid joint='j0' slewmax='-1'/>", "slewmax"},
      {"<pid joint='j0' kp='1' delay='0.01' nsample='5'/>", "one control"},
      {"<motor joint='j0' input='pos'/>", "input"},
  };
  for (const Bad& bad : cases) {
    std::string xml = Hinges(1, bad.actuator);
    test_util::ExpectMessageParts(test_util::XmlLoadError(xml), {bad.says}, xml);
  }
}

}  // namespace
}  // namespace simlab
