// Adhesion actuators and their body transmission (engine/transmission.cc). Conformance
// with MuJoCo is in the adhesion cases of conformance_test.cc (tests/conformance/adhesion);
// here, properties that hold by construction, on the same models:
//   - a box resting flat on a plane is pulled straight into it: its moment is minus the
//     contact normal (no sideways force, no torque), so qfrc_actuator = -gain * ctrl on z;
//   - pyramidal and elliptic cones give the same moment (the pyramid edges' frictional
//     parts cancel in their mean);
//   - contacts in the gap (no constraint rows) count too: the box hanging below the
//     ceiling is pulled up before it touches;
//   - without contacts the moment is zero while the force is still gain * ctrl;
//   - bad adhesion parameters are load errors with the file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

constexpr double kTol = 1e-12;

std::string Adhesion(const std::string& rel) {
  return std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/adhesion/" + rel;
}

// The moment row of actuator i.
std::vector<double> MomentRow(const Model& m, const Data& d, int i) {
  auto first = d.actuator_moment.begin() + static_cast<long>(i) * m.nv;
  return std::vector<double>(first, first + m.nv);
}

// The model in its initial state with control `ctrl`, after Forward.
Data AtRest(const Model& m, double ctrl) {
  Data d = MakeData(m);
  d.ctrl[0] = ctrl;
  Forward(m, d);
  return d;
}

TEST(Adhesion, PullsStraightIntoThePlane) {
  Model m = LoadXml(Adhesion("base/plane.xml"));
  Data d = AtRest(m, 0.5);
  ASSERT_EQ(d.ncon, 4);
  std::vector<double> moment = MomentRow(m, d, 0);
  for (int v = 0; v < 6; v++) {
    EXPECT_NEAR(moment[v], v == 2 ? -1.0 : 0.0, kTol) << "dof " << v;
  }
  EXPECT_EQ(d.actuator_length[0], 0);
  EXPECT_NEAR(d.actuator_force[0], 0.5 * m.actuator_gainprm[0], kTol);
  EXPECT_NEAR(d.qfrc_actuator[2], -0.5 * m.actuator_gainprm[0], kTol);
}

TEST(Adhesion, SameMomentForEllipticCones) {
  Model pyramidal = LoadXml(Adhesion("base/plane.xml"));
  Model elliptic = LoadXml(Adhesion("models/plane__elliptic.xml"));
  ASSERT_EQ(elliptic.opt.cone, kConeElliptic);
  Data dp = AtRest(pyramidal, 1), de = AtRest(elliptic, 1);
  ASSERT_EQ(dp.ncon, de.ncon);
  ASSERT_NE(dp.nefc, de.nefc);  // pyramids have two rows per friction direction
  std::vector<double> mp = MomentRow(pyramidal, dp, 0), me = MomentRow(elliptic, de, 0);
  for (int v = 0; v < pyramidal.nv; v++) EXPECT_NEAR(mp[v], me[v], kTol) << "dof " << v;
}

TEST(Adhesion, ContactsInTheGapPullToo) {
  Model m = LoadXml(Adhesion("base/ceiling.xml"));
  Data d = AtRest(m, 1);
  ASSERT_GT(d.ncon, 0);
  for (int c = 0; c < d.ncon; c++) EXPECT_EQ(d.contact[c].exclude, 1) << "contact " << c;
  EXPECT_EQ(d.nefc, 0);
  std::vector<double> moment = MomentRow(m, d, 0);
  EXPECT_NEAR(moment[2], 1.0, kTol);  // up, toward the ceiling
  EXPECT_GT(d.qacc[2], 0);  // gain 22 beats the weight of 1.2 kg
}

TEST(Adhesion, NoContactsNoMoment) {
  Model m = LoadXml(Adhesion("base/plane.xml"));
  Data d = MakeData(m);
  d.qpos[2] = 0.5;  // lifted well beyond the margin
  d.ctrl[0] = 0.5;
  Forward(m, d);
  ASSERT_EQ(d.ncon, 0);
  for (double x : MomentRow(m, d, 0)) EXPECT_EQ(x, 0);
  EXPECT_NEAR(d.actuator_force[0], 0.5 * m.actuator_gainprm[0], kTol);
  for (double x : d.qfrc_actuator) EXPECT_EQ(x, 0);
}

TEST(Adhesion, BadParametersNameTheLine) {
  const std::string head = "<mujoco>\n<worldbody><body name=\"b\"><freejoint/><geom size=\"1\"/>"
                           "</body></worldbody>\n<actuator>\n";
  struct BadCase {
    std::string element, expected;
  };
  const BadCase cases[] = {
      {"<adhesion body=\"b\" gain=\"-1\" ctrlrange=\"0 1\"/>", "gain cannot be negative"},
      {"<adhesion body=\"b\" ctrlrange=\"-1 1\"/>", "control range cannot be negative"},
      {"<adhesion body=\"nobody\" ctrlrange=\"0 1\"/>", "unknown body 'nobody'"},
      {"<adhesion body=\"b\"/>", "invalid ctrlrange"},
  };
  for (const BadCase& c : cases) {
    std::string xml = head + c.element + "\n</actuator>\n</mujoco>";
    test_util::ExpectMessageParts(test_util::XmlLoadError(xml), {"bad.xml:4", c.expected}, xml);
  }
}

}  // namespace
}  // namespace simlab
