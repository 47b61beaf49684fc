// Contact sensors: what the loader refuses (tactile meshes, contact criteria), and physical
// checks the goldens only imply: a box at rest on the floor is held up by its weight,
// which the touch zones split between them and the contact sensor's net reduction
// gathers under the box's centre.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

void ExpectError(const std::string& xml, const std::vector<std::string>& pieces) {
  test_util::ExpectMessageParts(test_util::XmlLoadError(xml), pieces, xml);
}

TEST(ContactSensorErrors, NameTheLineAndTheProblem) {
  // A tactile mesh needs a normal and two tangents per vertex; this one has one normal.
  ExpectError("<mujoco>\n<asset><mesh name=\"pad\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/></asset>\n"
              "<worldbody><geom name=\"pad\" type=\"mesh\" mesh=\"pad\"/></worldbody>\n"
              "<sensor>\n<tactile mesh=\"pad\" geom=\"pad\"/>\n</sensor>\n</mujoco>\n",
              {"bad.xml:5:", "<tactile>", "needs a normal and two tangents per vertex"});
  const std::string head =
      "<mujoco>\n<worldbody>\n<geom name=\"floor\" type=\"plane\" size=\"1 1 .1\"/>\n"
      "<body name=\"b\"><freejoint/><geom name=\"g\" size=\".1\"/>"
      "<site name=\"s\"/></body>\n</worldbody>\n<sensor>\n";
  const std::string tail = "\n</sensor>\n</mujoco>\n";
  ExpectError(head + "<contact geom1=\"g\" body1=\"b\"/>" + tail,
              {"bad.xml:7:", "<contact>", "at most one of"});
  ExpectError(head + "<contact body2=\"nope\"/>" + tail,
              {"bad.xml:7:", "unrecognized name 'nope'"});
  ExpectError(head + "<contact num=\"0\"/>" + tail, {"bad.xml:7:", "'num' must be positive"});
  ExpectError(head + "<touch site=\"nope\"/>" + tail,
              {"bad.xml:7:", "<touch>", "unrecognized name 'nope'"});
}

// A 2 kg box resting on the floor, touch zones over its four bottom corners and one
// over the whole box, and the net contact wrench between box and floor.
const char* kRestingBox = R"(
<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="box" pos="0 0 0.05">
      <freejoint/>
      <geom type="box" size="0.2 0.1 0.05" mass="2"/>
      <site name="all" type="box" size="0.21 0.11 0.06"/>
      <site name="c1" type="sphere" pos="0.2 0.1 -0.05" size="0.02"/>
      <site name="c2" type="box" pos="-0.2 0.1 -0.05" size="0.02 0.02 0.02"/>
      <site name="c3" type="capsule" pos="0.2 -0.1 -0.05" size="0.02 0.01"/>
      <site name="c4" type="ellipsoid" pos="-0.2 -0.1 -0.05" size="0.02 0.03 0.01"/>
      <site name="top" type="box" pos="0 0 0.05" size="0.1 0.05 0.01"/>
    </body>
  </worldbody>
  <sensor>
    <touch site="all"/>
    <touch site="c1"/>
    <touch site="c2"/>
    <touch site="c3"/>
    <touch site="c4"/>
    <touch site="top"/>
    <contact body1="box" body2="world" data="found force pos" reduce="netforce"/>
  </sensor>
</mujoco>
)";

TEST(ContactSensors, RestingBoxCarriesItsWeight) {
  Model m = LoadXmlString(kRestingBox, "resting.xml");
  Data d = MakeData(m);
  for (int k = 0; k < 1000; k++) Step(m, d);
  const double weight = 2 * 9.81;
  const double* s = d.sensordata.data();

  // The whole-box zone carries the weight, the corners share it, the top feels nothing.
  EXPECT_NEAR(s[0], weight, 1e-3 * weight);
  EXPECT_NEAR(s[1] + s[2] + s[3] + s[4], s[0], 1e-9 * weight);
  for (int c = 1; c <= 4; c++) EXPECT_GT(s[c], 0.1 * weight) << "corner " << c;
  EXPECT_EQ(s[5], 0);

  // Net wrench: four contacts; with the box named first, the normal points from it to
  // the floor, so the force is the box pressing the floor down; centred under the box.
  const double* net = s + 6;
  EXPECT_EQ(net[0], 4);
  EXPECT_NEAR(net[3], -weight, 1e-3 * weight);
  EXPECT_NEAR(net[4], 0, 1e-6);
  EXPECT_NEAR(std::hypot(net[1], net[2]), 0, 1e-6);
  EXPECT_NEAR(net[5], 0, 1e-6);
}

}  // namespace
}  // namespace simlab
