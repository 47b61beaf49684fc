// Spatial tendons, tendon armature, and actuator damping and armature.
//
// Paths: tests/conformance/tendon/paths/*.json hold what MuJoCo 3.5.1 computes
// (dump_paths.mjs) for each base model at six states of a rollout: the path points
// (ten_wrapadr, ten_wrapnum, wrap_obj, wrap_xpos), ten_length, ten_J, qM (tendon
// armature included) and qfrc_bias (tendon armature bias included).
//
// Actuator damping and armature (MuJoCo 3.7+, which the 3.5.1 oracle cannot load) are
// checked by equivalence: an actuator with damping d, armature a and gear g must move
// its joint or tendon exactly like joint/tendon damping d g^2 and armature a g^2, under
// every integrator; the polynomial terms against the force written out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using Json = nlohmann::json;

std::string Source(const std::string& rel) { return std::string(SIMLAB_SOURCE_DIR) + "/" + rel; }

bool Near(double want, double got, double tol) {
  return std::abs(want - got) <= tol * std::max(1.0, std::abs(want));
}

// Sets qpos, qvel from a state file written for the oracle.
void ApplyState(const std::string& path, Data& d) {
  std::ifstream in(Source(path));
  Json state = Json::parse(in);
  for (auto& [name, values] : state.items()) {
    std::vector<double>& field = name == "qpos" ? d.qpos : d.qvel;
    for (size_t k = 0; k < values.size(); k++) field[k] = values[k].get<double>();
  }
}

// One record of a paths golden against our data.
void ComparePaths(const std::string& label, const Model& m, const Data& d, const Json& want) {
  constexpr double kTol = 1e-9;
  for (int i = 0; i < m.ntendon; i++) {
    ASSERT_EQ(d.ten_wrapadr[i], want["ten_wrapadr"][i].get<int>()) << label << " tendon " << i;
    ASSERT_EQ(d.ten_wrapnum[i], want["ten_wrapnum"][i].get<int>()) << label << " tendon " << i;
    for (int p = d.ten_wrapadr[i]; p < d.ten_wrapadr[i] + d.ten_wrapnum[i]; p++) {
      EXPECT_EQ(d.wrap_obj[p], want["wrap_obj"][p].get<int>()) << label << " point " << p;
      for (int k = 0; k < 3; k++) {
        double w = want["wrap_xpos"][3 * p + k].get<double>();
        EXPECT_TRUE(Near(w, d.wrap_xpos[3 * p + k], kTol))
            << label << " wrap_xpos point " << p << ": " << d.wrap_xpos[3 * p + k] << " vs " << w;
      }
    }
  }
  auto field = [&](const char* name, const std::vector<double>& ours) {
    ASSERT_EQ(want[name].size(), ours.size()) << label << " " << name;
    for (size_t k = 0; k < ours.size(); k++) {
      double w = want[name][k].get<double>();
      EXPECT_TRUE(Near(w, ours[k], kTol)) << label << " " << name << "[" << k << "]: " << ours[k]
                                          << " vs MuJoCo " << w;
    }
  };
  field("ten_length", d.ten_length);
  field("ten_J", d.ten_J);
  field("qM", d.qM);
  field("qfrc_bias", d.qfrc_bias);
}

class TendonPaths : public ::testing::TestWithParam<std::string> {};

