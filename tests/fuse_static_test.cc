// <compiler fusestatic="true">: bodies without joints merge into their parents, and the
// model simulates as the unfused one. (Every compiled field of two richer models is
// compared with MuJoCo's in compiler_conformance_test.cc, CompilerConformance.FuseStatic.)
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab {
namespace {

// A hinged body with a static child of two colliding spheres, fused or not; `extra`
// goes after the worldbody.
std::string HingeWithStaticChild(bool fuse, const std::string& child_name = "",
                                 const std::string& child_extra = "",
                                 const std::string& extra = "") {
  std::string name = child_name.empty() ? "" : " name=\"" + child_name + "\"";
  return std::string("<mujoco><compiler fusestatic=\"") + (fuse ? "true" : "false") +
         "\"/><worldbody><body><joint axis=\"1 0 0\"/>"
         "<geom size=\"0.5\" pos=\"1 0 0\" contype=\"0\" conaffinity=\"0\"/>"
         "<body" + name + "><geom size=\"0.5\" pos=\"0 1 0\"/><geom size=\"0.5\" pos=\"0 -2 0\"/>" +
         child_extra + "</body></body></worldbody>" + extra + "</mujoco>";
}

TEST(FuseStatic, FusedModelSimulatesAsTheUnfusedOne) {
  Model fused = LoadXmlString(HingeWithStaticChild(true), "fused.xml");
  Model unfused = LoadXmlString(HingeWithStaticChild(false), "unfused.xml");
  EXPECT_EQ(fused.nbody, 2);
  EXPECT_EQ(unfused.nbody, 3);
  EXPECT_EQ(fused.body_contype[1], 1);
  EXPECT_EQ(fused.body_conaffinity[1], 1);
  EXPECT_EQ(fused.body_bvhnum[1], 3);
  EXPECT_EQ(unfused.body_bvhnum[2], 3);

  // The same motion: the child's mass and inertia are now the parent's.
  Data a = MakeData(fused), b = MakeData(unfused);
  for (int i = 0; i < 50; i++) {
    Step(fused, a);
    Step(unfused, b);
  }
  EXPECT_NE(a.qvel[0], 0);
  EXPECT_NEAR(a.qvel[0], b.qvel[0], 1e-8);
  EXPECT_NEAR(a.qpos[0], b.qpos[0], 1e-9);
}

TEST(FuseStatic, BodiesNamedElsewhereAreKept) {
  // A name nobody uses does not keep a body.
  EXPECT_EQ(LoadXmlString(HingeWithStaticChild(true, "free"), "a.xml").nbody, 2);
  // An adhesion actuator, a light's target and a force sensor's site do.
  std::string adhesion = "<actuator><adhesion body=\"held\" ctrlrange=\"0 1\"/></actuator>";
  EXPECT_EQ(LoadXmlString(HingeWithStaticChild(true, "held", "", adhesion), "b.xml").nbody, 3);
  std::string light = "<worldbody><light mode=\"targetbody\" target=\"held\"/></worldbody>";
  EXPECT_EQ(LoadXmlString(HingeWithStaticChild(true, "held", "", light), "c.xml").nbody, 3);
  std::string force = "<sensor><force site=\"s\"/></sensor>";
  EXPECT_EQ(LoadXmlString(HingeWithStaticChild(true, "held", "<site name=\"s\"/>", force), "d.xml").nbody, 3);
}

TEST(FuseStatic, ElementsMoveToTheParent) {
  std::string xml = HingeWithStaticChild(
      true, "", "<site name=\"s\" pos=\"0 0 1\"/><camera name=\"c\"/><light name=\"l\"/>");
  Model m = LoadXmlString(xml, "e.xml");
  ASSERT_EQ(m.nbody, 2);
  EXPECT_EQ(m.ngeom, 3);
  EXPECT_EQ(m.site_bodyid[0], 1);
  EXPECT_EQ(m.cam_bodyid[0], 1);
  EXPECT_EQ(m.light_bodyid[0], 1);
  // Geoms keep their place in the world.
  Data d = MakeData(m);
  Forward(m, d);
  EXPECT_NEAR(d.geom_xpos[3 * 2 + 1], -2, 1e-12);
}

}  // namespace
}  // namespace simlab
