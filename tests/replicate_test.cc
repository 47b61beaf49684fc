// <replicate>: models that use it compile to MuJoCo's model (every array simlab has and
// every name, from goldens made by tools/dump_fields_names.mjs with MuJoCo 3.5.1), and
// bad replicate elements get file:line errors.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using nlohmann::json;

std::string Dir() { return std::string(SIMLAB_SOURCE_DIR) + "/tests/replicate/"; }

json ReadGolden(const std::string& name) {
  std::ifstream in(Dir() + "goldens/" + name + ".json");
  EXPECT_TRUE(in.good()) << "missing golden " << name;
  json j;
  if (in) in >> j;
  return j;
}

// The names of one kind against MuJoCo's (kinds the golden predates have none).
void CompareNames(const std::string& kind, const std::vector<std::string>& ours,
                  const json& golden) {
  std::vector<std::string> want;
  if (golden.contains(kind)) want = golden.at(kind).get<std::vector<std::string>>();
  EXPECT_EQ(ours, want) << kind << " names";
}

// One array against MuJoCo's; returns the worst absolute difference.
double CompareArray(const FieldView& f, const json& golden) {
  size_t n = static_cast<size_t>(f.rows) * f.cols;
  EXPECT_EQ(golden.size(), n) << f.name << " size";
  if (golden.size() != n) return INFINITY;
  double worst = 0;
  for (size_t i = 0; i < n; i++) {
    double want = golden[i].get<double>();
    double got = f.is_int ? f.ints[i] : f.doubles[i];
    double diff = std::abs(got - want);
    worst = std::max(worst, diff);
    EXPECT_LE(diff, 1e-12 * std::max(1.0, std::abs(want)))
        << f.name << "[" << i << "] = " << got << ", MuJoCo " << want;
  }
  return worst;
}

void CheckModel(const std::string& name) {
  Model m = LoadXml(Dir() + name + ".xml");
  json golden = ReadGolden(name);
  ASSERT_TRUE(golden.contains("names"));
#define SIMLAB_X(kind, count) CompareNames(#kind, m.kind##_names, golden["names"]);
  SIMLAB_MODEL_NAMED(SIMLAB_X)
#undef SIMLAB_X
  // Every array both have (the principal inertia frame is compared as a tensor elsewhere).
  int compared = 0;
  for (FieldView& f : m.Fields()) {
    const json& arrays = golden["arrays"];
    if (!arrays.contains(f.name)) continue;
    double worst = CompareArray(f, arrays[f.name]);
    EXPECT_TRUE(std::isfinite(worst)) << f.name;
    compared++;
  }
  EXPECT_GT(compared, 100) << "too few arrays compared";
}

// Nested replicates with separators and rotations, bodies with joints, sites, geoms and
// cameras, a replicate inside a frame and inside a body, in the world; actuators and
// sensors on replicated objects are replicated with them.
TEST(Replicate, TreeAndReferences) { CheckModel("replicate_tree"); }

// Pairs, excludes, tendons, equalities, actuators and sensors naming replicated objects
// follow MuJoCo's attach rules: copied when their suffixed names resolve (one of two
// objects may stay outside), dropped with the template when they name it; sensors
// without objects (clock, energy) are copied by every replica; a childclass on the
// replicate; a camera target inside.
TEST(Replicate, ReferencingElements) { CheckModel("replicate_refs"); }

// The XML reference's example (nested, sep on the inner one: Alice-00, Alice-10, ...) with
// a geom and a site of the same name and a light, and twelve free bodies (two-digit
// suffixes) each followed by an unnamed frame sensor. (Their geoms sit off the body
// origin: MuJoCo 3.5.1 gives a simple free body a diagonal M layout, M_rownnz 1, which
// simlab's compiled M_rownnz/M_rowadr/M_colind do not follow yet.)
TEST(Replicate, ReferenceExample) { CheckModel("replicate_doc"); }

// ---------------------------------------------------------------- bad input

// A worldbody fragment and the pieces its error message must contain.
struct BadCase {
  const char* body;
  std::vector<std::string> pieces;
};

