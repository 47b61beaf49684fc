// Equality constraints outside the compiled fields (which the compiler conformance test
// checks against MuJoCo): names, eq_active in Data and its resets, and the MuJoCo test
// models with equality constraints loading and stepping.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab {
namespace {

std::string Local(const std::string& rel) {
  return std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/" + rel;
}

std::string Corpus(const std::string& rel) {
  return std::string(SIMLAB_SOURCE_DIR) + "/../shared/corpus/mujoco/test/engine/testdata/" + rel;
}

// Named constraints are found by name; unnamed ones are not found by "".
TEST(Equality, NameToId) {
  Model m = LoadXml(Local("equality.xml"));
  ASSERT_EQ(m.neq, 14);
  EXPECT_EQ(NameToId(m, kObjEquality, "c_bodies"), 0);
  EXPECT_EQ(NameToId(m, kObjEquality, "w_sites"), 8);
  EXPECT_EQ(NameToId(m, kObjEquality, "t_pair"), 12);
  EXPECT_EQ(NameToId(m, kObjEquality, "nope"), -1);
  EXPECT_EQ(NameToId(m, kObjEquality, ""), -1);
  EXPECT_EQ(m.eq_type[NameToId(m, kObjEquality, "j_pair")], kEqJoint);
}

// eq_active starts at eq_active0 and returns to it on every reset.
TEST(Equality, ActiveFlagsReset) {
  Model m = LoadXmlString(
      "<mujoco><worldbody><body name=\"a\"><joint name=\"j\"/><geom size=\".1\"/></body>"
      "<body name=\"b\"><joint name=\"k\"/><geom size=\".1\"/></body></worldbody>"
      "<equality><joint joint1=\"j\"/><joint joint1=\"k\" active=\"false\"/></equality>"
      "<keyframe><key qpos=\"0.1 0.2\"/></keyframe></mujoco>");
  Data d = MakeData(m);
  ASSERT_EQ(d.eq_active.size(), 2u);
  EXPECT_EQ(d.eq_active[0], 1);
  EXPECT_EQ(d.eq_active[1], 0);
  d.eq_active = {0, 1};
  ResetData(m, d);
  EXPECT_EQ(d.eq_active[0], 1);
  EXPECT_EQ(d.eq_active[1], 0);
  d.eq_active = {0, 1};
  ResetDataKeyframe(m, d, 0);
  EXPECT_EQ(d.eq_active[0], 1);
  EXPECT_EQ(d.eq_active[1], 0);
}

// MuJoCo's own test models with equality constraints load and step (their dynamics
// wait for the constraint solver, so only finiteness is checked here).
TEST(Equality, CorpusModelsLoadAndStep) {
  for (const char* rel : {"core_constraint/jdotv_connect_3d.xml", "core_constraint/soft_weld.xml",
                          "core_constraint/jdotv_weld_3d.xml", "core_constraint/jdotv_connect_2d.xml",
                          "core_constraint/dofless_weld.xml"}) {
    SCOPED_TRACE(rel);
    Model m = LoadXml(Corpus(rel));
    EXPECT_GT(m.neq, 0);
    Data d = MakeData(m);
    for (int i = 0; i < 10; i++) Step(m, d);
    for (double q : d.qpos) EXPECT_TRUE(std::isfinite(q));
  }
}

}  // namespace
}  // namespace simlab
