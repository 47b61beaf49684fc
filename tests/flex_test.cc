// Flexes: what a <flexcomp> expands into, how the edge equality holds a cloth, and clear
// errors for flexes and flexcomps that cannot be built. (Agreement with MuJoCo is in the
// conformance goldens: tests/conformance/flex_cases.txt, and the compiler's flex fields
// in CompilerConformance.Flexes.)
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

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
  };
  for (const Case& c : cases) ExpectMessageParts(XmlLoadError(c.xml), c.parts, c.xml);
}

}  // namespace
}  // namespace simlab
