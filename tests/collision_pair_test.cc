// Per-pair contact conformance: every tests/collision_pairs/models/NAME.xml against
// goldens/NAME.json, the contacts MuJoCo 3.5.1 finds after mj_forward (written by
// tools/dump_contacts.mjs; regenerate with tests/collision_pairs/make_goldens.sh).
// Dropping a model and its golden in those folders adds a case.
//
// Two checks per model:
//   NarrowPhase  calls the narrow-phase function of every geom pair directly and
//                compares its contacts with MuJoCo's contacts of that pair (count,
//                order, dist, pos, normal). Box-box contacts are compared before the
//                driver's cleanup: MuJoCo's must appear in order among ours.
//   Contacts     runs Forward and compares d.contact, in order: geom ids, dist, pos and
//                the whole frame, then the driver's contact parameters.
//   ContactRows  efc_address and mu, which the constraint rows write into the contacts.
// Numbers agree when |ours - MuJoCo| <= 1e-9 * max(1, |MuJoCo|) (absolute below 1,
// relative above). Each check prints its worst differences.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/collision.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using nlohmann::json;

constexpr double kTol = 1e-9;

std::string PairsDir() { return std::string(SIMLAB_SOURCE_DIR) + "/tests/collision_pairs"; }

// Every model that has a golden, by name.
std::vector<std::string> CaseNames() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(PairsDir() + "/models")) {
    if (entry.path().extension() != ".xml") continue;
    std::string name = entry.path().stem().string();
    if (std::filesystem::exists(PairsDir() + "/goldens/" + name + ".json")) {
      names.push_back(name);
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

json ReadGolden(const std::string& name) {
  std::ifstream in(PairsDir() + "/goldens/" + name + ".json");
  json j;
  in >> j;
  return j;
}

// The model in the golden's state (keyframe or default), after Forward.
struct Loaded {
  Model m;
  Data d;
};
Loaded LoadCase(const std::string& name, const json& golden) {
  Loaded c{LoadXml(PairsDir() + "/models/" + name + ".xml"), {}};
  c.d = MakeData(c.m);
  int key = golden.value("key", -1);
  if (key >= 0) ResetDataKeyframe(c.m, c.d, key);
  Forward(c.m, c.d);
  return c;
}

// Worst differences seen, by quantity.
struct Worst {
  double dist = 0, pos = 0, frame = 0, params = 0;
  int contacts = 0;
  size_t ours = 0;  // narrow phase: our contacts before the driver's box-box cleanup
  void Print(const std::string& what) const {
    std::cout << what << ": " << contacts << " contacts, worst |d dist| " << dist
              << ", |d pos| " << pos << ", |d frame| " << frame;
    if (params > 0) std::cout << ", |d params| " << params;
    if (ours > static_cast<size_t>(contacts)) std::cout << " (ours before cleanup " << ours << ")";
    std::cout << "\n";
  }
};

// Compares n numbers; records the worst absolute difference in `worst`.
bool NearAll(const double* got, const json& want, int n, double& worst) {
  bool ok = true;
  for (int i = 0; i < n; i++) {
    double w = want[i].get<double>();
    double diff = std::abs(got[i] - w);
    worst = std::max(worst, diff);
    if (!(diff <= kTol * std::max(1.0, std::abs(w)))) ok = false;
  }
  return ok;
}

// Prints a contact for failure messages.
std::string Describe(const Contact& c) {
  std::ostringstream s;
  s << "dist " << c.dist << " pos (" << c.pos[0] << ", " << c.pos[1] << ", " << c.pos[2]
    << ") normal (" << c.frame[0] << ", " << c.frame[1] << ", " << c.frame[2] << ")";
  return s.str();
}

// dist, pos and the first `frame_n` frame entries of one contact.
bool SameGeometry(const Contact& got, const json& want, int frame_n, Worst& worst) {
  double dist[1] = {got.dist};
  json want_dist = json::array({want["dist"]});
  bool ok = NearAll(dist, want_dist, 1, worst.dist);
  ok = NearAll(got.pos, want["pos"], 3, worst.pos) && ok;
  ok = NearAll(got.frame, want["frame"], frame_n, worst.frame) && ok;
  return ok;
}

class CollisionPair : public ::testing::TestWithParam<std::string> {};

// ---------------------------------------------------------------- narrow phase

// MuJoCo's contacts of geom pair (g1, g2), in order.
std::vector<json> GoldenOfPair(const json& golden, int g1, int g2) {
  std::vector<json> out;
  for (const json& c : golden["contact"]) {
    if (c["geom"][0].get<int>() == g1 && c["geom"][1].get<int>() == g2) out.push_back(c);
  }
  return out;
}

// Ours against MuJoCo's for one pair. MuJoCo's box-box contacts went through the
// driver's cleanup, so they need only appear in order among ours.
void ComparePair(const std::string& name, const std::vector<Contact>& ours,
                 const std::vector<json>& want, bool subsequence, Worst& worst) {
  worst.ours += ours.size();
  if (!subsequence) {
    ASSERT_EQ(ours.size(), want.size()) << name;
  }
  size_t k = 0;
  for (const json& w : want) {
    Worst trial = worst;
    while (k < ours.size() && subsequence && !SameGeometry(ours[k], w, 3, trial)) {
      trial = worst;
      k++;
    }
    ASSERT_LT(k, ours.size()) << name << ": no contact of ours matches MuJoCo's " << w.dump();
    EXPECT_TRUE(SameGeometry(ours[k], w, 3, worst))
        << name << " contact " << k << ": ours " << Describe(ours[k]) << ", MuJoCo "
        << w.dump();
    k++;
    worst.contacts++;
  }
}

// The margin MuJoCo's driver gives geoms a and b: an explicit <pair>'s own, else the
// sum of the geoms' margins.
double PairMargin(const Model& m, int a, int b) {
  for (int p = 0; p < m.npair; p++) {
    int p1 = m.pair_geom1[p], p2 = m.pair_geom2[p];
    if ((p1 == a && p2 == b) || (p1 == b && p2 == a)) return m.pair_margin[p];
  }
  return m.geom_margin[a] + m.geom_margin[b];
}

TEST_P(CollisionPair, NarrowPhase) {
  const std::string name = GetParam();
  json golden = ReadGolden(name);
  Loaded c = LoadCase(name, golden);
  const Model& m = c.m;
  Worst worst;
  int pairs_with_contacts = 0;
  for (int g1 = 0; g1 < m.ngeom; g1++) {
    for (int g2 = g1 + 1; g2 < m.ngeom; g2++) {
      if (m.geom_bodyid[g1] == m.geom_bodyid[g2]) continue;
      int a = g1, b = g2;
      if (m.geom_type[a] > m.geom_type[b]) std::swap(a, b);
      CollideFn fn = CollisionFunction(m.geom_type[a], m.geom_type[b]);
      if (!fn) continue;
      double margin = PairMargin(m, a, b);
      std::vector<Contact> con(kMaxContactPair);
      int n = fn(m, c.d, con.data(), a, b, margin);
      con.resize(n);
      std::vector<json> want = GoldenOfPair(golden, a, b);
      pairs_with_contacts += !want.empty();
      bool boxes = m.geom_type[a] == kGeomBox && m.geom_type[b] == kGeomBox;
      ComparePair(name + " geoms " + std::to_string(a) + "-" + std::to_string(b), con, want,
                  boxes, worst);
    }
  }
  EXPECT_EQ(worst.contacts, golden["ncon"].get<int>()) << name << ": contacts compared";
  worst.Print(name + " narrow phase (" + std::to_string(pairs_with_contacts) + " pairs)");
}

// ---------------------------------------------------------------- whole pipeline

// The contact parameters the driver fills in.
bool SameParameters(const Contact& got, const json& want, double& worst) {
  double margin[1] = {got.includemargin};
  bool ok = NearAll(margin, json::array({want["includemargin"]}), 1, worst);
  ok = NearAll(got.friction, want["friction"], 5, worst) && ok;
  ok = NearAll(got.solref, want["solref"], kNRef, worst) && ok;
  ok = NearAll(got.solreffriction, want["solreffriction"], kNRef, worst) && ok;
  ok = NearAll(got.solimp, want["solimp"], kNImp, worst) && ok;
  return ok && got.dim == want["dim"].get<int>() && got.exclude == want["exclude"].get<int>();
}

TEST_P(CollisionPair, Contacts) {
  const std::string name = GetParam();
  json golden = ReadGolden(name);
  Loaded c = LoadCase(name, golden);
  const json& want = golden["contact"];
  ASSERT_EQ(c.d.ncon, golden["ncon"].get<int>()) << name;
  Worst worst;
  for (int i = 0; i < c.d.ncon; i++) {
    const Contact& got = c.d.contact[i];
    const json& w = want[i];
    EXPECT_EQ(got.geom[0], w["geom"][0].get<int>()) << name << " contact " << i;
    EXPECT_EQ(got.geom[1], w["geom"][1].get<int>()) << name << " contact " << i;
    EXPECT_TRUE(SameGeometry(got, w, 9, worst))
        << name << " contact " << i << ": ours " << Describe(got) << ", MuJoCo " << w.dump();
    EXPECT_TRUE(SameParameters(got, w, worst.params))
        << name << " contact " << i << ": ours includemargin " << got.includemargin << " dim "
        << got.dim << " exclude " << got.exclude << " friction[0] " << got.friction[0]
        << " solref[0] " << got.solref[0] << ", MuJoCo " << w.dump();
    worst.contacts++;
  }
  worst.Print(name + " contacts");
}

// What the constraint rows write back into the contacts: first row and friction.
TEST_P(CollisionPair, ContactRows) {
  const std::string name = GetParam();
  json golden = ReadGolden(name);
  Loaded c = LoadCase(name, golden);
  ASSERT_EQ(c.d.ncon, golden["ncon"].get<int>()) << name;
  for (int i = 0; i < c.d.ncon; i++) {
    const Contact& got = c.d.contact[i];
    const json& w = golden["contact"][i];
    EXPECT_EQ(got.efc_address, w["efc_address"].get<int>()) << name << " contact " << i;
    EXPECT_NEAR(got.mu, w["mu"].get<double>(), kTol * std::max(1.0, w["mu"].get<double>()))
        << name << " contact " << i;
  }
}

std::string CaseName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Goldens, CollisionPair, ::testing::ValuesIn(CaseNames()), CaseName);

}  // namespace
}  // namespace simlab
