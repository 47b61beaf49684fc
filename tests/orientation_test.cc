// The orientation actuator (MuJoCo 3.11) on MuJoCo's own test model and small ones: the
// layout of its 3 or 4 controls and 3 outputs among other actuators, the identity
// quaternion command after a reset, the force's independence of the command's
// representative (a rotation vector beyond pi, a scaled or negated quaternion), the norm
// clamp, the winding integrator kept within a half turn, 3-number sensors, and the
// loader's checks. Whole rollouts are compared with native MuJoCo in
// tests/conformance/actuators312.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

const std::string kOrientation =
    std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/actuators312/mujoco/orientation.xml";

// Balls named b0, b1, ... without gravity, driven by `actuators`.
std::string Balls(int n, const std::string& actuators) {
  std::string bodies;
  for (int k = 0; k < n; k++) {
    bodies += "<body pos='" + std::to_string(0.5 * k) + " 0 0'><joint name='b" + std::to_string(k) +
              "' type='ball'/><geom type='box' size='.07 .09 .05'/></body>";
  }
  return "<mujoco><option gravity='0 0 0'/><worldbody>" + bodies +
         "</worldbody><actuator>" + actuators + "</actuator></mujoco>";
}

// The quaternion of rotation vector v.
void QuatOf(const double v[3], double* q) {
  double angle = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  q[0] = std::cos(angle / 2);
  for (int k = 0; k < 3; k++) q[1 + k] = v[k] / angle * std::sin(angle / 2);
}

TEST(Orientation, MujocosModelHasItsLayout) {
  Model m = LoadXml(kOrientation);
  EXPECT_EQ(m.nactuator, 5);
  EXPECT_EQ(m.nu, 10);
  EXPECT_EQ(m.nout, 9);
  EXPECT_EQ(m.na, 0);
  int expmap = m.NameToId(kObjActuator, "expmap"), quat = m.NameToId(kObjActuator, "quat");
  EXPECT_EQ(m.actuator_ctrladr[expmap], 3);
  EXPECT_EQ(m.actuator_ctrlnum[expmap], 3);
  EXPECT_EQ(m.actuator_outadr[expmap], 3);
  EXPECT_EQ(m.actuator_outnum[expmap], 3);
  EXPECT_EQ(m.actuator_ctrladr[quat], 6);
  EXPECT_EQ(m.actuator_ctrlnum[quat], 4);
  EXPECT_EQ(m.actuator_ctrlspec[quat], kChartQuat);
  EXPECT_EQ(m.actuator_trntype[quat], kTrnSo3);
  // The quaternion's controls are limited to [-1, 1] by its class; the gear fills every row.
  EXPECT_EQ(m.actuator_ctrllimited[6], 1);
  EXPECT_EQ(m.actuator_ctrlrange[2 * 9 + 1], 1);
  EXPECT_EQ(m.actuator_gear[6 * 8], 1);
  // dampratio 1 from the first row's inertia: kv = 2 sqrt(kp m).
  EXPECT_NEAR(-m.actuator_biasprm[kNBias * expmap + 2], 0.1887220177933672, 1e-12);
}

TEST(Orientation, QuaternionCommandStartsAtTheIdentity) {
  Model m = LoadXml(kOrientation);
  Data d = MakeData(m);
  for (int c = 0; c < m.nu; c++) EXPECT_EQ(d.ctrl[c], c == 6 ? 1 : 0) << c;
  std::fill(d.ctrl.begin(), d.ctrl.end(), 0.5);
  ResetData(m, d);
  for (int c = 0; c < m.nu; c++) EXPECT_EQ(d.ctrl[c], c == 6 ? 1 : 0) << c;
}

// Held at the commanded orientation, the force is zero whichever representative says it.
TEST(Orientation, ForceIgnoresTheCommandsRepresentative) {
  Model m = LoadXmlString(Balls(2, "<orientation joint='b0' kp='1' kv='1'/>"
                                   "<orientation joint='b1' kp='1' kv='1' input='quat'/>"));
  Data d = MakeData(m);
  const double v[3] = {4, 4, 0};  // beyond a half turn
  double q[4];
  QuatOf(v, q);
  for (int k = 0; k < 4; k++) d.qpos[k] = d.qpos[4 + k] = q[k];
  for (double scale : {1.0, 2.0, -1.0}) {
    for (int k = 0; k < 3; k++) d.ctrl[k] = v[k];
    for (int k = 0; k < 4; k++) d.ctrl[3 + k] = scale * q[k];
    Forward(m, d);
    for (int o = 0; o < 6; o++) EXPECT_NEAR(d.actuator_force[o], 0, 1e-10) << scale << " " << o;
  }
  // The length is the canonical rotation vector, within a half turn.
  double norm = std::sqrt(32.0);
  EXPECT_NEAR(d.actuator_length[0], 4 * (1 - 2 * std::numbers::pi / norm), 1e-10);
}

