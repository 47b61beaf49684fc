// MuJoCo's signed distance field plugins (mujoco.sdf.torus, .bolt, .nut, .gear, .bowl):
// their fields against native MuJoCo's numbers, the mesh the compiler makes of a field
// (marching cubes) against MuJoCo's compiled model, rays marching onto a field, and the
// errors of bad configurations. (Rollouts equal to native MuJoCo's to the bit are the
// conformance cases of tests/conformance/plugins/make_goldens.sh.)
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A model with one instance of `plugin` configured by `config`, its mesh, and an sdf geom
// of it on a body at height 1, plus `extra` in the worldbody.
std::string OneShape(const std::string& plugin, const std::string& config, const std::string& extra = "") {
  return "<mujoco><extension><plugin plugin='" + plugin + "'><instance name='s'>" + config +
         "</instance></plugin></extension><asset><mesh name='s'><plugin instance='s'/></mesh>"
         "</asset><worldbody><body pos='0 0 1'><geom type='sdf' mesh='s'><plugin instance='s'/>"
         "</geom></body>" + extra + "</worldbody></mujoco>";
}

// The state after `steps` steps from rest.
Data DroppedOnTheFloor(const Model& m, int steps) {
  Data d = MakeData(m);
  for (int i = 0; i < steps; i++) Step(m, d);
  return d;
}

// The plugin's shape on a free body at height 1 above a floor.
Model OnAFloor(const std::string& plugin) {
  std::string xml = OneShape(plugin, "", "<geom type='plane' size='5 5 .1'/>");
  xml.replace(xml.find("<body pos='0 0 1'>"), 18, "<body pos='0 0 1'><freejoint/>");
  return LoadXmlString(xml, "floor.xml");
}

TEST(SdfPlugin, FieldsEqualNativeMuJoCo) {
  // Each field at six points, as native MuJoCo's plugins compute them (default
  // attributes but the torus's).
  struct Shape {
    std::string plugin, config;
    std::vector<double> expected;
  };
  const std::vector<Shape> shapes = {
      {"mujoco.sdf.torus", "",
       {0.26753679447079703, 0.18412888492114735, 0.090904745285949717, -0.031398719117154542,
        -0.02929980355779585, 0.11955652560644534}},
      {"mujoco.sdf.bolt", "",
       {-0.099999999999999978, -0.22999999999999998, -0.14000000000000001,
        -0.010000000000000009, 0.12, 0.25}},
      {"mujoco.sdf.nut", "",
       {0.033260608509240383, 0.084456737117997838, 0.1021650411817607, 0.048209796694321738,
        0.12, 0.25}},
      {"mujoco.sdf.gear", "",
       {0.70984690810302453, 0.74021592451099616, 0.72075950522210641, 0.64177894832435944,
        0.53695479642450528, 0.44861955191515829}},
      {"mujoco.sdf.bowl", "",
       {0.51845801924418611, 0.66957931769935164, 0.77191107670036829, 0.74796336496147853,
        0.62225567789271619, 0.4692751973837942}},
  };
  for (const Shape& shape : shapes) {
    Model m = LoadXmlString(OneShape(shape.plugin, shape.config), "shape.xml");
    Data d = MakeData(m);
    ASSERT_EQ(m.geom_plugin[0], 0) << shape.plugin;
    for (int i = 0; i < 6; i++) {
      double x[3] = {0.1 * i - 0.23, 0.07 * i + 0.011, 0.13 * i - 0.4};
      EXPECT_EQ(SdfPluginDistance(m, d, 0, x), shape.expected[i]) << shape.plugin << " point " << i;
    }
  }
}

TEST(SdfPlugin, TorusGradientPointsAwayFromTheTube) {
  Model m = LoadXmlString(OneShape("mujoco.sdf.torus", ""), "torus.xml");
  Data d = MakeData(m);
  // Outside the tube on the +x side and above it: the gradient is the unit direction
  // from the tube's centre circle.
  double g[3], above[3] = {0.35, 0, 0.5}, outside[3] = {0.8, 0, 0};
  SdfPluginGradient(m, d, 0, g, above);
  EXPECT_NEAR(g[0], 0, 1e-15);
  EXPECT_NEAR(g[2], 1, 1e-15);
  SdfPluginGradient(m, d, 0, g, outside);
  EXPECT_NEAR(g[0], 1, 1e-15);
  EXPECT_NEAR(g[2], 0, 1e-15);
}

TEST(SdfPlugin, LevelSetMeshIsMuJoCos) {
  // Native MuJoCo's compiled torus of radii 0.35 and 0.15 (MuJoCo's model/plugin/sdf
  // mesh.xml): 49896 vertices, 99792 triangles, left in the plugin's frame; its geom's
  // size is the mesh's half extent and its body's inertia MuJoCo's (principal moments in
  // eigenvalue order on the unrotated axes).
  Model m = LoadXmlString(OneShape("mujoco.sdf.torus", "<config key='radius1' value='0.35'/>"
                                                       "<config key='radius2' value='0.15'/>"),
                          "torus.xml");
  EXPECT_EQ(m.mesh_vertnum[0], 49896);
  EXPECT_EQ(m.mesh_facenum[0], 99792);
  EXPECT_EQ(m.mesh_pos[0], 0);
  EXPECT_EQ(m.mesh_quat[0], 1);
  EXPECT_EQ(m.body_mass[1], 195.62170779342242);
  EXPECT_EQ(m.body_inertia[3], 22.823207401879255);
  EXPECT_EQ(m.body_inertia[4], 12.407592607420632);
  EXPECT_EQ(m.body_inertia[5], 12.407082444269152);
  EXPECT_EQ(m.geom_size[0], 0.49995070695877075);
  EXPECT_EQ(m.geom_size[2], 0.1499999761581421);
  EXPECT_EQ(m.noct, 0);  // (no octree: contacts come from the field)
}

