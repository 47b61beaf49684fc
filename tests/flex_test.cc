// Flexes: what a <flexcomp> expands into, how the edge equality holds a cloth, and clear
// errors for flexes and flexcomps that cannot be built. (Agreement with MuJoCo is in the
// conformance goldens: tests/conformance/flex_cases.txt, and the compiler's flex fields
// in CompilerConformance.Flexes.)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/sleep.h"
#include "load_error.h"
#include "simlab/simlab.h"
#include "simlab/support.h"

namespace simlab {
namespace {

using test_util::ExpectMessageParts;
using test_util::XmlLoadError;

// A model with one flexcomp (attributes and children as given) in a body named "b".
std::string Flexcomp(const std::string& attrs, const std::string& children = "") {
  return "<mujoco><worldbody><body name='b' pos='0 0 1'><flexcomp name='f' " + attrs + ">" +
         children + "</flexcomp></body></worldbody></mujoco>";
}

// A 3 x 2 grid: a body per point (f_0 ... f_5) with three orthogonal sliders, the
// flexcomp's mass shared equally, a flex of 4 triangles and 9 edges on those bodies.
TEST(Flex, GridExpandsIntoBodiesAndSliders) {
  Model m = LoadXmlString(Flexcomp("type='grid' count='3 2 1' spacing='.1 .1 .1' mass='6'"), "grid.xml");
  ASSERT_EQ(m.nflex, 1);
  EXPECT_EQ(m.nbody, 2 + 6);
  EXPECT_EQ(m.njnt, 18);
  EXPECT_EQ(m.flex_vertnum[0], 6);
  EXPECT_EQ(m.flex_elemnum[0], 4);
  EXPECT_EQ(m.flex_edgenum[0], 9);
  EXPECT_EQ(m.flex_dim[0], 2);
  for (int i = 0; i < 6; i++) {
    int body = m.flex_vertbodyid[i];
    EXPECT_EQ(m.body_names[body], "f_" + std::to_string(i));
    EXPECT_DOUBLE_EQ(m.body_mass[body], 1.0);
    EXPECT_EQ(m.body_jntnum[body], 3);
    EXPECT_EQ(m.jnt_type[m.body_jntadr[body]], kJointSlide);
  }
  // The grid is centred on the parent: the first point at (-0.1, -0.05, 0).
  EXPECT_NEAR(m.body_pos[3 * m.flex_vertbodyid[0]], -0.1, 1e-15);
  EXPECT_NEAR(m.body_pos[3 * m.flex_vertbodyid[0] + 1], -0.05, 1e-15);
}

// Pinned points stay in the parent body; a fully pinned flexcomp is rigid.
TEST(Flex, PinnedPointsStayInTheParent) {
  Model m = LoadXmlString(Flexcomp("type='grid' count='3 3 1' spacing='.1 .1 .1'",
                                   "<pin id='0 8'/>"), "pin.xml");
  EXPECT_EQ(m.nbody, 2 + 7);
  EXPECT_EQ(m.body_names[m.flex_vertbodyid[0]], "b");
  EXPECT_EQ(m.body_names[m.flex_vertbodyid[8]], "b");
  Model rigid = LoadXmlString(Flexcomp("type='grid' count='3 3 1' spacing='.1 .1 .1' rigid='true'"),
                              "rigid.xml");
  EXPECT_EQ(rigid.nbody, 2);
  EXPECT_EQ(rigid.flex_rigid[0], 1);
}

// A cloth held by its edge equality keeps its edges near their rest lengths while it
// hangs from a pinned row, and the simulation stays finite.
TEST(Flex, EdgeEqualityHoldsAHangingCloth) {
  std::string xml = "<mujoco><option solver='CG' tolerance='1e-8'/><worldbody><body name='b' pos='0 0 1'>"
                    "<flexcomp name='f' type='grid' count='5 5 1' spacing='.05 .05 .05' radius='.001'>"
                    "<edge equality='true'/><pin gridrange='0 0 0 4'/></flexcomp>"
                    "</body></worldbody></mujoco>";
  Model m = LoadXmlString(xml, "cloth.xml");
  ASSERT_EQ(m.neq, 1);
  EXPECT_EQ(m.eq_type[0], kEqFlex);
  Data d = MakeData(m);
  for (int i = 0; i < 500; i++) Step(m, d);
  double worst = 0;
  for (int e = 0; e < m.nflexedge; e++) {
    ASSERT_TRUE(std::isfinite(d.flexedge_length[e]));
    worst = std::max(worst, std::abs(d.flexedge_length[e] - m.flexedge_length0[e]));
  }
  EXPECT_LT(worst, 0.005);  // soft constraints: millimetres on 5 cm edges
  // The free corner fell: it hangs below the pinned row.
  int corner = m.flex_vertadr[0] + 24;
  EXPECT_LT(d.flexvert_xpos[3 * corner + 2], 0.95);
}

// Flexes and flexcomps that cannot be built: file, line, element and what is wrong.
// Two tetrahedra at the ends of a 4 x 1 x 1 box, trilinear on cellcount='4 1 1': a
// lattice of 5 x 2 x 2 nodes over the box. The middle cells hold no element, so the
// nodes that only they hold (x = 2) stay in the parent; the others get bodies sharing
// the mass. Elastic cells get a 24 x 24 stiffness each, empty ones none (MuJoCo 3.12).
std::string CellFlexcomp(const std::string& attrs, const std::string& children = "") {
  return Flexcomp("type='direct' dim='3' dof='trilinear' mass='1.6' radius='.01' " + attrs +
                      " point='0 0 0  .9 0 0  0 1 0  0 0 1  4 1 1  3.1 1 1  4 0 1  4 1 0'"
                      " element='0 1 2 3  4 5 6 7'",
                  "<contact selfcollide='none'/>" + children);
}

TEST(Flex, CellcountLatticePinsNodesOfEmptyCells) {
  Model m = LoadXmlString(CellFlexcomp("cellcount='4 1 1'", "<elasticity young='100' poisson='0.3'/>"),
                          "cells.xml");
  ASSERT_EQ(m.nflex, 1);
  EXPECT_EQ(m.flex_cellnum[0], 4);
  EXPECT_EQ(m.flex_cellnum[1], 1);
  EXPECT_EQ(m.flex_cellnum[2], 1);
  EXPECT_EQ(m.flex_interp[0], 1);
  ASSERT_EQ(m.flex_nodenum[0], 5 * 2 * 2);
  for (int i = 0; i < 5; i++) {
    for (int j = 0; j < 2; j++) {
      for (int k = 0; k < 2; k++) {
        int body = m.flex_nodebodyid[(i * 2 + j) * 2 + k];
        std::string name = "f_" + std::to_string(i) + "_" + std::to_string(j) + "_" + std::to_string(k);
        EXPECT_EQ(m.body_names[body], i == 2 ? "b" : name);
        if (i != 2) EXPECT_DOUBLE_EQ(m.body_mass[body], 0.1);  // 1.6 over 16 nodes
      }
    }
  }
  EXPECT_EQ(m.nbody, 2 + 16);
  EXPECT_EQ(m.flex_centered[0], 0);
  // A pinned node sits at its place in the parent: (2, 0, 0) of the box.
  EXPECT_DOUBLE_EQ(m.flex_node[3 * 8], 2.0);
  // The stiffness of four cells, zero in the two empty ones.
  ASSERT_EQ(m.nflexstiffness, 4 * 24 * 24);
  EXPECT_EQ(m.flex_stiffnessadr[0], 0);
  for (int cell = 0; cell < 4; cell++) {
    double first = m.flex_stiffness[cell * 24 * 24];
    if (cell == 1 || cell == 2) {
      EXPECT_EQ(first, 0) << cell;
    } else {
      EXPECT_LT(first, 0) << cell;  // stored negated
    }
  }
  // A vertex moves with its own cell's nodes: at rest, where it was written.
  Data d = MakeData(m);
  Forward(m, d);
  EXPECT_NEAR(d.flexvert_xpos[3 * 4 + 0], 4.0, 1e-12);
  EXPECT_NEAR(d.flexvert_xpos[3 * 4 + 2], 2.0, 1e-12);  // z 1 in b at height 1
}

// A shell (2D elasticity on an interpolated flex): the lattice's interior nodes stay in
// the parent, flex_interp is -order, each of the 24 boundary faces of 2 x 2 x 2 cells gets
// a 12 x 12 membrane stiffness, and the 48 edges between faces their bending.
TEST(Flex, CellcountShellPinsTheInterior) {
  Model m = LoadXmlString(
      CellFlexcomp("cellcount='2 2 2'", "<elasticity young='100' poisson='0.3' elastic2d='bend' thickness='.1'/>"),
      "shell.xml");
  EXPECT_EQ(m.flex_interp[0], -1);
  ASSERT_EQ(m.flex_nodenum[0], 27);
  for (int n = 0; n < 27; n++) {
    EXPECT_EQ(m.body_names[m.flex_nodebodyid[n]] == "b", n == 13) << n;  // (1, 1, 1)
  }
  EXPECT_EQ(m.nflexstiffness, 24 * 12 * 12);
  ASSERT_GE(m.flex_bendingadr[0], 0);
  EXPECT_EQ(m.flex_bending[m.flex_bendingadr[0]], 48);
  EXPECT_EQ(m.nflexbending, 1 + 48 * 10);
}

TEST(Flex, BadFlexesAreClearErrors) {
  struct Case {
    std::string xml;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {Flexcomp("type='grid' count='0 2 1'"), {"bad.xml:1", "flexcomp", "Count too small"}},
      {Flexcomp("type='grid' count='3 3 1' dim='4'"), {"Invalid dim"}},
      {Flexcomp("type='grid' count='3 3 1' spacing='.001 .001 .001'"),
       {"Spacing must be larger than geometry size"}},
      {Flexcomp("type='box' count='3 1 3' spacing='.1 .1 .1'"), {"Count too small"}},
      {Flexcomp("type='direct' point='0 0 0 1 0 0' element='0 5' dim='1'"),
       {"element 1 has point id 5, number of points is 2"}},
      {Flexcomp("type='grid' count='100000 100000 100000'"), {"count=", "budget"}},
      {Flexcomp("type='grid' count='3 3 1'", "<pin id='99'/>"), {"pinid out of range"}},
      {Flexcomp("type='grid' count='3 3 1'", "<edge equality='true'/><elasticity young='1' elastic2d='both'/>"),
       {"elasticity and edge constraints cannot both be present"}},
      {"<mujoco><deformable><flex name='x' dim='2' body='nobody nobody nobody' element='0 1 2'/></deformable></mujoco>",
       {"unknown body 'nobody' in flex"}},
      {"<mujoco><worldbody><body name='a'/></worldbody><deformable>"
       "<flex name='x' dim='2' body='a a a' element='0 1 1'/></deformable></mujoco>",
       {"repeated vertex in element"}},
      {"<mujoco><worldbody><body name='a'/></worldbody><deformable>"
       "<flex name='x' dim='2' body='a' vertex='0 0 0 1 0 0 0 1 0' element='0 1 2'/></deformable>"
       "<equality><flex flex='x'/></equality></mujoco>",
       {"rigid flex 'x' in equality constraint"}},
      {"<mujoco><equality><flex flex='missing'/></equality></mujoco>", {"missing"}},
      {Flexcomp("type='grid' count='3 3 1' cellcount='2 2 1'"),
       {"bad.xml:1", "flexcomp", "cellcount requires dof=\"trilinear\" or \"quadratic\""}},
      {CellFlexcomp("cellcount='0 1 1'"),
       {"cellcount cannot be 0 in any dimension when interpolation order > 0"}},
      {CellFlexcomp("cellcount='2 -1 1'"), {"cellcount must be positive"}},
      {CellFlexcomp("cellcount='2 2'"), {"cellcount"}},
      {CellFlexcomp("cellcount='2000 2000 2000'"), {"cellcount=", "budget"}},
  };
  for (const Case& c : cases) ExpectMessageParts(XmlLoadError(c.xml), c.parts, c.xml);
}

// A <flex> interpolated on the nodes at `nodes` (x slowest, bodies n0, n1... with three
// sliders each) with its four vertices in body p, a tetrahedron, and `attrs`/`children`.
std::string NodeFlex(const std::vector<std::array<double, 3>>& nodes, const std::string& attrs,
                     const std::string& children = "") {
  std::string bodies, names;
  for (size_t n = 0; n < nodes.size(); n++) {
    char pos[96];
    std::snprintf(pos, sizeof(pos), "%g %g %g", nodes[n][0], nodes[n][1], nodes[n][2]);
    std::string name = "n" + std::to_string(n);
    bodies += "<body name='" + name + "' pos='" + pos + "'><joint type='slide' axis='1 0 0'/>"
              "<joint type='slide' axis='0 1 0'/><joint type='slide' axis='0 0 1'/>"
              "<geom size='.05' mass='.1'/></body>";
    names += (n ? " " : "") + name;
  }
  return "<mujoco><worldbody><body name='p'>" + bodies + "</body></worldbody><deformable>\n"
         "<flex name='f' dim='3' body='p p p p' vertex='.1 .1 .1  .9 .1 .1  .1 .9 .1  .1 .1 .9' "
         "element='0 1 2 3' node='" + names + "' " + attrs + ">" + children +
         "<contact selfcollide='none'/></flex></deformable></mujoco>";
}

// The nodes of a lattice of cells whose nodes lie at x = xs[i], y and z = 0 or 1.
std::vector<std::array<double, 3>> LatticeNodes(const std::vector<double>& xs, int ny = 2, int nz = 2) {
  std::vector<std::array<double, 3>> nodes;
  for (double x : xs) {
    for (int j = 0; j < ny; j++) {
      for (int k = 0; k < nz; k++) nodes.push_back({x, j / (ny - 1.0), k / (nz - 1.0)});
    }
  }
  return nodes;
}

// Interpolated flexes whose nodes do not fit their cellcount and dof, or whose shell has
// a flat face, are refused as MuJoCo 3.12 refuses them (its messages) instead of being
// simulated with nodes the interpolation does not read, a wrapped cell count or NaN
// stiffness.
TEST(Flex, BadCellFlexesAreClearErrors) {
  const auto cube = LatticeNodes({0, 1});
  const auto cube27 = LatticeNodes({0, .5, 1}, 3, 3);
  std::string flat_strain = NodeFlex(LatticeNodes({0, 1, 1}), "dof='trilinear' cellcount='2 1 1'");
  flat_strain.insert(flat_strain.rfind("</mujoco>"),
                     "<equality><flexstrain flex='f' cell='0 0 0'/></equality>");
  struct Case {
    std::string xml;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {NodeFlex(cube, "dof='trilinear' cellcount='-1 -1 1'"),
       {"bad.xml:2", "<flex name=\"f\">", "cellcount must be positive"}},
      // (3 x 3 x 954437177 is 1 modulo 2^32)
      {NodeFlex(cube, "dof='trilinear' cellcount='3 3 954437177'"),
       {"bad.xml:2", "<flex name=\"f\">", "number of nodes (8) does not match cellcount and dof"}},
      {NodeFlex(cube27, "dof='trilinear'"),
       {"bad.xml:2", "number of nodes (27) does not match cellcount and dof expected (8)"}},
      {NodeFlex(cube, "dof='quadratic'"),
       {"bad.xml:2", "number of nodes (8) does not match cellcount and dof expected (27)"}},
      {"<mujoco><worldbody><body name='p'/></worldbody><deformable>\n<flex name='f' dim='3' "
       "body='p p p p' vertex='0 0 0 1 0 0 0 1 0 0 0 1' element='0 1 2 3' dof='trilinear'/>"
       "</deformable></mujoco>",
       {"bad.xml:2", "number of nodes (0) does not match cellcount and dof expected (8)"}},
      {NodeFlex(LatticeNodes({0, 1, 1}), "dof='trilinear' cellcount='2 1 1'",
                "<elasticity young='100' poisson='.3' elastic2d='stretch' thickness='.1'/>"),
       {"bad.xml:2", "<flex name=\"f\">", "degenerate 2D element with zero extent"}},
      // (a flat cell's stiffness divides by zero: NaN, and with strain equality all its
      // NaN eigenmodes were kept, one more than its block holds)
      {NodeFlex(LatticeNodes({0, 1, 1}), "dof='trilinear' cellcount='2 1 1'",
                "<elasticity young='100' poisson='.3'/>"),
       {"bad.xml:2", "<flex name=\"f\">", "degenerate 3D element with zero extent (cell 1)"}},
      {flat_strain,
       {"bad.xml:2", "<flex name=\"f\">", "degenerate 3D element with zero extent (cell 1)"}},
  };
  for (const Case& c : cases) ExpectMessageParts(XmlLoadError(c.xml), c.parts, c.xml);

  // The same lattices with nodes that fit load.
  EXPECT_EQ(XmlLoadError(NodeFlex(cube, "dof='trilinear' cellcount='1 1 1'")), "");
  EXPECT_EQ(XmlLoadError(NodeFlex(cube27, "dof='quadratic'")), "");
  EXPECT_EQ(XmlLoadError(NodeFlex(LatticeNodes({0, 1, 2}), "dof='trilinear' cellcount='2 1 1'",
                                  "<elasticity young='100' poisson='.3' elastic2d='stretch' "
                                  "thickness='.1'/>")),
            "");
}

// Grid pins on an interpolated flexcomp that is not a grid: MuJoCo checks their
// coordinates against the node lattice (pingrid) or count (pingridrange) but pins the
// point at their place in a grid of `count` points, past its arrays when that grid is
// larger than the flexcomp's points and nodes. simlab refuses such a pin.
TEST(Flex, GridPinsPastTheFlexcompsPointsAreClearErrors) {
  auto direct = [](const std::string& attrs, const std::string& pin) {
    return Flexcomp("type='direct' dim='3' dof='trilinear' radius='.01' " + attrs +
                        " point='0 0 0 1 0 0 0 1 0 0 0 1' element='0 1 2 3'",
                    pin + "<contact selfcollide='none'/>");
  };
  struct Case {
    std::string xml;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {direct("", "<pin grid='1 1 1'/>"), {"bad.xml:1", "<flexcomp", "pingrid out of range"}},
      {direct("count='1000 1000 1000'", "<pin grid='1 1 1'/>"), {"pingrid out of range"}},
      {direct("count='100000 100000 100000'", "<pin grid='1 1 1'/>"), {"pingrid out of range"}},
      {direct("", "<pin gridrange='0 0 0 1 1 1'/>"), {"bad.xml:1", "<flexcomp", "pingridrange out of range"}},
  };
  for (const Case& c : cases) ExpectMessageParts(XmlLoadError(c.xml), c.parts, c.xml);

  // A grid pin within the points (and nodes) pins what MuJoCo pins: grid point (0 0 1)
  // of count 1 1 2 is node 1, which then stays in the parent.
  Model m = LoadXmlString(direct("count='1 1 2'", "<pin grid='0 0 1'/>"), "pin.xml");
  EXPECT_EQ(m.body_names[m.flex_nodebodyid[1]], "b");
  EXPECT_NE(m.body_names[m.flex_nodebodyid[0]], "b");
}

// A model follows MuJoCo 3.12 (Model::release) when it uses what only 3.12 defines: a
// flexcomp's cells, shell, strain equality or dof="2d", a flex's dof or cellcount, a
// flexstrain equality; otherwise 3.5.1, the oracle's.
TEST(Flex, ModelsUsingNewerConstructsFollowMuJoCo312) {
  auto release = [](const std::string& xml) { return LoadXmlString(xml, "release.xml").release; };
  EXPECT_EQ(release(Flexcomp("type='grid' count='3 3 1' spacing='.1 .1 .1'")), Release::k3_5_1);
  const std::string no_self = "<contact selfcollide='none'/>";
  EXPECT_EQ(release(Flexcomp("type='grid' count='3 3 1' spacing='.1 .1 .1' dof='trilinear'",
                             no_self)),
            Release::k3_5_1);
  EXPECT_EQ(release(Flexcomp("type='grid' count='3 3 1' spacing='.1 .1 .1' dof='2d'")),
            Release::k3_12);
  EXPECT_EQ(release(Flexcomp("type='box' count='4 4 4' spacing='.1 .1 .1' dim='3' "
                             "dof='trilinear' cellcount='2 1 1'", no_self)),
            Release::k3_12);
  EXPECT_EQ(release(Flexcomp("type='box' count='4 4 4' spacing='.1 .1 .1' dim='3' "
                             "dof='trilinear'", no_self + "<edge equality='strain'/>")),
            Release::k3_12);
}

// A bending cloth pinned to a static body: MuJoCo 3.5.1 refuses it, 3.12 accepts it (the
// pins carry the bending forces), so such a model follows 3.12. Pinned to a moving
// body it is refused, with the message of the release the model follows.
TEST(Flex, BendingClothPinnedToAStaticBodyFollowsMuJoCo312) {
  // A cloth in body `name` at x, hinged or not, pinned along one side.
  auto cloth = [](const std::string& name, int x, bool hinged) {
    return "<body name='" + name + "' pos='" + std::to_string(x) + " 0 1'>" +
           (hinged ? "<joint type='hinge'/><geom size='.01'/>" : "") + "<flexcomp name='" + name +
           "' type='grid' count='4 4 1' spacing='.05 .05 .05' radius='.005' dim='2'>"
           "<elasticity young='3e4' poisson='.2' thickness='.01' elastic2d='bend'/>"
           "<pin id='0 4 8 12'/><contact selfcollide='none'/></flexcomp></body>";
  };
  auto model = [](const std::string& bodies) {
    return "<mujoco><worldbody>" + bodies + "</worldbody></mujoco>";
  };
  EXPECT_EQ(LoadXmlString(model(cloth("a", 0, false)), "pinned.xml").release, Release::k3_12);
  std::string hinged = model(cloth("b", 1, true));
  ExpectMessageParts(XmlLoadError(hinged), {"bad.xml", "pins are not supported for bending"}, hinged);
  std::string both = model(cloth("a", 0, false) + cloth("b", 1, true));
  ExpectMessageParts(XmlLoadError(both),
                     {"bad.xml", "pinned flex vertices with bending require a static (jointless) "
                                 "pin body, body 'b' has joints"},
                     both);
}

// A cloth laid flat on the floor touches it at every vertex: a 3.5.1 model keeps every
// contact, a 3.12 model (made one here by dof="2d") keeps kMaxContactPair of them per
// collision pair.
TEST(Flex, MuJoCo312ModelsThinFlexContactsPerPair) {
  auto contacts = [](const std::string& extra) {
    std::string xml = "<mujoco><worldbody><geom type='plane' size='1 1 .1'/>"
                      "<flexcomp name='f' type='grid' count='9 9 1' spacing='.02 .02 .02' "
                      "radius='.01' pos='0 0 .005' " + extra + "><contact selfcollide='none'/>"
                      "</flexcomp></worldbody></mujoco>";
    Model m = LoadXmlString(xml, "thin.xml");
    Data d = MakeData(m);
    Forward(m, d);
    return std::make_pair(m.release, d.ncon);
  };
  auto [old_release, all] = contacts("");
  EXPECT_EQ(old_release, Release::k3_5_1);
  EXPECT_EQ(all, 81);
  auto [new_release, thinned] = contacts("dof='2d'");
  EXPECT_EQ(new_release, Release::k3_12);
  EXPECT_EQ(thinned, 50);
}

// dof='2d': a body per point with two sliders, along its parent's x and y. Under a
// parent turned 90 degrees about x the sheet's plane holds the world's z: the cloth,
// pinned along one row, falls in that plane and never leaves it.
TEST(Flex, PlanarFlexcompSlidesInItsParentsPlane) {
  std::string xml = "<mujoco><worldbody><body name='b' pos='0 0 1' euler='90 0 0'>"
                    "<flexcomp name='f' type='grid' count='3 3 1' spacing='.05 .05 .05' "
                    "radius='.001' dof='2d'><edge equality='true'/><pin id='2 5 8'/>"
                    "</flexcomp></body></worldbody></mujoco>";
  Model m = LoadXmlString(xml, "planar.xml");
  EXPECT_EQ(m.nbody, 2 + 6);
  EXPECT_EQ(m.njnt, 12);
  for (int v : {0, 1, 3, 4, 6, 7}) {
    int body = m.flex_vertbodyid[v];
    ASSERT_EQ(m.body_jntnum[body], 2);
    EXPECT_EQ(m.body_simple[body], 2);  // a point mass on sliders (MuJoCo's simple 2)
    for (int j = 0; j < 2; j++) {
      int joint = m.body_jntadr[body] + j;
      EXPECT_EQ(m.jnt_type[joint], kJointSlide);
      for (int k = 0; k < 3; k++) EXPECT_EQ(m.jnt_axis[3 * joint + k], k == j ? 1 : 0);
    }
  }
  Data d = MakeData(m);
  for (int i = 0; i < 300; i++) Step(m, d);
  for (int v = 0; v < m.flex_vertnum[0]; v++) {
    EXPECT_NEAR(d.flexvert_xpos[3 * v + 1], 0, 1e-12) << v;  // the parent's z: world -y
  }
  EXPECT_LT(d.flexvert_xpos[3 * 0 + 2], 1 - 0.01);  // the free side fell
}

// The elastic forces on a 2d sheet's point masses (taken in their bodies' frame) equal
// the same forces through the bodies' Jacobians: the same sheet under a parent that
// slides, whose vertex bodies are not simple.
TEST(Flex, PlanarElasticForcesOnPointMassesFollowTheirFrame) {
  auto sheet = [](const std::string& joint) {
    return "<mujoco><worldbody><body name='b' pos='0 0 1' euler='90 30 0'>"
           "<inertial pos='0 0 0' mass='1' diaginertia='1 1 1'/>" + joint +
           "<flexcomp name='f' type='grid' count='3 3 1' spacing='.1 .1 .1' radius='.001' "
           "dof='2d'><elasticity young='1e3' poisson='.3' thickness='.01' elastic2d='stretch'/>"
           "</flexcomp></body></worldbody></mujoco>";
  };
  Model simple = LoadXmlString(sheet(""), "simple.xml");
  Model moving = LoadXmlString(sheet("<joint type='slide' axis='0 0 1'/>"), "moving.xml");
  int body = simple.flex_vertbodyid[4];
  ASSERT_EQ(simple.body_simple[body], 2);
  ASSERT_EQ(moving.body_simple[moving.flex_vertbodyid[4]], 0);
  Data a = MakeData(simple), b = MakeData(moving);
  // Stretch the middle vertex; the moving model's dofs follow the parent's one.
  int q = simple.jnt_qposadr[simple.body_jntadr[body]];
  for (auto [data, shift] : {std::pair<Data*, int>{&a, 0}, {&b, 1}}) {
    data->qpos[q + shift] += 0.01;
    data->qpos[q + shift + 1] -= 0.02;
  }
  Forward(simple, a);
  Forward(moving, b);
  double largest = 0;
  for (int v = 0; v < simple.nv; v++) {
    largest = std::max(largest, std::abs(a.qfrc_spring[v]));
    EXPECT_NEAR(a.qfrc_spring[v], b.qfrc_spring[v + 1], 1e-9) << v;
  }
  EXPECT_GT(largest, 1e-3);
}

// Strain equality on a trilinear cube (MuJoCo 3.12): one flexstrain for its one cell,
// a row per stiff mode of the cell's stiffness (24 node dofs less 6 rigid motions; 75
// for the 27 quadratic nodes). Stretched by a fifth along x, the rows pull it back to
// its rest shape.
TEST(Flex, StrainEqualityPullsAStretchedBoxBack) {
  auto cube = [](const char* dof) {
    return std::string("<mujoco><option gravity='0 0 0'/><worldbody><body name='b'>"
                       "<flexcomp name='f' type='grid' count='2 2 2' spacing='.1 .1 .1' dim='3' "
                       "radius='.001' dof='") +
           dof + "'><edge equality='strain'/><contact selfcollide='none'/></flexcomp>"
                 "</body></worldbody></mujoco>";
  };
  Model quadratic = LoadXmlString(cube("quadratic"), "quadratic.xml");
  Data dq = MakeData(quadratic);
  Forward(quadratic, dq);
  EXPECT_EQ(dq.ne, 75);

  Model m = LoadXmlString(cube("trilinear"), "strain.xml");
  ASSERT_EQ(m.neq, 1);
  EXPECT_EQ(m.eq_type[0], kEqFlexStrain);
  EXPECT_EQ(m.flex_edgeequality[0], 3);
  Data d = MakeData(m);
  Forward(m, d);
  ASSERT_EQ(d.ne, 18);
  for (int r = 0; r < d.ne; r++) EXPECT_NEAR(d.efc_pos[r], 0, 1e-12);

  // Nodes (1, j, k) moved 2 cm along x, away from nodes (0, j, k).
  auto extent = [&](const Data& data) {
    double sum = 0;
    for (int n = 0; n < 4; n++) {
      sum += data.xpos[3 * m.flex_nodebodyid[4 + n]] - data.xpos[3 * m.flex_nodebodyid[n]];
    }
    return sum / 4;
  };
  for (int n = 4; n < 8; n++) d.qpos[m.jnt_qposadr[m.body_jntadr[m.flex_nodebodyid[n]]]] += 0.02;
  Forward(m, d);
  double stretched = 0;
  for (int r = 0; r < d.ne; r++) stretched = std::max(stretched, std::abs(d.efc_pos[r]));
  EXPECT_GT(stretched, 1e-3);
  EXPECT_NEAR(extent(d), 0.12, 1e-12);
  for (int i = 0; i < 500; i++) Step(m, d);
  Forward(m, d);
  double left = 0;
  for (int r = 0; r < d.ne; r++) left = std::max(left, std::abs(d.efc_pos[r]));
  EXPECT_LT(left, 1e-3 * stretched);
  EXPECT_NEAR(extent(d), 0.1, 1e-4);
}

// Strain equalities and planar flexcomps that cannot be built: file, line, element and
// what is wrong (MuJoCo's words where MuJoCo refuses it; MuJoCo accepts the rest and
// reads past its arrays or makes no rows).
TEST(Flex, BadStrainEqualitiesAreClearErrors) {
  const std::string trilinear =
      "type='grid' count='2 2 2' spacing='.1 .1 .1' dim='3' dof='trilinear'";
  auto with_equality = [&](const std::string& equality) {
    return "<mujoco><worldbody><body name='b'>\n<flexcomp name='f' " + trilinear +
           "><contact selfcollide='none'/></flexcomp></body></worldbody>\n<equality>\n" +
           equality + "\n</equality></mujoco>";
  };
  struct Case {
    std::string xml;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {Flexcomp("type='grid' count='3 3 1' dof='3d'"),
       {"bad.xml:1", "<flexcomp", "dof", "invalid keyword '3d'", "2d"}},
      {Flexcomp("type='grid' count='3 3 1'", "<edge equality='strain'/>"),
       {"bad.xml:1", "<flexcomp", "strain equality needs an interpolated flexcomp"}},
      {Flexcomp(trilinear,
                "<edge equality='strain'/><elasticity young='10'/><contact selfcollide='none'/>"),
       {"bad.xml:1", "<flexcomp",
        "flex constraints and elasticity (young) cannot both be present"}},
      {with_equality("<flexstrain flex='missing' cell='0 0 0'/>"),
       {"bad.xml:4", "<flexstrain", "unknown flex 'missing'"}},
      {with_equality("<flexstrain cell='0 0 0'/>"), {"bad.xml:4", "<flexstrain", "flex"}},
      {with_equality("<flexstrain flex='f'/>"), {"bad.xml:4", "<flexstrain", "missing cell"}},
      {with_equality("<flexstrain flex='f' cell='1 0 0'/>"),
       {"bad.xml:4", "<flexstrain", "cell '1 0 0' is not one of the 1 x 1 x 1 cells of flex 'f'"}},
      {with_equality("<flexstrain flex='f' cell='0 0.5 0'/>"), {"bad.xml:4", "cell '0 0.5 0'"}},
      {"<mujoco><worldbody><body name='a'/><body name='c'><joint type='slide'/><geom size='.1'/>"
       "</body></worldbody>"
       "<deformable><flex name='x' dim='1' body='a c' element='0 1'/></deformable>\n"
       "<equality><flexstrain flex='x' cell='0 0 0'/></equality></mujoco>",
       {"bad.xml:2", "<flexstrain", "flex 'x' is not interpolated"}},
      {"<mujoco><worldbody><body name='a'/></worldbody><deformable>"
       "<flex name='x' dim='2' body='a' vertex='0 0 0 1 0 0 0 1 0' element='0 1 2'/></deformable>\n"
       "<equality><flexstrain flex='x' cell='0 0 0'/></equality></mujoco>",
       {"bad.xml:2", "rigid flex 'x' in equality constraint"}},
  };
  for (const Case& c : cases) ExpectMessageParts(XmlLoadError(c.xml), c.parts, c.xml);
}

// A cable of three vertices held by its edge equality, resting on the floor with sleep
// enabled, and a ball that falls on it after about 0.35 s (MuJoCo 3.12's
// test/engine/testdata/sleep/flex_contact.xml); `ball_z` places the ball.
std::string SleepingCable(const std::string& ball_z) {
  return "<mujoco><option integrator='implicitfast' viscosity='2' sleep_tolerance='0.1'>"
         "<flag sleep='enable'/></option><worldbody><geom type='plane' size='5 5 .01'/>"
         "<body name='cable' pos='0 0 0.01'><flexcomp name='c' type='grid' dim='1' count='3 1 1' "
         "spacing='.05 .05 .05' radius='.01' mass='1'><edge equality='true' solref='0.15 0.2'/>"
         "</flexcomp></body><body name='ball' pos='0 0.01 " +
         ball_z + "'><freejoint/><geom type='sphere' size='.05'/></body></worldbody></mujoco>";
}

// Are all of flex f's trees asleep (awake)?
bool FlexTreesAre(const Model& m, const Data& d, int f, bool awake) {
  for (int v = m.flex_vertadr[f]; v < m.flex_vertadr[f] + m.flex_vertnum[f]; v++) {
    if (d.tree_awake[m.body_treeid[m.flex_vertbodyid[v]]] != awake) return false;
  }
  return true;
}

// Steps until flex 0 sleeps (at most n steps); true if it did.
bool StepUntilFlexSleeps(const Model& m, Data& d, int n) {
  for (int i = 0; i < n && !FlexTreesAre(m, d, 0, false); i++) Step(m, d);
  return FlexTreesAre(m, d, 0, false);
}

// A constrained flex may sleep (MuJoCo 3.12): left resting, its trees fall asleep
// together, still and without contacts; the ball landing on it wakes them all.
TEST(Flex, RestingConstrainedFlexSleepsAndWakesWhenTouched) {
  Model m = LoadXmlString(SleepingCable("0.5"), "cable.xml");
  ASSERT_EQ(m.ntree, 4);
  for (int t = 0; t < 3; t++) EXPECT_EQ(m.tree_sleep_policy[t], kSleepAutoAllowed);
  Data d = MakeData(m);
  ASSERT_TRUE(StepUntilFlexSleeps(m, d, 50));
  EXPECT_TRUE(d.tree_awake[3]);  // (the ball, still falling)
  for (int v = 0; v < 9; v++) EXPECT_EQ(d.qvel[v], 0.0);
  Step(m, d);
  EXPECT_EQ(d.ncon, 0);  // asleep on the floor: no contacts
  EXPECT_EQ(d.ne, 0);    // nor equality rows

  // The ball lands on it: every tree of the flex wakes, in contact with the ball.
  int step = 0;
  while (step < 400 && FlexTreesAre(m, d, 0, false)) Step(m, d), step++;
  ASSERT_TRUE(FlexTreesAre(m, d, 0, true)) << "still asleep after " << step << " steps";
  bool touched = false;
  for (int c = 0; c < d.ncon; c++) {
    touched = touched || d.contact[c].flex[0] == 0 || d.contact[c].flex[1] == 0;
  }
  EXPECT_TRUE(touched);
  EXPECT_GT(d.ne, 0);

  // An unconstrained flex never sleeps.
  std::string free_cable = SleepingCable("0.5");
  free_cable.replace(free_cable.find("<edge equality='true' solref='0.15 0.2'/>"), 41, "");
  Model free_m = LoadXmlString(free_cable, "free_cable.xml");
  for (int t = 0; t < 3; t++) EXPECT_EQ(free_m.tree_sleep_policy[t], kSleepAutoNever);
}

// A sleeping flex wakes with its equality partners: pushing one vertex wakes the
// whole cable; and a tree of the flex awake among sleeping ones (each in its own sleeping
// island) wakes the others through the flex's equality, one island per pass.
TEST(Flex, SleepingFlexWakesWithItsEqualityPartners) {
  Model m = LoadXmlString(SleepingCable("2"), "cable.xml");
  Data d = MakeData(m);
  ASSERT_TRUE(StepUntilFlexSleeps(m, d, 50));
  d.xfrc_applied[6 * m.flex_vertbodyid[2] + 2] = 1;
  Step(m, d);
  EXPECT_TRUE(FlexTreesAre(m, d, 0, true));
  EXPECT_NE(d.qvel[m.body_dofadr[m.flex_vertbodyid[2]] + 2], 0.0);  // (its z slider)
  d.xfrc_applied[6 * m.flex_vertbodyid[2] + 2] = 0;

  ASSERT_TRUE(StepUntilFlexSleeps(m, d, 100));
  for (int t = 0; t < 3; t++) d.tree_asleep[t] = t;  // each tree its own island
  d.tree_asleep[0] = -(1 + kMinAwake);
  UpdateSleep(m, d);
  Forward(m, d);
  EXPECT_TRUE(d.tree_awake[1]);
  EXPECT_FALSE(d.tree_awake[2]);
  Forward(m, d);
  EXPECT_TRUE(FlexTreesAre(m, d, 0, true));
}

}  // namespace
}  // namespace simlab