TEST_P(TendonPaths, MatchMuJoCo) {
  std::ifstream in(Source("tests/conformance/tendon/paths/" + GetParam() + ".json"));
  ASSERT_TRUE(in.good()) << GetParam();
  Json golden = Json::parse(in);
  Model m = LoadXml(Source(golden["model"].get<std::string>()));
  Data d = MakeData(m);
  if (!golden["state"].is_null()) ApplyState(golden["state"].get<std::string>(), d);
  Forward(m, d);
  const Json& records = golden["records"];
  for (size_t r = 0; r < records.size(); r++) {
    if (r > 0) {
      for (int s = 0; s < 100; s++) Step(m, d);
      Forward(m, d);
    }
    ComparePaths(GetParam() + " record " + std::to_string(r), m, d, records[r]);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, TendonPaths,
                         ::testing::Values("tendon_sites", "wrap_sphere", "wrap_cylinder",
                                           "pulley", "armature", "actuated"));

// ---------------------------------------------------------------- compile errors

// A world with two bodies, sites, a sphere and a box, and the given tendon section.
std::string WithTendon(const std::string& tendon) {
  return "<mujoco>\n<worldbody>\n<site name=\"w\"/>\n"
         "<body><joint/><geom name=\"ball\" size=\".1\"/><geom name=\"box\" type=\"box\" "
         "size=\".1 .1 .1\"/><site name=\"a\"/><site name=\"b\"/></body>\n"
         "</worldbody>\n<tendon>\n" +
         tendon + "\n</tendon>\n</mujoco>";
}

TEST(SpatialTendonErrors, PathRules) {
  struct Case {
    std::string tendon, line, what;
  };
  const Case cases[] = {
      {"<spatial/>", "bad.xml:7:", "path cannot be empty"},
      {"<spatial><site site=\"a\"/></spatial>", "bad.xml:7:", "at least two objects"},
      {"<spatial width=\"0\"><site site=\"w\"/><site site=\"a\"/></spatial>", "bad.xml:7:",
       "positive width"},
      {"<spatial><site site=\"w\"/><site site=\"nope\"/></spatial>", "bad.xml:7:", "unknown site 'nope'"},
      {"<spatial><site site=\"w\"/><geom geom=\"box\"/><site site=\"a\"/></spatial>", "bad.xml:7:",
       "not a sphere or cylinder"},
      {"<spatial><site site=\"w\"/><geom geom=\"ball\" sidesite=\"x\"/><site site=\"a\"/></spatial>",
       "bad.xml:7:", "unknown side site 'x'"},
      {"<spatial><geom geom=\"ball\"/><site site=\"w\"/><site site=\"a\"/></spatial>", "bad.xml:7:",
       "between two sites"},
      {"<spatial><site site=\"w\"/><site site=\"a\"/><pulley divisor=\"2\"/></spatial>",
       "bad.xml:7:", "ends with a pulley"},
      {"<spatial><site site=\"w\"/><site site=\"a\"/><pulley divisor=\"2\"/><pulley "
       "divisor=\"2\"/><site site=\"a\"/><site site=\"b\"/></spatial>",
       "bad.xml:7:", "consecutive pulleys"},
      {"<spatial><site site=\"w\"/><site site=\"a\"/><pulley divisor=\"-1\"/><site site=\"w\"/>"
       "<site site=\"a\"/></spatial>",
       "bad.xml:7:", "negative divisor"},
      {"<spatial><site site=\"w\"/><site site=\"a\"/><pulley divisor=\"2\"/><site site=\"b\"/>"
       "</spatial>",
       "bad.xml:7:", "neighbor that is not a pulley"},
      {"<spatial><site site=\"a\"/><site site=\"a\"/></spatial>", "bad.xml:7:", "site is repeated"},
      {"<spatial armature=\"1\"><site site=\"w\"/><geom geom=\"ball\"/><site site=\"a\"/></spatial>",
       "bad.xml:7:", "tendon armature"},
      {"<spatial armature=\"-1\"><site site=\"w\"/><site site=\"a\"/></spatial>", "bad.xml:7:",
       "armature cannot be negative"},
      {"<spatial><joint joint=\"j\" coef=\"1\"/></spatial>", "bad.xml:7:", "<joint>"},
      {"<fixed><site site=\"a\"/></fixed>", "bad.xml:7:", "<site>"},
      {"<fixed width=\"1\"><joint joint=\"j\" coef=\"1\"/></fixed>", "bad.xml:7:", "width"},
  };
  for (const Case& c : cases) {
    std::string msg = test_util::XmlLoadError(WithTendon(c.tendon));
    EXPECT_NE(msg.find(c.line), std::string::npos) << c.tendon << " -> " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << c.tendon << " -> " << msg;
  }
}

// ---------------------------------------------------------------- actuator damping, armature

// A hinge arm (with a second, passive hinge) and a fixed tendon across both hinges.
// `joint_extra` goes on the first hinge, `tendon_extra` on the tendon, `actuators` in
// <actuator>.
std::string ArmModel(int integrator, const std::string& joint_extra,
                     const std::string& tendon_extra, const std::string& actuators) {
  const char* names[] = {"Euler", "RK4", "implicit", "implicitfast"};
  return std::string("<mujoco>\n<option integrator=\"") + names[integrator] +
         "\"><flag contact=\"disable\"/></option>\n<worldbody>\n"
         "<body pos=\"0 0 1\"><joint name=\"j1\" axis=\"0 1 0\" " + joint_extra +
         "/><geom type=\"capsule\" fromto=\"0 0 0 .3 0 0\" size=\".03\"/>\n"
         "<body pos=\".3 0 0\"><joint name=\"j2\" axis=\"0 1 .3\"/><geom type=\"capsule\" "
         "fromto=\"0 0 0 .25 0 0\" size=\".02\"/></body></body>\n</worldbody>\n"
         "<tendon><fixed name=\"t\" " + tendon_extra +
         "><joint joint=\"j1\" coef=\"1\"/><joint joint=\"j2\" coef=\"-.7\"/></fixed></tendon>\n"
         "<actuator>" + actuators + "</actuator>\n</mujoco>";
}

// Rolls out 300 steps from a moving state with a control schedule; returns qpos, qvel.
std::vector<double> Rollout(const Model& m) {
  Data d = MakeData(m);
  d.qpos[0] = 0.4;
  d.qvel[0] = 2.0;
  d.qvel[1] = -3.0;
  std::vector<double> out;
  for (int s = 0; s < 300; s++) {
    for (int u = 0; u < m.nu; u++) d.ctrl[u] = std::sin(0.05 * s + u);
    Step(m, d);
    out.insert(out.end(), d.qpos.begin(), d.qpos.end());
    out.insert(out.end(), d.qvel.begin(), d.qvel.end());
  }
  return out;
}

// `joint_form` (damping, armature on the joint or tendon) and `actuator_form` (the same
// through actuators) must agree; `without` (neither) must not.
void ExpectSameTrajectory(const std::string& joint_form, const std::string& actuator_form,
                          const std::string& without, const std::string& label) {
  std::vector<double> a = Rollout(LoadXmlString(joint_form));
  std::vector<double> b = Rollout(LoadXmlString(actuator_form));
  std::vector<double> c = Rollout(LoadXmlString(without));
  ASSERT_EQ(a.size(), b.size());
  double worst = 0, effect = 0;
  for (size_t k = 0; k < a.size(); k++) {
    worst = std::max(worst, std::abs(a[k] - b[k]) / std::max(1.0, std::abs(a[k])));
    effect = std::max(effect, std::abs(a[k] - c[k]));
  }
  EXPECT_LE(worst, 1e-12) << label;
  EXPECT_GT(effect, 1e-3) << label;
}

TEST(ActuatorDamping, EqualsJointDampingAndArmatureTimesGearSquared) {
  for (int integrator = 0; integrator < 4; integrator++) {
    std::string label = "integrator " + std::to_string(integrator);
    // Hinge: gear 3, damping 0.2, armature 0.05 -> joint damping 1.8, armature 0.45; a
    // second actuator on the same joint (several: summed) adds damping 0.1 at gear 2.
    const std::string plain = "<motor joint=\"j1\" gear=\"3\"/><motor joint=\"j2\"/><general joint=\"j1\" gear=\"2\"/>";
    ExpectSameTrajectory(
        ArmModel(integrator, "damping=\"2.2\" armature=\"0.45\"", "", plain),
        ArmModel(integrator, "", "",
                 "<motor joint=\"j1\" gear=\"3\" damping=\"0.2\" armature=\"0.05\"/>"
                 "<motor joint=\"j2\"/><general joint=\"j1\" gear=\"2\" damping=\"0.1\"/>"),
        ArmModel(integrator, "", "", plain), label + " hinge");
    // Fixed tendon: gear -2, damping 0.5, armature 0.1 -> tendon damping 2, armature 0.4.
    const std::string servo = "<position tendon=\"t\" gear=\"-2\" kp=\"3\"/><motor joint=\"j2\"/>";
    ExpectSameTrajectory(
        ArmModel(integrator, "", "damping=\"2\" armature=\"0.4\"", servo),
        ArmModel(integrator, "", "",
                 "<position tendon=\"t\" gear=\"-2\" kp=\"3\" damping=\"0.5\" armature=\"0.1\"/>"
                 "<motor joint=\"j2\"/>"),
        ArmModel(integrator, "", "", servo), label + " tendon");
  }
}

TEST(ActuatorDamping, TargetIds) {
  Model m = LoadXmlString(ArmModel(0, "", "",
                                   "<motor joint=\"j1\" damping=\"1\"/><motor joint=\"j1\" armature=\"1\"/>"
                                   "<motor joint=\"j2\"/><motor tendon=\"t\" damping=\"0 0 1\"/>"));
  EXPECT_EQ(m.jnt_actuatorid[0], -2);
  EXPECT_EQ(m.jnt_actuatorid[1], -1);
  EXPECT_EQ(m.tendon_actuatorid[0], 3);
  EXPECT_EQ(m.actuator_dampingpoly[2 * 3 + 1], 1);
}

// force = -g^2 (a v + b v|v| + c v^3) on the joint, and its velocity slope in qDeriv.
TEST(ActuatorDamping, PolynomialForceByHand) {
  Model m = LoadXmlString(ArmModel(2, "", "", "<motor joint=\"j1\" gear=\"1.5\" damping=\"0.3 0.7 0.2\"/>"));
  Data d = MakeData(m);
  const double a = 0.3, b = 0.7, c = 0.2, g2 = 1.5 * 1.5;
  for (double v : {-2.5, -0.3, 0.0, 0.8, 3.0}) {
    d.qvel[0] = v;
    Forward(m, d);
    double want = -g2 * (a * v + b * v * std::abs(v) + c * v * v * v);
    EXPECT_NEAR(d.qfrc_damper[0], want, 1e-12 * std::max(1.0, std::abs(want))) << v;
    SmoothVelocityDerivative(m, d, false);
    double slope = -g2 * (a + 2 * b * std::abs(v) + 3 * c * v * v);
    EXPECT_NEAR(d.qDeriv[0], slope, 1e-12 * std::max(1.0, std::abs(slope))) << v;
  }
}

TEST(ActuatorDamping, Errors) {
  std::string site = "<mujoco>\n<worldbody>\n<body><joint/><geom size=\".1\"/><site name=\"s\"/></body>\n"
                     "</worldbody>\n<actuator>\n";
  std::string msg = test_util::XmlLoadError(site + "<motor site=\"s\" damping=\"1\"/>\n</actuator>\n</mujoco>");
  EXPECT_NE(msg.find("bad.xml:6:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("damping requires a joint or tendon transmission"), std::string::npos) << msg;
  msg = test_util::XmlLoadError(site + "<motor site=\"s\" armature=\"1\"/>\n</actuator>\n</mujoco>");
  EXPECT_NE(msg.find("armature requires a joint or tendon transmission"), std::string::npos) << msg;
  msg = test_util::XmlLoadError(site + "<adhesion body=\"world\" damping=\"1\"/>\n</actuator>\n</mujoco>");
  EXPECT_NE(msg.find("damping"), std::string::npos) << msg;
}

}  // namespace
}  // namespace simlab
