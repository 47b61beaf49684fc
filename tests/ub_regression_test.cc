// Ordinary models that once made the engine or the compiler do undefined things (issue
// 15): rows of empty arrays taken as &array[offset] (a keyframe of a model without
// actuators, activations or mocap bodies; a body without dofs; tendons and actuators of a
// model without dofs), memcpy to a null pointer (a mesh file without normals or faces),
// and a double outside int's range cast to int (a huge geom over a height field). In the
// normal build these tests check the numbers against MuJoCo 3.5.1 (the values below come
// from ../shared/oracle); in the sanitizer build (tools/sanitize.sh) they also fail on
// the undefined behaviour itself.
#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab {
namespace {

// MuJoCo's integrators, by their MJCF names.
constexpr const char* kIntegrators[] = {"Euler", "implicit", "implicitfast", "RK4"};

// A model of `body` (the elements inside <mujoco>) stepped by `integrator`.
std::string WithIntegrator(const std::string& integrator, const std::string& body) {
  return "<mujoco>\n  <option integrator=\"" + integrator + "\"/>" + body + "\n</mujoco>";
}

// A world site and a site on a body without joints (nv = 0) joined by the spatial tendon
// "t" with `attributes`, sqrt(5) long.
std::string TendonWithoutDofs(const std::string& attributes) {
  return R"(
  <worldbody>
    <site name="a" pos="0 0 0"/>
    <body name="post" pos="1 0 0">
      <site name="b" pos="0 2 0"/>
    </body>
  </worldbody>
  <tendon>
    <spatial name="t" )" + attributes + R"(>
      <site site="a"/>
      <site site="b"/>
    </spatial>
  </tendon>)";
}

// A pendulum whose keyframe gives qpos and qvel only: key_act, key_ctrl, key_mpos and
// key_mquat are empty arrays.
constexpr char kKeyframeOnlyState[] = R"(
<mujoco>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="h" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 .5 0 0" size=".05"/>
    </body>
  </worldbody>
  <keyframe>
    <key qpos="0.3" qvel="-1"/>
  </keyframe>
</mujoco>)";

TEST(UbRegression, KeyframeWithoutActCtrlMocap) {
  Model m = LoadXmlString(kKeyframeOnlyState);
  ASSERT_EQ(m.nu + m.na + m.nmocap, 0);
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  EXPECT_EQ(d.qpos[0], 0.3);
  EXPECT_EQ(d.qvel[0], -1);
  Forward(m, d);
  EXPECT_NEAR(d.qacc[0], 26.030792629928495, 1e-9);
}

// A keyframe of a model without any dof: every key array but key_time is empty.
TEST(UbRegression, KeyframeOfAModelWithoutDofs) {
  Model m = LoadXmlString(R"(
<mujoco>
  <worldbody>
    <geom type="plane" size="1 1 .1"/>
  </worldbody>
  <keyframe>
    <key time="1.5"/>
  </keyframe>
</mujoco>)");
  ASSERT_EQ(m.nq, 0);
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  EXPECT_EQ(d.time, 1.5);
  Step(m, d);
  EXPECT_DOUBLE_EQ(d.time, 1.502);
}

