// The dcmotor actuator on one hinge at a time, each feature against its formula: the
// stateless torque K/R (V - K w), the current's exact step, the thermal resistance, the
// torque-space controller (equal to a pid in its linear range), cogging beyond the
// saturation, an actuator with no inputs, ratings turned into constants, and the
// loader's checks. Whole rollouts are compared with native MuJoCo in
// tests/conformance/actuators312 (bit for bit in every integrator).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

constexpr double kK = 0.05, kR = 2;  // motorconst, resistance

// One hinge without gravity driven by `actuators`.
std::string Hinge(const std::string& actuators, const std::string& options = "") {
  return "<mujoco><option gravity='0 0 0' timestep='0.001' " + options +
         "/><worldbody><body><joint name='j' axis='0 1 0'/><geom type='capsule' size='.02' "
         "fromto='0 0 0 .3 0 0'/></body><body pos='0 1 0'><joint name='j2' axis='0 1 0'/>"
         "<geom type='capsule' size='.02' fromto='0 0 0 .3 0 0'/></body></worldbody><actuator>" +
         actuators + "</actuator></mujoco>";
}

// Forward at joint velocity w and control u (its first control).
Data At(const Model& m, double w, double u) {
  Data d = MakeData(m);
  d.qvel[0] = w;
  if (m.nu) d.ctrl[0] = u;
  Forward(m, d);
  return d;
}

TEST(Dcmotor, StatelessTorqueIsBackEmfLimited) {
  Model m = LoadXmlString(Hinge("<dcmotor joint='j' motorconst='0.05' resistance='2'/>"));
  EXPECT_EQ(m.actuator_ctrlspec[0], kInputVoltage);
  EXPECT_EQ(m.na, 0);
  Data d = At(m, 3, 12);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], kK / kR * (12 - kK * 3));
}

TEST(Dcmotor, CurrentStepsExactly) {
  Model m = LoadXmlString(Hinge("<dcmotor joint='j' motorconst='0.05' resistance='2' inductance='0.01'/>"));
  ASSERT_EQ(m.na, 1);
  double te = 0.01 / kR;
  EXPECT_DOUBLE_EQ(m.actuator_dynprm[0], te);
  Data d = MakeData(m);
  d.ctrl[0] = 12;
  Step(m, d);
  EXPECT_NEAR(d.act[0], 12 / kR * (1 - std::exp(-0.001 / te)), 1e-12);
}

TEST(Dcmotor, HeatRaisesTheResistance) {
  Model m = LoadXmlString(
      Hinge("<dcmotor joint='j' motorconst='0.05' resistance='2' thermal='10 5 0 0.004 25 25'/>"));
  ASSERT_EQ(m.na, 1);
  Data d = MakeData(m);
  d.ctrl[0] = 10;
  d.act[0] = 50;  // degrees above ambient
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], kK / (kR * (1 + 0.004 * 50)) * 10);
  // and heats at R i^2 / C (cooling through RT)
  double r = kR * 1.2, i = 10 / r;
  EXPECT_DOUBLE_EQ(d.act_dot[0], (r * i * i - 50 / 10.0) / 5);
}

TEST(Dcmotor, ControllerGivesTorqueAndDamping) {
  Model m = LoadXmlString(Hinge(
      "<dcmotor joint='j' motorconst='0.05' resistance='2' input='pos vel' controller='2 0 0.5'/>"));
  EXPECT_EQ(m.nu, 2);
  EXPECT_DOUBLE_EQ(At(m, 0, 5).actuator_force[0], 10);
  EXPECT_DOUBLE_EQ(At(m, 2, 5).actuator_force[0], 9);
}

// In its linear range (no saturation, no inductance) the controller is a pid.
TEST(Dcmotor, ControllerEqualsPid) {
  Model m = LoadXmlString(Hinge(
      "<pid joint='j' kp='10' kv='5'/>"
      "<dcmotor joint='j2' motorconst='0.05' resistance='2' input='pos vel' controller='10 0 5'/>",
      "integrator='implicitfast'"));
  ASSERT_EQ(m.nu, 4);
  Data d = MakeData(m);
  for (int k = 0; k < 1000; k++) {
    d.ctrl[0] = d.ctrl[2] = std::sin(3 * d.time);
    d.ctrl[1] = d.ctrl[3] = 3 * std::cos(3 * d.time);
    Step(m, d);
    ASSERT_NEAR(d.qpos[0], d.qpos[1], 1e-12) << k;
    ASSERT_NEAR(d.actuator_force[0], d.actuator_force[1], 1e-11) << k;
  }
}

// The saturation clamps the electrical torque; cogging comes after it.
TEST(Dcmotor, CoggingBypassesTheSaturation) {
  Model m = LoadXmlString(Hinge(
      "<dcmotor joint='j' motorconst='0.05' resistance='2' saturation='0.001' cogging='0.1 6 0'/>"));
  EXPECT_EQ(m.actuator_forcerange[1], 0.001);
  Data d = MakeData(m);
  d.qpos[0] = 1;
  d.ctrl[0] = 100;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.actuator_force[0], 0.001 + 0.1 * std::sin(6.0));
}

// input="none": no controls at all, a shorted brake with friction.
TEST(Dcmotor, NoInputsIsABrake) {
  Model m = LoadXmlString(Hinge(
      "<dcmotor joint='j' motorconst='0.05' resistance='2' input='none' lugre='100 1 0.5 0.7 10'/>"));
  EXPECT_EQ(m.nu, 0);
  EXPECT_EQ(m.nactuator, 1);
  EXPECT_EQ(m.actuator_ctrlnum[0], 0);
  Data d = MakeData(m);
  d.qvel[0] = 2;
  for (int k = 0; k < 100; k++) Step(m, d);
  EXPECT_GT(d.act[0], 0);
  EXPECT_LT(d.qvel[0], 2);
}

// Nominal ratings: Ke = volts / no-load speed without damping, R from the stall torque.
TEST(Dcmotor, RatingsGiveTheConstants) {
  Model m = LoadXmlString(Hinge("<dcmotor joint='j' nominal='12 0.6 100'/>"));
  EXPECT_DOUBLE_EQ(m.actuator_gainprm[1], 0.12);
  EXPECT_DOUBLE_EQ(m.actuator_gainprm[0], 0.12 * 12 / 0.6);
  Model geometric = LoadXmlString(Hinge("<dcmotor joint='j' motorconst='0.03 0.05' resistance='1'/>"));
  EXPECT_DOUBLE_EQ(geometric.actuator_gainprm[1], std::sqrt(0.03 * 0.05));
}

TEST(Dcmotor, BadParametersAreClearErrors) {
  struct Bad {
    std::string actuator, says;
  };
  const Bad cases[] = {
      {"<dcmotor joint='j' resistance='2'/>", "motor constant"},
      {"<dcmotor joint='j' motorconst='0.05'/>", "resistance"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' input='none' controller='0 0 0 1'/>", "slew"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' input='vel ff' controller='1 1'/>", "pos input"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' controller='1'/>", "controller gains"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' forcerange='-1 1'/>", "forcerange"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' thermal='0 0 5'/>", "thermal"},
      {"<dcmotor joint='j' motorconst='0.05' resistance='2' input='none' nsample='4'/>", "history"},
  };
  for (const Bad& bad : cases) {
    std::string xml = Hinge(bad.actuator);
    test_util::ExpectMessageParts(test_util::XmlLoadError(xml), {bad.says}, xml);
  }
}

}  // namespace
}  // namespace simlab
