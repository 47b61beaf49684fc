// Fluid forces (engine/fluid.cc). Their conformance with MuJoCo is in the fluid cases of
// conformance_test.cc (tests/conformance/fluid); here, properties that hold by
// construction:
//   - the analytic velocity derivative (used by implicit and implicitfast) equals
//     central finite differences of qfrc_fluid, for both models;
//   - only the velocity relative to the medium counts: moving at u in still fluid
//     pushes as hard as resting in a wind of -u;
//   - the fluid is a passive force: off only when springs and dampers both are;
//   - fluidshape takes "none" or "ellipsoid", with the file and line on error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

std::string Base(const std::string& name) {
  return std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/fluid/base/" + name;
}

// qvel from the state file the oracle was started from.
void ApplyState(const std::string& name, Data& d) {
  std::ifstream in(Base(name + ".state.json"));
  nlohmann::json state = nlohmann::json::parse(in);
  for (size_t k = 0; k < state["qvel"].size(); k++) d.qvel[k] = state["qvel"][k].get<double>();
}

std::vector<double> FluidAt(const Model& m, Data& d) {
  Forward(m, d);
  return d.qfrc_fluid;
}

// The ellipsoid model on larger geoms than the conformance model's: MuJoCo floors the
// denominator sqrt(num^3 den) of the projected area's slope at 1e-15, which (as MuJoCo
// does, and we with it) leaves that slope short for centimetre-sized plates.
const char* const kLargeEllipsoids = R"(
<mujoco><option density="1000" viscosity="0.01" wind="0 .5 -.3"/>
  <default><geom fluidshape="ellipsoid" density="100"/></default>
  <worldbody>
    <body euler="10 20 30"><freejoint/><geom type="ellipsoid" size=".4 .2 .1"/></body>
    <body pos="2 0 0"><joint axis="0 1 0"/><geom type="cylinder" fromto="0 0 0 1 0 0" size=".1"/>
      <body pos="1 0 0"><joint axis="1 0 0"/><geom type="box" size=".5 .3 .1" pos=".5 0 0"/>
        <geom type="sphere" size=".1" pos="1 0 0" fluidshape="none"/></body></body>
  </worldbody></mujoco>)";

class FluidDerivativeTest : public ::testing::TestWithParam<const char*> {};

TEST_P(FluidDerivativeTest, MatchesFiniteDifferences) {
  std::string name = GetParam();
  bool large = name == "large_ellipsoids";
  Model m = large ? LoadXmlString(kLargeEllipsoids) : LoadXml(Base(name + ".xml"));
  Data d = MakeData(m);
  if (large) {
    const double qvel[8] = {0.5, -0.5, 1.0, 3.0, 2.0, -4.0, 1.0, -2.0};
    std::copy(qvel, qvel + 8, d.qvel.begin());
  } else {
    ApplyState(name, d);
  }
  Forward(m, d);
  std::fill(d.qDeriv.begin(), d.qDeriv.end(), 0.0);
  FluidDerivative(m, d);
  // qDeriv in the dof-dof pattern D, spread to a dense nv x nv matrix.
  std::vector<double> analytic(static_cast<size_t>(m.nv) * m.nv, 0.0);
  for (int i = 0; i < m.nv; i++) {
    for (int adr = m.D_rowadr[i]; adr < m.D_rowadr[i] + m.D_rownnz[i]; adr++) {
      analytic[i * m.nv + m.D_colind[adr]] = d.qDeriv[adr];
    }
  }
  double scale = 0;
  for (double x : analytic) scale = std::max(scale, std::abs(x));
  ASSERT_GT(scale, 0) << name << ": no fluid derivative";

  // Column j: (qfrc_fluid(qvel + h e_j) - qfrc_fluid(qvel - h e_j)) / 2h.
  const double h = 1e-6;
  int nv = m.nv;
  for (int j = 0; j < nv; j++) {
    double v0 = d.qvel[j];
    d.qvel[j] = v0 + h;
    std::vector<double> plus = FluidAt(m, d);
    d.qvel[j] = v0 - h;
    std::vector<double> minus = FluidAt(m, d);
    d.qvel[j] = v0;
    for (int i = 0; i < nv; i++) {
      double fd = (plus[i] - minus[i]) / (2 * h);
      EXPECT_NEAR(analytic[i * nv + j], fd, 1e-6 * scale) << name << " d qfrc_fluid[" << i
                                                          << "] / d qvel[" << j << "]";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models, FluidDerivativeTest,
                         ::testing::Values("box_wind", "viscosity_only", "density_only",
                                           "ellipsoid_custom", "large_ellipsoids"));

// A free body with a box (inertia-box model) and one with an ellipsoid geom.
std::string FreeBodies(const std::string& wind) {
  return "<mujoco><option density=\"1000\" viscosity=\"0.01\" wind=\"" + wind + "\"/>"
         "<worldbody>"
         "<body euler=\"10 20 30\"><freejoint/><geom type=\"box\" size=\".1 .05 .02\"/></body>"
         "<body pos=\"1 0 0\" euler=\"30 0 10\"><freejoint/>"
         "<geom type=\"ellipsoid\" size=\".1 .05 .02\" fluidshape=\"ellipsoid\"/></body>"
         "</worldbody></mujoco>";
}

TEST(Fluid, OnlyTheRelativeVelocityCounts) {
  const double u[3] = {0.7, -1.2, 0.4};
  Model still = LoadXmlString(FreeBodies("0 0 0"));
  Data moving = MakeData(still);
  for (int body = 0; body < 2; body++) {
    for (int k = 0; k < 3; k++) moving.qvel[6 * body + k] = u[k];
  }
  Forward(still, moving);

  Model windy = LoadXmlString(FreeBodies("-0.7 1.2 -0.4"));
  Data resting = MakeData(windy);
  Forward(windy, resting);
  for (int v = 0; v < still.nv; v++) {
    // The box feels no torque from translation; the ellipsoid does (Kutta lift).
    if (v < 3 || v >= 6) EXPECT_NE(moving.qfrc_fluid[v], 0) << v;
    EXPECT_NEAR(moving.qfrc_fluid[v], resting.qfrc_fluid[v],
                1e-12 * std::max(1.0, std::abs(resting.qfrc_fluid[v])))
        << v;
  }
}

TEST(Fluid, PassiveForceFlags) {
  auto force = [](const std::string& flags) {
    std::string xml = FreeBodies("1 0 0");
    xml.replace(xml.find("\"/>"), 3, "\"><flag " + flags + "/></option>");
    Model m = LoadXmlString(xml);
    Data d = MakeData(m);
    Forward(m, d);
    double sum = 0;
    for (int v = 0; v < m.nv; v++) {
      EXPECT_EQ(d.qfrc_passive[v], d.qfrc_fluid[v]) << flags;
      sum += std::abs(d.qfrc_fluid[v]);
    }
    return sum;
  };
  EXPECT_GT(force("damper=\"disable\""), 0);
  EXPECT_GT(force("spring=\"disable\""), 0);
  EXPECT_EQ(force("spring=\"disable\" damper=\"disable\""), 0);
}

TEST(Fluid, FluidshapeValues) {
  const std::string xml =
      "<mujoco>\n<worldbody>\n<geom size=\".1\" fluidshape=\"box\"/>\n</worldbody>\n</mujoco>";
  test_util::ExpectMessageParts(test_util::XmlLoadError(xml), {"bad.xml:3:", "fluidshape"}, xml);
}

}  // namespace
}  // namespace simlab