TEST(Orientation, ForcerangeClampsTheNorm) {
  Model m = LoadXmlString(Balls(2, "<orientation joint='b0' kp='1'/>"
                                   "<orientation joint='b1' kp='1' forcerange='0 .5'/>"));
  Data d = MakeData(m);
  for (int k = 0; k < 3; k++) d.ctrl[k] = d.ctrl[3 + k] = k == 0 ? 1 : k == 1 ? 2 : 0;
  Forward(m, d);
  const double* free = &d.actuator_force[0];
  const double* clamped = &d.actuator_force[3];
  double free_norm = std::sqrt(free[0] * free[0] + free[1] * free[1] + free[2] * free[2]);
  double norm = std::sqrt(clamped[0] * clamped[0] + clamped[1] * clamped[1] + clamped[2] * clamped[2]);
  EXPECT_NEAR(norm, 0.5, 1e-12);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(clamped[k], free[k] * 0.5 / free_norm, 1e-12);
}

// An integrator of the rotation vector turning at 1 rad/s: the setpoint stays within a
// half turn (the same orientation), and the joint follows.
TEST(Orientation, IntegratorWindsWithinAHalfTurn) {
  Model m = LoadXmlString(Balls(1, "<general joint='b0' dyntype='integrator' gaintype='so3' "
                                   "biastype='so3' gainprm='1' biasprm='0 -1 -1'/>"));
  ASSERT_EQ(m.nu, 3);
  ASSERT_EQ(m.nout, 3);
  ASSERT_EQ(m.na, 3);
  Data d = MakeData(m);
  d.ctrl[2] = 1;
  while (d.time < 8 * std::numbers::pi) {
    Step(m, d);
    double angle = std::sqrt(d.act[0] * d.act[0] + d.act[1] * d.act[1] + d.act[2] * d.act[2]);
    ASSERT_LT(angle, std::numbers::pi + 0.1) << d.time;
  }
  EXPECT_NEAR(d.actuator_velocity[2], 1, 0.02);
}

TEST(Orientation, SensorsReadThreeNumbers) {
  std::string xml = Balls(1, "<orientation name='o' joint='b0' kp='2'/><motor joint='b0' gear='0 0 1'/>");
  xml.replace(xml.find("</mujoco>"), 9,
              "<sensor><actuatorpos actuator='o'/><actuatorfrc actuator='o'/></sensor></mujoco>");
  Model m = LoadXmlString(xml);
  EXPECT_EQ(m.sensor_dim[0], 3);
  EXPECT_EQ(m.sensor_adr[1], 3);
  EXPECT_EQ(m.actuator_outadr[1], 3);  // the motor's one output follows the three
  Data d = MakeData(m);
  d.ctrl[1] = 0.3;
  Forward(m, d);
  for (int k = 0; k < 3; k++) EXPECT_EQ(d.sensordata[3 + k], d.actuator_force[k]);
}

TEST(Orientation, BadTargetsAndParametersAreClearErrors) {
  const std::string hinge =
      "<mujoco><worldbody><site name='s'/><body><joint name='h'/><geom size='.1'/>"
      "<site name='t'/></body></worldbody><actuator>%</actuator></mujoco>";
  struct Bad {
    std::string xml, says;
  };
  auto with = [](std::string xml, const std::string& actuator) {
    return xml.replace(xml.find('%'), 1, actuator);
  };
  const Bad cases[] = {
      {with(hinge, "<orientation joint='h'/>"), "ball"},
      {with(hinge, "<orientation site='t'/>"), "refsite"},
      {Balls(1, "<general joint='b0' gaintype='so3' biastype='affine' biasprm='0 -1'/>"), "both"},
      {Balls(1, "<orientation joint='b0' forcerange='-4 4'/>"), "lower bound must be 0"},
      {Balls(1, "<general joint='b0' dyntype='integrator' gaintype='so3' biastype='so3' "
                "biasprm='0 -1' input='quat'/>"), "dyntype"},
      {Balls(1, "<orientation joint='b0' input='ff'/>"), "expmap or quat"},
      {Balls(1, "<orientation joint='b0' kp='1' delay='0.01' nsample='4'/>"), "one control"},
  };
  for (const Bad& bad : cases) {
    test_util::ExpectMessageParts(test_util::XmlLoadError(bad.xml), {bad.says}, bad.xml);
  }
}

}  // namespace
}  // namespace simlab
