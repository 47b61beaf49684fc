// Tactile sensor: the values of MuJoCo's definition checked on a scene simple enough to
// work them out by hand (taxels sinking into the floor plane, whose signed distance is
// the height), and the cases the goldens cannot show: mesh geoms are skipped (no
// octree), a height field touching the sensor is an engine error (Step turns it into
// a warning and a reset: tests/warning_test.cc).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/sensor.h"
#include "math/math.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A pad sliding over the floor, 0.8 mm into it, with 3 x 2 taxels 12 mm below its
// centre on a child body tilted 8 degrees (some taxels are in the floor, some not); a
// second pad of the same kind over a mesh block and a height field.
const char* kPadScene = R"(
<mujoco>
  <asset>
    <mesh name="plate" builtin="plate" params="3 2" scale="0.04 0.03 0.012"/>
    <mesh name="cube" vertex="-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1"
          scale="0.05 0.05 0.01"/>
    <hfield name="bumps" nrow="2" ncol="2" size="0.1 0.1 0.01 0.01"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.01"/>
    <body name="pad" pos="0 0 0.0092">
      <joint name="y" type="slide" axis="0 1 0"/>
      <joint name="z" type="slide" axis="0 0 1"/>
      <geom name="pad_box" type="box" size="0.05 0.05 0.01" mass="0.2"/>
      <body name="holder" euler="0 8 0">
        <inertial pos="0 0 0" mass="0.01" diaginertia="1e-6 1e-6 1e-6"/>
        <geom name="taxels" type="mesh" mesh="plate" contype="0" conaffinity="0"/>
      </body>
    </body>
    <geom name="mesh_block" type="mesh" mesh="cube" pos="1 0 0.01"/>
    <geom name="bumps" type="hfield" hfield="bumps" pos="2 0 0"/>
    <body name="pad2" pos="1 0 0.0292">
      <joint type="slide" axis="0 0 1"/>
      <geom name="pad2_box" type="box" size="0.04 0.04 0.01" mass="0.2"/>
      <geom name="taxels2" type="mesh" mesh="plate" contype="0" conaffinity="0" mass="0.01"/>
    </body>
  </worldbody>
  <sensor>
    <tactile name="pad" mesh="plate" geom="taxels"/>
    <tactile name="pad2" mesh="plate" geom="taxels2"/>
  </sensor>
</mujoco>
)";

// Taxel j's world position and its frame (normal, tangent 1, tangent 2) as the sensor
// reads it: the stored frame rotated by the mesh's quaternion.
void Taxel(const Model& m, const Data& d, int mesh, int geom, int j, double pos[3],
           double frame[9]) {
  const double* vert = &m.mesh_vert[3 * (m.mesh_vertadr[mesh] + j)];
  math::MulMatVec3(pos, &d.geom_xmat[9 * geom], vert);
  math::Add3(pos, pos, &d.geom_xpos[3 * geom]);
  const double* stored = &m.mesh_normal[3 * m.mesh_normaladr[mesh] + 9 * j];
  for (int k = 0; k < 3; k++) math::RotVecQuat(frame + 3 * k, stored + 3 * k, &m.mesh_quat[4 * mesh]);
}

TEST(TactileSensor, PressureAndSlipOfTaxelsInTheFloor) {
  Model m = LoadXmlString(kPadScene, "pad.xml");
  Data d = MakeData(m);
  const double vel[3] = {0, 0.3, -0.2};  // the pad slides along y and sinks
  d.qvel[0] = vel[1];
  d.qvel[1] = vel[2];
  Forward(m, d);
  ASSERT_GT(d.ncon, 0);

  // Three channels of six taxels: pressure depth / (5 cm - depth) along the normal, then
  // the slip speed along each tangent (the floor is still), zero where a taxel is above
  // the floor.
  int mesh = m.NameToId(kObjMesh, "plate"), geom = m.NameToId(kObjGeom, "taxels");
  ASSERT_EQ(m.mesh_vertnum[mesh], 6);
  std::span<double> out = SensorData(m, d, "pad");
  ASSERT_EQ(out.size(), 18u);
  int inside = 0;
  for (int j = 0; j < 6; j++) {
    double pos[3], frame[9];
    Taxel(m, d, mesh, geom, j, pos, frame);
    double depth = std::min(pos[2], 0.0);
    inside += depth < 0;
    double pressure = depth / (0.05 - depth);
    double normal_sq = math::Dot3(frame, frame);
    EXPECT_NEAR(out[j], pressure * normal_sq, 1e-12) << "taxel " << j;
    EXPECT_NEAR(out[6 + j], depth < 0 ? std::abs(math::Dot3(vel, frame + 3)) : 0, 1e-12);
    EXPECT_NEAR(out[12 + j], depth < 0 ? std::abs(math::Dot3(vel, frame + 6)) : 0, 1e-12);
  }
  // The tilt puts some taxels in the floor and leaves others above it.
  EXPECT_GT(inside, 0);
  EXPECT_LT(inside, 6);
}

TEST(TactileSensor, MeshGeomsAreSkipped) {
  // The second pad rests on a mesh block: MuJoCo builds mesh octrees only for sdf
  // geoms, so the sensor skips the block and reads nothing though they touch.
  Model m = LoadXmlString(kPadScene, "pad.xml");
  Data d = MakeData(m);
  Forward(m, d);
  int block = m.NameToId(kObjGeom, "mesh_block");
  bool touching = false;
  for (int k = 0; k < d.ncon; k++) {
    touching |= d.contact[k].geom1 == block || d.contact[k].geom2 == block;
  }
  ASSERT_TRUE(touching);
  for (double v : SensorData(m, d, "pad2")) EXPECT_EQ(v, 0);
}

TEST(TactileSensor, HeightFieldTouchingStopsWithAnError) {
  // MuJoCo's signed distances have no height field case (it stops with an error);
  // a contact of the pad with the height field is made by hand here.
  Model m = LoadXmlString(kPadScene, "pad.xml");
  Data d = MakeData(m);
  Forward(m, d);
  ASSERT_GT(d.ncon, 0);
  d.contact[0].geom1 = m.NameToId(kObjGeom, "pad_box");
  d.contact[0].geom2 = m.NameToId(kObjGeom, "bumps");
  d.ncon = 1;
  int sensor = SensorId(m, "pad");
  std::vector<double> out(m.sensor_dim[sensor]);
  try {
    TactileSensor(m, d, sensor, out.data());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tactile sensor 'pad'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("height field"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace simlab
