// The statements of lesson 2.3 ("The actuator model"), each checked on our engine:
// forces live in actuator space, clamping never rewrites ctrl, the Euler filter runs
// ahead of the exponential that filterexact follows, a hand-written `general` equals
// the `position` shortcut, and the knowledge check's answers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "simlab/simlab.h"

namespace simlab {
namespace {

Model Bench() { return LoadXml(std::string(SIMLAB_SOURCE_DIR) + "/models/actuator_bench.xml"); }

// One hinge about z (no gravity torque) carrying the given actuator XML.
Model OneHinge(const std::string& actuator, const std::string& option = "") {
  return LoadXmlString(
      "<mujoco><option timestep=\"0.002\"" + option + "/><worldbody><body>"
      "<joint name=\"j\" axis=\"0 0 1\"/>"
      "<geom type=\"capsule\" size=\"0.02\" fromto=\"0 0 0 0.2 0 0\"/>"
      "</body></worldbody><actuator>" + actuator + "</actuator></mujoco>");
}

// ---------------------------------------------------------------- force and gear

// actuator_force is p in actuator space; the joint receives gear * p.
TEST(LessonActuators, ForceIsInActuatorSpaceAndJointGetsGearTimesIt) {
  Model m = Bench();
  Data d = MakeData(m);
  const double ctrl[] = {0.4, 0.5, 1.0, 0.8};
  for (int i = 0; i < m.nu; i++) {
    d.qpos[i] = 0.3;
    d.qvel[i] = -0.5;
    d.ctrl[i] = ctrl[i];
  }
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 0.4);
  EXPECT_DOUBLE_EQ(d.qfrc_actuator[0], 0.8);
  // Joint i is dof i and carries actuator i only.
  for (int i = 0; i < m.nu; i++) {
    EXPECT_DOUBLE_EQ(d.qfrc_actuator[i], m.actuator_gear[6 * i] * d.actuator_force[i]) << i;
  }
}

// ---------------------------------------------------------------- clamping

// ctrl is clamped inside the computation and still reads what was written.
TEST(LessonActuators, ClampingLeavesCtrlAsWritten) {
  Model m = Bench();
  Data d = MakeData(m);
  d.ctrl[0] = 5.0;
  d.ctrl[1] = 2.0;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 1.0);  // ctrlrange [-1, 1]
  EXPECT_DOUBLE_EQ(d.actuator_force[1], 3.0);  // kp * 2 = 20, forcerange [-3, 3]
  EXPECT_EQ(d.ctrl[0], 5.0);
  // Knowledge check: ctrl 3 with ctrlrange [-1, 1] still holds 3 after a step.
  d.ctrl[0] = 3.0;
  Step(m, d);
  EXPECT_EQ(d.ctrl[0], 3.0);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 1.0);
}

// ---------------------------------------------------------------- activation

// Euler: act_n = 1 - (1 - h/tau)^n, which exceeds the exact 1 - exp(-t/tau).
TEST(LessonActuators, EulerFilterRunsAheadOfTheExponential) {
  Model m = Bench();
  Data d = MakeData(m);
  const double h = m.opt.timestep, tau = m.actuator_dynprm[kNDyn * 3];
  d.ctrl[3] = 1.0;
  for (int n = 1; n <= 250; n++) {
    Step(m, d);
    double exact = 1 - std::exp(-d.time / tau);
    EXPECT_NEAR(d.act[0], 1 - std::pow(1 - h / tau, n), 1e-12) << n;
    EXPECT_GT(d.act[0], exact) << n;
  }
  // The lesson's 50 ms figure: 0.3965 against 0.3935.
  Data e = MakeData(m);
  e.ctrl[3] = 1.0;
  for (int n = 0; n < 25; n++) Step(m, e);
  EXPECT_NEAR(e.act[0], 0.3965, 5e-5);
}

// filterexact integrates the filter exactly: act(t) = 1 - exp(-t/tau).
TEST(LessonActuators, FilterExactMatchesTheExponential) {
  Model m = OneHinge(
      "<general joint=\"j\" dyntype=\"filterexact\" dynprm=\"0.1\" gainprm=\"5\"/>");
  Data d = MakeData(m);
  d.ctrl[0] = 1.0;
  for (int n = 1; n <= 500; n++) {
    Step(m, d);
    EXPECT_NEAR(d.act[0], 1 - std::exp(-d.time / 0.1), 1e-12) << n;
  }
}

// ---------------------------------------------------------------- the exercise