// A static body (no dofs: dofadr -1) between the world and a hinged arm, with an
// accelerometer and a force sensor on it (RNE and its post-constraint pass visit it).
// Stepped by every integrator (the implicit ones differentiate RNE).
TEST(UbRegression, BodyWithoutDofs) {
  // the arm's angle after one step, by integrator (RK4 differs)
  const double qpos1[] = {0.298108844146423, 0.298108844146423, 0.298108844146423,
                          0.2980545231256536};
  for (int i = 0; i < 4; i++) {
    SCOPED_TRACE(kIntegrators[i]);
    Model m = LoadXmlString(WithIntegrator(kIntegrators[i], R"(
  <worldbody>
    <body name="base" pos="0 0 1">
      <geom size=".1" mass="2" contype="0" conaffinity="0"/>
      <site name="s"/>
      <body name="arm" pos=".1 0 0">
        <joint name="h" type="hinge" axis="0 1 0" damping="0.5"/>
        <geom type="capsule" fromto="0 0 0 .5 0 0" size=".05"/>
      </body>
    </body>
  </worldbody>
  <sensor>
    <accelerometer site="s"/>
    <force site="s"/>
  </sensor>
  <keyframe>
    <key qpos="0.3" qvel="-1"/>
  </keyframe>)"));
    ASSERT_EQ(m.body_dofnum[1], 0);
    Data d = MakeData(m);
    ResetDataKeyframe(m, d, 0);
    Forward(m, d);
    EXPECT_NEAR(d.qacc[0], 27.2789647185505, 1e-9);
    const double sensors[6] = {0, 0, 0, -10.032543293354873, 0, 34.612845610503236};
    for (int k = 0; k < 6; k++) EXPECT_NEAR(d.sensordata[k], sensors[k], 1e-9) << k;
    Step(m, d);
    EXPECT_NEAR(d.qpos[0], qpos1[i], 1e-12);
  }
}

// A model without dofs whose spatial tendon (limited, with friction loss, stiffness, damping and
// armature, sensed) has an empty Jacobian: ten_J is (1 x 0). Stepped by every
// integrator (the implicit ones differentiate the forces).
TEST(UbRegression, TendonWithoutDofs) {
  for (const char* integrator : kIntegrators) {
    SCOPED_TRACE(integrator);
    Model m = LoadXmlString(WithIntegrator(
        integrator, TendonWithoutDofs(R"(limited="true" range="0 1" stiffness="3" damping="1"
                                         armature="0.1" frictionloss="0.5")") + R"(
  <sensor>
    <tendonpos tendon="t"/>
  </sensor>
  <keyframe>
    <key time="1"/>
  </keyframe>)"));
    ASSERT_EQ(m.nv, 0);
    Data d = MakeData(m);
    ResetDataKeyframe(m, d, 0);
    Step(m, d);
    EXPECT_DOUBLE_EQ(d.ten_length[0], std::sqrt(5.0));
    EXPECT_DOUBLE_EQ(d.sensordata[0], std::sqrt(5.0));
  }
}

// The same model without dofs with an actuator on the tendon: actuator_moment is (1 x 0)
// (the compiler's acc0 took a row of it as &array[offset]).
TEST(UbRegression, ActuatorWithoutDofs) {
  for (const char* integrator : kIntegrators) {
    SCOPED_TRACE(integrator);
    Model m = LoadXmlString(WithIntegrator(integrator, TendonWithoutDofs(R"(damping="1")") + R"(
  <actuator>
    <motor name="pull" tendon="t"/>
    <velocity name="damp" tendon="t" kv="2"/>
  </actuator>
  <sensor>
    <actuatorfrc actuator="pull"/>
  </sensor>
  <keyframe>
    <key ctrl="0.5 0"/>
  </keyframe>)"));
    ASSERT_EQ(m.nv, 0);
    Data d = MakeData(m);
    ResetDataKeyframe(m, d, 0);
    Step(m, d);
    EXPECT_DOUBLE_EQ(d.actuator_length[0], std::sqrt(5.0));
    EXPECT_EQ(d.actuator_force[0], 0.5);
    EXPECT_EQ(d.sensordata[0], 0.5);
  }
}

// A tetrahedron in MuJoCo's binary MSH format with vertices only: no normals, texture
// coordinates or faces (the faces come from its convex hull).
TEST(UbRegression, MeshFileWithoutNormalsOrFaces) {
  const int counts[4] = {4, 0, 0, 0};
  const float vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::string bytes(sizeof(counts) + sizeof(vertices), '\0');
  std::memcpy(bytes.data(), counts, sizeof(counts));
  std::memcpy(bytes.data() + sizeof(counts), vertices, sizeof(vertices));
  Model m = LoadXmlString(R"(
<mujoco>
  <asset>
    <mesh name="tet" file="tet.msh"/>
  </asset>
  <worldbody>
    <body name="tet" pos="0 0 1">
      <freejoint/>
      <geom type="mesh" mesh="tet"/>
    </body>
  </worldbody>
</mujoco>)",
                          "tet.xml", {{"tet.msh", bytes}});
  EXPECT_EQ(m.mesh_vertnum[0], 4);
  EXPECT_EQ(m.mesh_facenum[0], 4);
  EXPECT_NEAR(m.body_mass[1], 1000.0 / 6, 1e-9);
}

// A box much larger than int's range of grid cells resting on a height field: its
// sub-grid is the whole field. MuJoCo (the oracle, ../shared/oracle/rollout.mjs) finds 7
// contacts and qacc -9.810049198059374, as here.
TEST(UbRegression, HugeGeomOverHeightField) {
  Model m = LoadXmlString(R"(
<mujoco>
  <asset>
    <hfield name="h" nrow="3" ncol="4" size="1 1 .2 .1"
            elevation="0.1 0.5 0.2 0.3 0.4 0.6 0.1 0.2 0.3 0.9 0.5 0.2"/>
  </asset>
  <worldbody>
    <geom name="field" type="hfield" hfield="h"/>
    <body name="slab">
      <joint name="z" type="slide" axis="0 0 1"/>
      <geom name="huge" type="box" size="1e10 1e10 0.05"/>
    </body>
  </worldbody>
</mujoco>)");
  Data d = MakeData(m);
  Forward(m, d);
  EXPECT_EQ(d.ncon, 7);
  EXPECT_NEAR(d.qacc[0], -9.810049198059374, 1e-9);
}

// Texture colours outside [0, 1] (found by the fuzzer: a builtin texture's rgb1 of 9):
// converting 255 * 9 to a byte is undefined in C++ (and in MuJoCo's own conversion), so
// components saturate at 255 (and 0 below); colours inside [0, 1] convert as MuJoCo's.
TEST(UbRegression, TextureColoursOutsideTheUnitRange) {
  Model m = LoadXmlString(R"(
<mujoco>
  <asset>
    <texture name="t" type="cube" builtin="flat" width="4" height="4" rgb1="9 0.5 -2"
             rgb2="0 0 0"/>
    <texture name="g" type="2d" builtin="gradient" width="4" height="4" rgb1="3 3 3"
             rgb2="-1 -1 -1"/>
  </asset>
</mujoco>)");
  ASSERT_EQ(m.ntex, 2);
  EXPECT_EQ(m.tex_data[0], 255);
  EXPECT_EQ(m.tex_data[1], 127);
  EXPECT_EQ(m.tex_data[2], 0);
  // The gradient's blends of out-of-range colours saturate at both ends (and run under
  // UBSan in the sanitizer suite).
  bool low = false, high = false;
  for (int i = m.tex_adr[1]; i < m.ntexdata; i++) {
    low = low || m.tex_data[i] == 0;
    high = high || m.tex_data[i] == 255;
  }
  EXPECT_TRUE(low && high);
}

}  // namespace
}  // namespace simlab
