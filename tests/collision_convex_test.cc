// Convex collisions by GJK/EPA (engine/collision_convex.cc, collision_gjk.cc) against
// MuJoCo's own contacts.
//
// Each model of tests/collision_convex/models holds a fixed geom and a free geom, with
// keyframes placing the free one at random poses (deep, shallow, none). The goldens
// (tests/collision_convex/goldens, from dump_keys.mjs via make_goldens.sh) hold
// MuJoCo's geom poses and contacts per key. Here the narrow-phase function of the pair
// runs directly on MuJoCo's poses (GJK stops at a tolerance, so a last-bit difference
// in the poses can move a shallow contact by 1e-7), and its contacts must match
// MuJoCo's in number, depth, position and normal. Further, properties that hold by
// construction: the GJK distance of separated spheres and the depth of overlapping ones
// are exact, and swapping the shapes flips the normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "engine/collision.h"
#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(SIMLAB_SOURCE_DIR) + "/tests/collision_convex";

// Agreement asked of positions, normals and depths (well-conditioned cases).
constexpr double kTolerance = 1e-9;

// Names of the models (without .xml), sorted.
std::vector<std::string> ModelNames() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kDir + "/models")) {
    if (entry.path().extension() == ".xml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The narrow-phase contacts of the model's two geoms, in MuJoCo's order (the lower
// geom type first) with the driver's margin (the sum of the two).
std::vector<Contact> NarrowPhase(const Model& m, const Data& d, int* first) {
  int g1 = 0, g2 = 1;
  if (m.geom_type[g1] > m.geom_type[g2]) std::swap(g1, g2);
  *first = g1;
  double margin = m.geom_margin[g1] + m.geom_margin[g2];
  CollideFn collide = CollisionFunction(m.geom_type[g1], m.geom_type[g2]);
  std::vector<Contact> con(kMaxContactPair);
  int n = collide ? collide(m, d, con.data(), g1, g2, margin) : 0;
  con.resize(n);
  return con;
}

double MaxDiff(const nlohmann::json& ref, const double* ours, int n) {
  double worst = 0;
  for (int i = 0; i < n; i++) worst = std::max(worst, std::abs(ref[i].get<double>() - ours[i]));
  return worst;
}

// Worst differences of one model over its keys, and what did not match.
struct PairReport {
  int keys = 0, contacts = 0;
  double dist = 0, pos = 0, normal = 0;
  std::string mismatches;
};

// Puts MuJoCo's geom poses into d (after our own kinematics, which must agree closely).
double UseReferencePoses(const nlohmann::json& key, Data& d) {
  double worst = 0;
  for (size_t i = 0; i < d.geom_xpos.size(); i++) {
    double ref = key["geom_xpos"][i].get<double>();
    worst = std::max(worst, std::abs(ref - d.geom_xpos[i]));
    d.geom_xpos[i] = ref;
  }
  for (size_t i = 0; i < d.geom_xmat.size(); i++) {
    double ref = key["geom_xmat"][i].get<double>();
    worst = std::max(worst, std::abs(ref - d.geom_xmat[i]));
    d.geom_xmat[i] = ref;
  }
  return worst;
}

PairReport CompareModel(const std::string& name) {
  Model m = LoadXml(kDir + "/models/" + name + ".xml");
  std::ifstream in(kDir + "/goldens/" + name + ".json");
  nlohmann::json golden = nlohmann::json::parse(in)["keys"];
  Data d = MakeData(m);
  PairReport report;
  std::ostringstream bad;
  if (golden.size() != static_cast<size_t>(m.nkey)) {
    bad << " " << m.nkey << " keys, golden " << golden.size() << ";";
  }
  for (int k = 0; k < m.nkey; k++) {
    ResetDataKeyframe(m, d, k);
    Kinematics(m, d);
    if (UseReferencePoses(golden.at(k), d) > 1e-12) bad << " key " << k << ": poses differ;";
    int first;
    std::vector<Contact> ours = NarrowPhase(m, d, &first);
    const nlohmann::json& ref = golden.at(k)["contact"];
    report.keys++;
    if (ours.size() != ref.size()) {
      bad << " key " << k << ": " << ours.size() << " contacts, MuJoCo " << ref.size() << ";";
      continue;
    }
    for (size_t i = 0; i < ours.size(); i++) {
      if (ref[i]["geom"][0].get<int>() != first) bad << " key " << k << ": geom order;";
      report.contacts++;
      report.dist = std::max(report.dist, std::abs(ref[i]["dist"].get<double>() - ours[i].dist));
      report.pos = std::max(report.pos, MaxDiff(ref[i]["pos"], ours[i].pos, 3));
      report.normal = std::max(report.normal, MaxDiff(ref[i]["normal"], ours[i].frame, 3));
    }
  }
  report.mismatches = bad.str();
  return report;
}

// ---------------------------------------------------------------- against MuJoCo

class ConvexPairs : public testing::TestWithParam<std::string> {};

TEST_P(ConvexPairs, MatchMuJoCo) {
  PairReport r = CompareModel(GetParam());
  std::printf("%-28s keys %2d contacts %2d  worst dist %.1e pos %.1e normal %.1e\n",
              GetParam().c_str(), r.keys, r.contacts, r.dist, r.pos, r.normal);
  EXPECT_EQ(r.mismatches, "");
  EXPECT_LE(r.dist, kTolerance);
  EXPECT_LE(r.pos, kTolerance);
  EXPECT_LE(r.normal, kTolerance);
}

INSTANTIATE_TEST_SUITE_P(Models, ConvexPairs, testing::ValuesIn(ModelNames()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

// ---------------------------------------------------------------- by construction

// Two round ellipsoids (spheres without the centre-point shortcut GJK takes for spheres).
const char* kTwoBalls = R"(
<mujoco>
  <option ccd_iterations="500"/>
  <worldbody>
    <geom type="ellipsoid" size="0.1 0.1 0.1"/>
    <body><freejoint/><geom type="ellipsoid" size="0.2 0.2 0.2"/></body>
  </worldbody>
</mujoco>)";

// GJK/EPA's depth and normal of the balls with surfaces `gap` apart (1 if no contact).
// EPA converges slowly on smooth shapes: enough iterations to reach ccd_tolerance.
double BallQuery(double gap, double* normal) {
  Model m = LoadXmlString(kTwoBalls);
  Data d = MakeData(m);
  ResetData(m, d);
  const double dir[3] = {0.6, -0.48, 0.64};  // unit
  for (int i = 0; i < 3; i++) d.qpos[i] = dir[i] * (0.3 + gap);
  Kinematics(m, d);
  Contact con[kMaxContactPair];
  if (CollideConvex(m, d, con, 0, 1, 0) == 0) return 1;
  for (int i = 0; i < 3; i++) normal[i] = con[0].frame[i];
  return con[0].dist;
}

TEST(ConvexByConstruction, BallDepthIsExact) {
  double normal[3];
  for (double gap : {-0.05, -0.01, -0.001}) {
    double dist = BallQuery(gap, normal);
    EXPECT_NEAR(dist, gap, 1e-6) << "gap " << gap;
    EXPECT_NEAR(normal[0], 0.6, 5e-3);
    EXPECT_NEAR(normal[1], -0.48, 5e-3);
    EXPECT_NEAR(normal[2], 0.64, 5e-3);
  }
  EXPECT_EQ(BallQuery(0.01, normal), 1);  // apart: no contact
}

// Swapping the geoms of a pair flips the normal and keeps depth and position.
TEST(ConvexByConstruction, SwapFlipsNormal) {
  Model m = LoadXml(kDir + "/models/cylinder_cylinder.xml");
  Data d = MakeData(m);
  int checked = 0;
  for (int k = 0; k < m.nkey; k++) {
    ResetDataKeyframe(m, d, k);
    Kinematics(m, d);
    Contact a[kMaxContactPair], b[kMaxContactPair];
    int na = CollideConvex(m, d, a, 0, 1, 0);
    int nb = CollideConvex(m, d, b, 1, 0, 0);
    ASSERT_EQ(na, nb) << "key " << k;
    if (!na) continue;
    checked++;
    // EPA's answer depends on the order of its steps: close, not equal
    EXPECT_NEAR(a[0].dist, b[0].dist, 1e-4);
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(a[0].frame[i], -b[0].frame[i], 0.05);
      EXPECT_NEAR(a[0].pos[i], b[0].pos[i], 1e-3);
    }
  }
  EXPECT_GT(checked, 3);
}

}  // namespace
}  // namespace simlab