// A pendulum under gravity driven by a position servo, or by the same servo written
// out as a general actuator (gain kp, bias 0 -kp -kv, affine).
Model ServoPendulum(const std::string& actuator) {
  return LoadXmlString(
      "<mujoco><worldbody><body pos=\"0 0 1\">"
      "<joint name=\"j\" axis=\"0 1 0\" damping=\"0.05\"/>"
      "<geom type=\"capsule\" size=\"0.03\" fromto=\"0 0 0 0.3 0 0\"/>"
      "</body></worldbody><actuator>" + actuator + "</actuator></mujoco>");
}

// Same control sequence, 1000 steps: the trajectories agree bit for bit.
TEST(LessonActuators, HandWrittenGeneralEqualsPositionShortcut) {
  Model shortcut = ServoPendulum(
      "<position joint=\"j\" kp=\"20\" kv=\"2\" ctrlrange=\"-1 1\" forcerange=\"-4 4\"/>");
  Model general = ServoPendulum(
      "<general joint=\"j\" gainprm=\"20\" biastype=\"affine\" biasprm=\"0 -20 -2\" "
      "ctrlrange=\"-1 1\" forcerange=\"-4 4\"/>");
  // The compiled parameters are the same.
  for (int k = 0; k < kNGain; k++) EXPECT_EQ(shortcut.actuator_gainprm[k], general.actuator_gainprm[k]);
  for (int k = 0; k < kNBias; k++) EXPECT_EQ(shortcut.actuator_biasprm[k], general.actuator_biasprm[k]);
  EXPECT_EQ(shortcut.actuator_biastype[0], general.actuator_biastype[0]);

  // A varying control that leaves ctrlrange now and then.
  Data a = MakeData(shortcut), b = MakeData(general);
  for (int n = 0; n < 1000; n++) {
    a.ctrl[0] = b.ctrl[0] = 1.3 * std::sin(0.013 * n) + 0.2 * std::cos(0.07 * n);
    Step(shortcut, a);
    Step(general, b);
    ASSERT_EQ(a.qpos[0], b.qpos[0]) << n;
    ASSERT_EQ(a.qvel[0], b.qvel[0]) << n;
    ASSERT_EQ(a.actuator_force[0], b.actuator_force[0]) << n;
  }
  EXPECT_GT(std::abs(a.qpos[0]), 0.01);  // the servo moved the pendulum
}

// ---------------------------------------------------------------- knowledge check

// position kp 50 kv 2 at q 0.2, qdot 1, ctrl 0.5: 50 * 0.3 - 2 * 1 = 13.
TEST(LessonActuators, PositionServoForce) {
  Model m = OneHinge("<position joint=\"j\" kp=\"50\" kv=\"2\"/>");
  Data d = MakeData(m);
  d.qpos[0] = 0.2;
  d.qvel[0] = 1.0;
  d.ctrl[0] = 0.5;
  Forward(m, d);
  EXPECT_NEAR(d.actuator_force[0], 13.0, 1e-12);
}

// motor gear 10, ctrl 1.5: actuator_force 1.5, joint torque 15.
TEST(LessonActuators, MotorGearTorque) {
  Model m = OneHinge("<motor joint=\"j\" gear=\"10\"/>");
  Data d = MakeData(m);
  d.ctrl[0] = 1.5;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 1.5);
  EXPECT_DOUBLE_EQ(d.qfrc_actuator[0], 15.0);
}

// general with biasprm but no biastype: the numbers are compiled, the bias is none.
TEST(LessonActuators, GeneralBiasprmWithoutBiastypeIsIgnored) {
  Model m = OneHinge("<general joint=\"j\" gainprm=\"4\" biasprm=\"0 0 -4\"/>");
  Data d = MakeData(m);
  EXPECT_EQ(m.actuator_biastype[0], kBiasNone);
  EXPECT_EQ(m.actuator_biasprm[2], -4.0);
  d.qvel[0] = 1.0;
  d.ctrl[0] = 0.5;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 2.0);  // 4 * 0.5, no -4 * qdot
}

// The velocity servo written as general, with its biastype: p = 4u - 4 l'.
TEST(LessonActuators, GeneralEquivalentOfVelocityServo) {
  Model m = OneHinge(
      "<velocity joint=\"j\" kv=\"4\"/>"
      "<general joint=\"j\" gainprm=\"4\" biastype=\"affine\" biasprm=\"0 0 -4\"/>");
  Data d = MakeData(m);
  d.qvel[0] = 1.0;
  d.ctrl[0] = d.ctrl[1] = 0.5;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 4 * 0.5 - 4 * 1.0);
  EXPECT_EQ(d.actuator_force[0], d.actuator_force[1]);
}

}  // namespace
}  // namespace simlab
