// Meshes: what the compiler goldens (tests/meshes, MuJoCo 3.5.1) cannot show — ASCII
// STL (which MuJoCo refuses) against the same binary STL, the shape of the convex-hull
// graph, and bad input reported at the <mesh> or <geom> line.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using test_util::ExpectMessageParts;
using test_util::XmlLoadError;

std::string MeshDir() { return std::string(SIMLAB_SOURCE_DIR) + "/tests/meshes/assets"; }

// A model (loaded as if it were a file in tests/meshes) with the given assets and one
// free body holding `geoms`.
Model LoadWithMeshes(const std::string& assets, const std::string& geoms) {
  std::string xml = "<mujoco>\n<compiler meshdir=\"" + MeshDir() + "\"/>\n<asset>\n" + assets +
                    "\n</asset>\n<worldbody>\n<body><freejoint/>" + geoms +
                    "</body>\n</worldbody>\n</mujoco>";
  return LoadXmlString(xml, std::string(SIMLAB_SOURCE_DIR) + "/tests/meshes/inline.xml");
}

void ExpectMeshError(const std::string& assets, const std::string& geoms,
                     const std::vector<std::string>& parts) {
  std::string xml = "<mujoco>\n<compiler meshdir=\"" + MeshDir() + "\"/>\n<asset>\n" + assets +
                    "\n</asset>\n<worldbody>\n<body><freejoint/>" + geoms +
                    "</body>\n</worldbody>\n</mujoco>";
  ExpectMessageParts(XmlLoadError(xml), parts, xml);
}

// ASCII STL reads to the same compiled mesh as the binary file it was written from.
TEST(Mesh, AsciiStlMatchesBinary) {
  Model m = LoadWithMeshes("<mesh name=\"bin\" file=\"box.stl\"/><mesh name=\"txt\" file=\"box_ascii.stl\"/>",
                           "<geom type=\"mesh\" mesh=\"bin\"/><geom type=\"mesh\" mesh=\"txt\"/>");
  ASSERT_EQ(m.nmesh, 2);
  EXPECT_EQ(m.mesh_vertnum[0], 8);  // 36 corners merged into 8 vertices
  EXPECT_EQ(m.mesh_vertnum[0], m.mesh_vertnum[1]);
  EXPECT_EQ(m.mesh_facenum[0], m.mesh_facenum[1]);
  for (int i = 0; i < 3 * m.mesh_vertnum[0]; i++) {
    EXPECT_NEAR(m.mesh_vert[i], m.mesh_vert[3 * m.mesh_vertadr[1] + i], 1e-7) << i;
  }
  for (int k = 0; k < 3; k++) EXPECT_NEAR(m.mesh_pos[k], m.mesh_pos[3 + k], 1e-7);
  EXPECT_NEAR(m.geom_rbound[0], m.geom_rbound[1], 1e-7);
}

// The hull graph of a box: 8 vertices with 3..6 neighbours each, 12 outward triangles,
// and vertices centred on the mass centre (a box is its own hull).
TEST(Mesh, HullGraphOfABox) {
  Model m = LoadWithMeshes("<mesh name=\"box\" file=\"box.stl\"/>", "<geom type=\"mesh\" mesh=\"box\"/>");
  ASSERT_EQ(m.mesh_graphadr[0], 0);
  const int* g = m.mesh_graph.data();
  int numvert = g[0], numface = g[1];
  EXPECT_EQ(numvert, 8);
  EXPECT_EQ(numface, 12);
  EXPECT_EQ(m.nmeshgraph, 2 + 3 * numvert + 6 * numface);
  const int* edges = g + 2 + 2 * numvert;
  int separators = 0;
  for (int i = 0; i < numvert + 3 * numface; i++) separators += edges[i] == -1;
  EXPECT_EQ(separators, numvert);

  // Each hull triangle's normal points away from the centre (the origin after centring).
  const int* faces = g + 2 + 3 * numvert + 3 * numface;
  for (int f = 0; f < numface; f++) {
    const double* a = &m.mesh_vert[3 * faces[3 * f]];
    const double* b = &m.mesh_vert[3 * faces[3 * f + 1]];
    const double* c = &m.mesh_vert[3 * faces[3 * f + 2]];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    EXPECT_GT(n[0] * a[0] + n[1] * a[1] + n[2] * a[2], 0) << "face " << f;
  }
}