// Each bad replicate is refused with the file, the line, the element and the problem.
TEST(Replicate, BadInput) {
  const BadCase cases[] = {
      {"<replicate offset=\"1 0 0\">\n<geom size=\"1\"/>\n</replicate>",
       {"bad.xml:3:", "<replicate>", "required attribute missing: 'count'"}},
      {"<replicate count=\"0\">\n<geom size=\"1\"/>\n</replicate>",
       {"bad.xml:3:", "<replicate>", "count must be positive"}},
      {"<replicate count=\"two\">\n<geom size=\"1\"/>\n</replicate>",
       {"bad.xml:3:", "<replicate>", "count"}},
      {"<replicate count=\"2\" pos=\"1 0 0\">\n<geom size=\"1\"/>\n</replicate>",
       {"bad.xml:3:", "<replicate>", "'pos'"}},
      {"<replicate count=\"2\" childclass=\"nope\">\n<geom size=\"1\"/>\n</replicate>",
       {"bad.xml:3:", "<replicate>", "nope"}},
      {"<replicate count=\"2\">\n<joint/>\n</replicate>",
       {"bad.xml:4:", "<joint>", "world body cannot have joints"}},
      // names made equal by the suffixes
      {"<replicate count=\"2\">\n<geom name=\"a1\" size=\"1\"/>\n</replicate>\n"
       "<geom name=\"a11\" size=\"1\"/>",
       {"bad.xml:", "a11"}},
      // keyframes are resized and copied by MuJoCo's attach in ways not followed yet
      {"<replicate count=\"2\">\n<geom size=\"1\"/>\n</replicate>\n</worldbody>\n"
       "<keyframe><key time=\"1\"/></keyframe>\n<worldbody>",
       {"bad.xml:3:", "<replicate>", "keyframes is not supported yet"}},
  };
  for (const BadCase& c : cases) {
    std::string xml = "<mujoco>\n<worldbody>\n" + std::string(c.body) + "\n</worldbody>\n</mujoco>";
    test_util::ExpectMessageParts(test_util::XmlLoadError(xml), c.pieces, xml);
  }
}

}  // namespace
}  // namespace simlab

namespace simlab {
namespace {

// MuJoCo's 22_humanoids attaches its humanoid inside a <replicate>: the humanoid's
// keyframes come along, their values on the first replica only (MuJoCo's first copy
// takes them, the template forgets them), every other replica at qpos0; and each
// replica brings the humanoid's two excludes (checked against MuJoCo 3.5.1: equal
// key_qpos within 1e-15, equal exclude signatures).
TEST(Replicate, AttachedKeyframesGoToTheFirstReplica) {
  const std::string folder = std::string(SIMLAB_SOURCE_DIR) + "/../shared/corpus/mujoco/model/humanoid/";
  const Model one = LoadXml(folder + "humanoid.xml");
  const Model many = LoadXml(folder + "22_humanoids.xml");
  ASSERT_EQ(many.nkey, one.nkey);
  ASSERT_EQ(many.nq, 22 * one.nq);
  EXPECT_EQ(many.nexclude, 22 * one.nexclude);
  for (int k = 0; k < many.nkey; k++) {
    const double* row = &many.key_qpos[static_cast<size_t>(k) * many.nq];
    // (the first copy's joints after its free joint: the humanoid's own key values)
    for (int i = 7; i < one.nq; i++) EXPECT_EQ(row[i], one.key_qpos[k * one.nq + i]) << k << " " << i;
    for (int i = one.nq; i < many.nq; i++) EXPECT_NEAR(row[i], many.qpos0[i], 1e-15) << k << " " << i;
  }
}

}  // namespace
}  // namespace simlab

namespace simlab {
namespace {

// MuJoCo 3.5.1 accepts <replicate prefix> and leaves the names as they are (its names
// for this model, from the oracle: b0 b1 c-0 c-1, geoms g0 g1).
TEST(Replicate, PrefixIsAcceptedAndLeavesNames) {
  const Model m = LoadXmlString(
      "<mujoco><worldbody>\n"
      "<replicate count=\"2\" offset=\".2 0 0\" prefix=\"A\">\n"
      "  <body name=\"b\" pos=\"0 0 1\"><freejoint/><geom name=\"g\" size=\".1\"/></body>\n"
      "</replicate>\n"
      "<replicate count=\"2\" offset=\".2 0 0\" sep=\"-\" prefix=\"P\">\n"
      "  <body name=\"c\" pos=\"0 1 1\"><freejoint/><geom size=\".1\"/></body>\n"
      "</replicate>\n"
      "</worldbody></mujoco>\n",
      "prefix.xml");
  EXPECT_EQ(m.body_names, (std::vector<std::string>{"world", "b0", "b1", "c-0", "c-1"}));
  EXPECT_EQ(m.geom_names[0], "g0");
  EXPECT_EQ(m.geom_names[1], "g1");
}

}  // namespace
}  // namespace simlab
