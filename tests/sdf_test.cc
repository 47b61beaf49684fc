// sdf geoms on meshes: the signed distance octree the compiler builds, and bodies
// resting on an sdf geom. (Rollouts equal to MuJoCo's to the bit are in the corpus
// conformance cases, tests/conformance/corpus/make_goldens.sh.)
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A cube of half size 0.1 as an sdf geom, and `extra` in the worldbody.
std::string CubeSdf(const std::string& extra) {
  return "<mujoco><asset><mesh name=\"cube\" vertex=\"-.1 -.1 -.1  .1 -.1 -.1  -.1 .1 -.1  "
         ".1 .1 -.1  -.1 -.1 .1  .1 -.1 .1  -.1 .1 .1  .1 .1 .1\"/></asset><worldbody>"
         "<geom name=\"rock\" type=\"sdf\" mesh=\"cube\"/>" +
         extra + "</worldbody></mujoco>";
}

TEST(Sdf, OctreeHoldsSignedDistances) {
  Model m = LoadXmlString(CubeSdf(""), "cube.xml");
  ASSERT_GT(m.noct, 1);
  EXPECT_EQ(m.mesh_octadr[0], 0);
  EXPECT_EQ(m.mesh_octnum[0], m.noct);
  // The root cell: the mesh's box enlarged by 10% (the vertices read in single
  // precision, as MuJoCo reads them).
  const double half = static_cast<float>(0.1);
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(m.oct_aabb[k], 0, 1e-15);
    EXPECT_NEAR(m.oct_aabb[3 + k], 1.1 * half, 1e-15);
  }
  // Its corners lie 0.1 half outside the cube along each axis.
  for (int j = 0; j < 8; j++) EXPECT_NEAR(m.oct_coeff[j], 0.1 * half * std::sqrt(3.0), 1e-15);
  // Every cell's corner values: the distance to the cube's surface (negative inside).
  for (int c = 0; c < m.noct; c++) {
    const double* box = &m.oct_aabb[6 * c];
    for (int j = 0; j < 8; j++) {
      double p[3], outside[3], inside = -1e9;
      for (int k = 0; k < 3; k++) {
        p[k] = box[k] + ((j >> k) & 1 ? 1 : -1) * box[3 + k];
        double q = std::abs(p[k]) - half;
        outside[k] = std::max(q, 0.0);
        inside = std::max(inside, q);
      }
      double norm = std::sqrt(outside[0] * outside[0] + outside[1] * outside[1] + outside[2] * outside[2]);
      double exact = norm > 0 ? norm : inside;
      // (hanging corners are averages of their coarser neighbours': near, not equal)
      EXPECT_NEAR(m.oct_coeff[8 * c + j], exact, 0.011) << "cell " << c << " corner " << j;
    }
  }
}

TEST(Sdf, BodiesRestOnAnSdfGeom) {
  // A ball and a box dropped on the cube come to rest on its top face.
  Model m = LoadXmlString(CubeSdf("<body pos=\"0.02 0 0.3\"><freejoint/><geom name=\"ball\" size=\".03\"/></body>"
                                  "<body pos=\"-0.04 0.03 0.5\"><freejoint/><geom name=\"crate\" type=\"box\" size=\".03 .02 .01\"/></body>"),
                          "rest.xml");
  Data d = MakeData(m);
  for (int i = 0; i < 1500; i++) Step(m, d);
  EXPECT_NEAR(d.qpos[2], 0.1 + 0.03, 2e-3);
  EXPECT_GT(d.qpos[9], 0.1);
  EXPECT_LT(std::abs(d.qvel[2]), 1e-2);
  int rock = 0, found = 0;
  for (int i = 0; i < d.ncon; i++) {
    const Contact& c = d.contact[i];
    if (c.geom[1] != rock && c.geom[0] != rock) continue;
    found++;
    EXPECT_GT(std::abs(c.frame[2]), 0.9) << "contact normals are vertical on the top face";
  }
  EXPECT_GT(found, 0);
}

TEST(Sdf, HeightFieldPairsAreRefused) {
  std::string xml =
      "<mujoco><asset><mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/>"
              "<hfield name=\"h\" nrow=\"2\" ncol=\"2\" size=\"1 1 .1 .1\"/></asset>\n<worldbody>\n"
              "<geom type=\"hfield\" hfield=\"h\"/>\n<body><freejoint/>\n<geom type=\"sdf\" mesh=\"t\"/></body>"
              "</worldbody></mujoco>";
  test_util::ExpectMessageParts(
      test_util::XmlLoadError(xml),
      {"bad.xml:5:", "collisions between sdf geoms and hfield geoms are not supported yet"}, xml);
}

}  // namespace
}  // namespace simlab