// A visual-only mesh geom (no collisions) gets no hull.
// The hull's flat sides as polygons (multiccd): a cube's six quads with MuJoCo 3.5.1's
// vertex paths in its order (printed from the oracle's mesh_polyvert: by normal, +x +y +z
// -z -y -x), unit normals along the axes, and every corner in three of them.
TEST(Mesh, CubePolygons) {
  Model m = LoadXmlString(
      "<mujoco><asset><mesh name='box' vertex='-1 -1 -1 1 -1 -1 1 1 -1 1 1 1 1 -1 1 -1 1 -1 -1 1 1 -1 -1 1'/>"
      "</asset><worldbody><body><freejoint/><geom type='mesh' mesh='box'/></body></worldbody></mujoco>");
  ASSERT_EQ(m.mesh_polynum[0], 6);
  std::vector<std::vector<int>> ours, mujoco = {{3, 4, 1, 2}, {6, 3, 2, 5}, {4, 3, 6, 7},
                                                {5, 2, 1, 0}, {4, 7, 0, 1}, {6, 5, 0, 7}};
  for (int p = 0; p < 6; p++) {
    ASSERT_EQ(m.mesh_polyvertnum[p], 4);
    int adr = m.mesh_polyvertadr[p];
    ours.emplace_back(m.mesh_polyvert.begin() + adr, m.mesh_polyvert.begin() + adr + 4);
    const double* n = &m.mesh_polynormal[3 * p];
    EXPECT_NEAR(std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]), 1.0, 1e-12);
    // (the normal points away from the centre, through the first corner's side)
    const double* v = &m.mesh_vert[3 * ours.back()[0]];
    EXPECT_GT(n[0] * v[0] + n[1] * v[1] + n[2] * v[2], 0);
  }
  EXPECT_EQ(ours, mujoco);
  for (int v = 0; v < 8; v++) EXPECT_EQ(m.mesh_polymapnum[v], 3);
}

// A mesh without a hull gets the polygons of its own triangles (MuJoCo 3.5.1 makes them
// from the faces then): a box's 12 triangles make its 6 sides.
TEST(Mesh, PolygonsWithoutHull) {
  Model m = LoadWithMeshes("<mesh name=\"box\" file=\"box.stl\"/>",
                           "<geom type=\"mesh\" mesh=\"box\" contype=\"0\" conaffinity=\"0\"/>");
  ASSERT_EQ(m.nmeshgraph, 0);
  EXPECT_EQ(m.mesh_polynum[0], 6);
}

TEST(Mesh, NoHullWithoutCollisions) {
  Model m = LoadWithMeshes("<mesh name=\"box\" file=\"box.stl\"/>",
                           "<geom type=\"mesh\" mesh=\"box\" contype=\"0\" conaffinity=\"0\"/>");
  EXPECT_EQ(m.mesh_graphadr[0], -1);
  EXPECT_EQ(m.nmeshgraph, 0);
}

// An unnamed mesh is named after its file; geoms refer to it by that name.
TEST(Mesh, NamedAfterFile) {
  Model m = LoadWithMeshes("<mesh file=\"prism.obj\"/>", "<geom type=\"mesh\" mesh=\"prism\"/>");
  EXPECT_EQ(m.NameToId(kObjMesh, "prism"), 0);
  EXPECT_EQ(m.geom_dataid[0], 0);
}

TEST(Mesh, BadInputNamesTheLine) {
  ExpectMeshError("<mesh name=\"gone\" file=\"missing.stl\"/>", "<geom type=\"mesh\" mesh=\"gone\"/>",
                  {"bad.xml:4:", "<mesh name=\"gone\">", "cannot open mesh file", "missing.stl"});
  ExpectMeshError("<mesh name=\"ply\" file=\"box.ply\"/>", "<geom type=\"mesh\" mesh=\"ply\"/>",
                  {"bad.xml:4:", "unknown or unsupported mesh file"});
  ExpectMeshError("<mesh name=\"few\" vertex=\"0 0 0 1 0 0 0 1 0\"/>", "<geom type=\"mesh\" mesh=\"few\"/>",
                  {"bad.xml:4:", "at least 4 vertices"});
  ExpectMeshError("<mesh name=\"odd\" vertex=\"0 0 0 1 0 0 0 1 0 0 0\"/>", "",
                  {"bad.xml:4:", "multiple of 3"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\" face=\"0 1 7\"/>", "",
                  {"bad.xml:4:", "vertex index 7 does not exist"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\" face=\"0 1 x\"/>", "",
                  {"bad.xml:4:", "bad number 'x' in 'face'"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\" maxhullvert=\"3\"/>", "",
                  {"bad.xml:4:", "maxhullvert must be larger than 3"});
  ExpectMeshError("<mesh name=\"flat\" vertex=\"0 0 0 1 0 0 0 1 0 1 1 0\"/>", "<geom type=\"mesh\" mesh=\"flat\"/>",
                  {"bad.xml:4:", "<mesh name=\"flat\">", "qhull error"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/>",
                  "<geom type=\"mesh\" mesh=\"other\"/>", {"bad.xml:7:", "unknown mesh 'other'"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/>", "<geom type=\"mesh\"/>",
                  {"bad.xml:7:", "a mesh geom needs a mesh"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/>",
                  "<geom type=\"mesh\" mesh=\"t\" shellinertia=\"true\"/>",
                  {"bad.xml:7:", "inertia should be specified in the mesh asset"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/><mesh name=\"t\" file=\"box.stl\"/>",
                  "", {"bad.xml:4:", "repeated mesh name 't'"});
  ExpectMeshError("<mesh name=\"t\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/>", "<geom type=\"sdf\"/>",
                  {"bad.xml:7:", "an sdf geom needs a mesh"});
}

}  // namespace
}  // namespace simlab