TEST(SdfPlugin, RangefinderMarchesOntoTheField) {
  // A rangefinder on the x axis 2 away from the torus's centre, looking at it: the outer
  // side of the tube is 2 - 0.5 away.
  std::string site = "<site name='eye' pos='2 0 1' zaxis='-1 0 0'/>";
  std::string xml = OneShape("mujoco.sdf.torus", "", site);
  xml.replace(xml.find("</mujoco>"), 9, "<sensor><rangefinder site='eye'/></sensor></mujoco>");
  Model m = LoadXmlString(xml, "torus.xml");
  Data d = MakeData(m);
  Forward(m, d);
  EXPECT_NEAR(d.sensordata[0], 1.5, 1e-7);
}

TEST(SdfPlugin, ContactsHoldAShapeOnTheFloor) {
  // A bowl dropped on a plane comes to rest on its rim (the plane collides with the
  // level set's hull), touching the floor.
  Model m = OnAFloor("mujoco.sdf.bowl");
  Data d = DroppedOnTheFloor(m, 1500);
  EXPECT_GT(d.ncon, 0);
  EXPECT_LT(std::abs(d.qvel[2]), 1e-2);
  EXPECT_GT(d.qpos[2], 0);
  EXPECT_LT(d.qpos[2], 1.05);
}

TEST(SdfPlugin, OurOwnFieldRestsOnTheFloor) {
  // A sphere field of radius r (attribute, default 0.2) registered as a plugin: its
  // level-set mesh is a sphere, and it comes to rest touching the floor at height r.
  Plugin ball;
  ball.name = "test.sdf.ball";
  ball.capabilities = kPluginSdf;
  ball.attributes = {"r"};
  ball.sdf_defaults = {0.2};
  ball.sdf_distance = [](const double p[3], const double* a) {
    return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - a[0];
  };
  ball.sdf_gradient = [](double g[3], const double p[3], const double*) {
    double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; k++) g[k] = p[k] / n;
  };
  ball.sdf_aabb = [](double box[6], const double* a) {
    box[0] = box[1] = box[2] = 0;
    box[3] = box[4] = box[5] = a[0] * 1.1;
  };
  RegisterPlugin(ball);
  Model m = OnAFloor("test.sdf.ball");
  Data d = DroppedOnTheFloor(m, 1500);
  EXPECT_GT(d.ncon, 0);
  EXPECT_NEAR(d.qpos[2], 0.2, 5e-3);

  // simlab makes an sdf plugin's instances itself.
  Plugin own_init = ball;
  own_init.name = "test.sdf.ball_with_init";
  own_init.init = [](const Model&, Data&, int) { return std::unique_ptr<PluginInstanceData>(); };
  try {
    RegisterPlugin(own_init);
    ADD_FAILURE() << "an sdf plugin with its own init was registered";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("leave init unset"), std::string::npos) << e.what();
  }
}

TEST(SdfPlugin, BadConfigurationsAreClearErrors) {
  struct Bad {
    std::string xml;
    std::vector<std::string> says;
  };
  const std::vector<Bad> cases = {
      {OneShape("mujoco.sdf.torus", "<config key='radius1' value='wide'/>"),
       {"<instance name=\"s\">", "invalid attribute value for 'radius1': 'wide'"}},
      {OneShape("mujoco.sdf.torus", "<config key='width' value='1'/>"),
       {"unrecognized attribute 'plugin:width' for plugin 'mujoco.sdf.torus'"}},
      {OneShape("mujoco.sdf.gear", "<config key='diameter' value='0'/>"), {"too thin for a mesh"}},
      {OneShape("mujoco.sdf.torus", "<config key='radius1' value='nan'/>"), {"too thin for a mesh"}},
      {OneShape("mujoco.sdf.torus", "<config key='radius1' value='1e300'/>"), {"<mesh name=\"s\">"}},
      {"<mujoco><extension><plugin plugin='mujoco.pid'><instance name='p'/></plugin></extension>"
       "<asset><mesh name='m'><plugin instance='p'/></mesh></asset></mujoco>",
       {"<mesh name=\"m\">", "plugin 'mujoco.pid' does not support signed distance fields"}},
      {"<mujoco><extension><plugin plugin='mujoco.sdf.torus'><instance name='t'/></plugin></extension>"
       "<asset><mesh name='m' scale='2 2 2'><plugin instance='t'/></mesh></asset></mujoco>",
       {"scale is not compatible with SDFs"}},
      {"<mujoco><asset><mesh name='m'><plugin instance='nothing'/></mesh></asset></mujoco>",
       {"unrecognized name 'nothing' for plugin instance"}},
  };
  for (const Bad& bad : cases) test_util::ExpectMessageParts(test_util::XmlLoadError(bad.xml), bad.says, bad.xml);
}

}  // namespace
}  // namespace simlab