// ---------------------------------------------------------------- rays against flexes

namespace simlab {
namespace {

// mj_rayFlex against MuJoCo's own answers (tests/conformance/flex/make_ray_golden.mjs): a
// cloth, a soft box with layers and a cable after 150 steps, 864 rays under every
// combination of the vertex, edge, face and skin flags and two layers.
TEST(Flex, RaysHitFlexesAsMuJoCo) {
  const std::string dir = std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/flex";
  std::ifstream in(dir + "/ray_flex.json");
  ASSERT_TRUE(in.good());
  nlohmann::json golden = nlohmann::json::parse(in);
  Model m = LoadXml(dir + "/models/ray_flex.xml");
  Data d = MakeData(m);
  std::vector<double> qpos = golden["qpos"].get<std::vector<double>>();
  ASSERT_EQ(qpos.size(), d.qpos.size());
  d.qpos = qpos;
  Forward(m, d);
  int hits = 0;
  for (const auto& ray : golden["rays"]) {
    std::vector<double> pnt = ray["pnt"], vec = ray["vec"], ref_normal = ray["normal"];
    const auto& flags = ray["flags"];
    int vertid = -1;
    double normal[3];
    double x = RayCastFlex(m, d, ray["layer"], flags[0] == 1, flags[1] == 1, flags[2] == 1,
                           flags[3] == 1, ray["flex"], pnt.data(), vec.data(), &vertid, normal);
    double ref = ray["x"];
    EXPECT_NEAR(x, ref, 1e-12 * std::max(1.0, std::abs(ref))) << ray.dump();
    if (ref < 0) continue;
    hits++;
    EXPECT_EQ(vertid, ray["vertid"].get<int>()) << ray.dump();
    for (int k = 0; k < 3; k++) EXPECT_NEAR(normal[k], ref_normal[k], 1e-12) << ray.dump();
  }
  EXPECT_GT(hits, 300);
}

}  // namespace
}  // namespace simlab
