// Compiler conformance: every compiled field of a model against MuJoCo's, from goldens
// made by tools/dump_model.mjs (MuJoCo 3.5.1) and committed in tests/compiler_goldens.
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "math/math.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using nlohmann::json;

// Relative-ish tolerance on compiled numbers.
constexpr double kTol = 1e-12;

bool Near(double a, double b, double tol = kTol) {
  return std::abs(a - b) <= tol * std::max(1.0, std::abs(b));
}

json ReadGolden(const std::string& name) {
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_goldens/" + name + ".json");
  EXPECT_TRUE(in.good()) << "missing golden " << name;
  json j;
  if (in) in >> j;
  return j;
}

// The inertia tensor R diag(I) R^T of body i: independent of the principal-axes order.
void InertiaTensor(const double* quat, const double* diag, double* out) {
  double r[9];
  math::QuatToMat(r, quat);
  for (int a = 0; a < 3; a++) {
    for (int b = 0; b < 3; b++) {
      out[3 * a + b] = 0;
      for (int k = 0; k < 3; k++) out[3 * a + b] += r[3 * a + k] * diag[k] * r[3 * b + k];
    }
  }
}

// Compares one dumped array with our field of the same name; returns the worst
// absolute difference.
double CompareField(const std::string& model, FieldView& f, const json& golden) {
  size_t n = static_cast<size_t>(f.rows) * f.cols;
  // MuJoCo's bvh_* continue past the bodies' trees with its meshes' face trees, which
  // simlab does not build: the bodies' part is compared.
  bool body_part = std::string(f.name).rfind("bvh_", 0) == 0 && golden.size() > n;
  if (!body_part) EXPECT_EQ(golden.size(), n) << model << ": " << f.name << " size";
  if (!body_part && golden.size() != n) return INFINITY;
  double worst = 0;
  for (size_t i = 0; i < n; i++) {
    double want = golden[i].get<double>();
    double got = f.is_int ? f.ints[i] : f.doubles[i];
    worst = std::max(worst, std::abs(got - want));
    if (f.is_int) {
      EXPECT_EQ(got, want) << model << ": " << f.name << "[" << i << "]";
    } else {
      EXPECT_TRUE(Near(got, want)) << model << ": " << f.name << "[" << i << "] = " << got
                                   << ", MuJoCo " << want;
    }
  }
  return worst;
}

// body_iquat: compare the rotated inertia tensors instead of the quaternions.
void CompareInertialFrames(const std::string& model, const Model& m, const json& arrays) {
  for (int b = 0; b < m.nbody; b++) {
    double want_q[4], want_i[3], want[9], got[9];
    for (int k = 0; k < 4; k++) want_q[k] = arrays["body_iquat"][4 * b + k].get<double>();
    for (int k = 0; k < 3; k++) want_i[k] = arrays["body_inertia"][3 * b + k].get<double>();
    InertiaTensor(want_q, want_i, want);
    InertiaTensor(&m.body_iquat[4 * b], &m.body_inertia[3 * b], got);
    for (int k = 0; k < 9; k++) {
      EXPECT_TRUE(Near(got[k], want[k])) << model << ": inertia tensor of body " << b << "[" << k
                                         << "] = " << got[k] << ", MuJoCo " << want[k];
    }
  }
}

void CompareOptions(const std::string& model, const Model& m, const json& opt) {
  EXPECT_EQ(m.opt.timestep, opt["timestep"].get<double>()) << model;
  for (int k = 0; k < 3; k++) EXPECT_EQ(m.opt.gravity[k], opt["gravity"][k].get<double>()) << model;
  EXPECT_EQ(m.opt.integrator, opt["integrator"].get<int>()) << model;
  EXPECT_EQ(m.opt.cone, opt["cone"].get<int>()) << model;
  EXPECT_EQ(m.opt.jacobian, opt["jacobian"].get<int>()) << model;
  EXPECT_EQ(m.opt.solver, opt["solver"].get<int>()) << model;
  EXPECT_EQ(m.opt.iterations, opt["iterations"].get<int>()) << model;
  EXPECT_EQ(m.opt.ls_iterations, opt["ls_iterations"].get<int>()) << model;
  EXPECT_EQ(m.opt.disableflags, opt["disableflags"].get<int>()) << model;
  EXPECT_EQ(m.opt.enableflags, opt["enableflags"].get<int>()) << model;
  EXPECT_EQ(m.opt.disableactuator, opt["disableactuator"].get<int>()) << model;
  EXPECT_EQ(m.opt.impratio, opt["impratio"].get<double>()) << model;
  EXPECT_EQ(m.opt.tolerance, opt["tolerance"].get<double>()) << model;
  for (int k = 0; k < 5; k++) EXPECT_EQ(m.opt.o_solimp[k], opt["o_solimp"][k].get<double>()) << model;
  // The medium of the fluid forces (goldens made before them lack it).
  if (opt.contains("density")) {
    EXPECT_EQ(m.opt.density, opt["density"].get<double>()) << model;
    EXPECT_EQ(m.opt.viscosity, opt["viscosity"].get<double>()) << model;
    for (int k = 0; k < 3; k++) EXPECT_EQ(m.opt.wind[k], opt["wind"][k].get<double>()) << model;
  }
}

// Loads `path` and compares every dumped field with the golden `name`.
void CheckModel(const std::string& name, const std::string& path) {
  json golden = ReadGolden(name);
  ASSERT_FALSE(golden.is_null());
  Model m = LoadXml(path);

  // Sizes.
  const json& sizes = golden["sizes"];
  EXPECT_EQ(m.nq, sizes["nq"].get<int>());
  EXPECT_EQ(m.nv, sizes["nv"].get<int>());
  EXPECT_EQ(m.nu, sizes["nu"].get<int>());
  EXPECT_EQ(m.na, sizes["na"].get<int>());
  EXPECT_EQ(m.nbody, sizes["nbody"].get<int>());
  EXPECT_EQ(m.njnt, sizes["njnt"].get<int>());
  EXPECT_EQ(m.ngeom, sizes["ngeom"].get<int>());
  EXPECT_EQ(m.nsite, sizes["nsite"].get<int>());
  EXPECT_EQ(m.ntendon, sizes["ntendon"].get<int>());
  EXPECT_EQ(m.nwrap, sizes["nwrap"].get<int>());
  EXPECT_EQ(m.nkey, sizes["nkey"].get<int>());
  EXPECT_EQ(m.nM, sizes["nM"].get<int>());
  EXPECT_EQ(m.nmocap, sizes["nmocap"].get<int>());
  if (sizes.contains("neq")) EXPECT_EQ(m.neq, sizes["neq"].get<int>());
  if (sizes.contains("ncam")) EXPECT_EQ(m.ncam, sizes["ncam"].get<int>());
  if (sizes.contains("nmeshnormal")) EXPECT_EQ(m.nmeshnormal, sizes["nmeshnormal"].get<int>());
  if (sizes.contains("nlight")) {
    EXPECT_EQ(m.nlight, sizes["nlight"].get<int>());
    EXPECT_EQ(m.ntex, sizes["ntex"].get<int>());
    EXPECT_EQ(m.ntexdata, sizes["ntexdata"].get<int>());
    EXPECT_EQ(m.nmat, sizes["nmat"].get<int>());
  }
  if (sizes.contains("ntree")) EXPECT_EQ(m.ntree, sizes["ntree"].get<int>());
  if (sizes.contains("nB")) EXPECT_EQ(m.nB, sizes["nB"].get<int>());
  if (sizes.contains("nmeshtexcoord")) EXPECT_EQ(m.nmeshtexcoord, sizes["nmeshtexcoord"].get<int>());
  if (sizes.contains("nmeshpoly")) {
    EXPECT_EQ(m.nmeshpoly, sizes["nmeshpoly"].get<int>());
    EXPECT_EQ(m.nmeshpolyvert, sizes["nmeshpolyvert"].get<int>());
    EXPECT_EQ(m.nmeshpolymap, sizes["nmeshpolymap"].get<int>());
  }
  if (sizes.contains("nskin")) {
    EXPECT_EQ(m.nskin, sizes["nskin"].get<int>());
    EXPECT_EQ(m.nskinvert, sizes["nskinvert"].get<int>());
    EXPECT_EQ(m.nskintexvert, sizes["nskintexvert"].get<int>());
    EXPECT_EQ(m.nskinface, sizes["nskinface"].get<int>());
    EXPECT_EQ(m.nskinbone, sizes["nskinbone"].get<int>());
    EXPECT_EQ(m.nskinbonevert, sizes["nskinbonevert"].get<int>());
  }
  if (::testing::Test::HasFailure()) return;

  // Every array we have and MuJoCo dumped.
  const json& arrays = golden["arrays"];
  int compared = 0;
  double worst = 0;
  std::string worst_field;
  for (FieldView& f : m.Fields()) {
    std::string field = f.name;
    // M_* are our legacy-layout CSR rows; MuJoCo's skip "simple" dofs.
    if (!arrays.contains(field) || field == "body_iquat" || field.rfind("M_", 0) == 0) continue;
    double w = CompareField(name, f, arrays[field]);
    if (!f.is_int && w > worst) worst = w, worst_field = field;
    compared++;
  }
  CompareInertialFrames(name, m, arrays);
  CompareOptions(name, m, golden["opt"]);
  if (golden.contains("stat")) {
    double meaninertia = golden["stat"]["meaninertia"].get<double>();
    EXPECT_TRUE(Near(m.stat.meaninertia, meaninertia)) << name << " meaninertia";
  }
  EXPECT_GT(compared, 100) << name;
  std::cout << "[ compiler ] " << name << ": " << compared << " fields, worst |diff| " << worst
            << " in " << worst_field << "\n";
}

std::string Corpus(const std::string& rel) {
  return std::string(SIMLAB_SOURCE_DIR) + "/../shared/corpus/mujoco/model/" + rel;
}

std::string Local(const std::string& rel) {
  return std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/" + rel;
}

TEST(CompilerConformance, Humanoid) { CheckModel("humanoid", Corpus("humanoid/humanoid.xml")); }
TEST(CompilerConformance, SliderCrank) {
  CheckModel("slider_crank", Corpus("slider_crank/slider_crank.xml"));
}
TEST(CompilerConformance, Orientations) { CheckModel("orientations", Local("orientations.xml")); }
TEST(CompilerConformance, Frames) { CheckModel("frames", Local("frames.xml")); }
TEST(CompilerConformance, Defaults) { CheckModel("defaults", Local("defaults.xml")); }
TEST(CompilerConformance, GeomInertia) { CheckModel("geom_inertia", Local("geom_inertia.xml")); }
TEST(CompilerConformance, Inertial) { CheckModel("inertial", Local("inertial.xml")); }
TEST(CompilerConformance, Radian) { CheckModel("radian", Local("radian.xml")); }
TEST(CompilerConformance, Actuators) { CheckModel("actuators", Local("actuators.xml")); }
TEST(CompilerConformance, Tendons) { CheckModel("tendons", Local("tendons.xml")); }
TEST(CompilerConformance, BoundingVolumes) { CheckModel("bvh", Local("bvh.xml")); }
TEST(CompilerConformance, Keyframes) { CheckModel("keyframes", Local("keyframes.xml")); }
TEST(CompilerConformance, RefsiteDampratio) {
  CheckModel("refsite_dampratio", Local("refsite_dampratio.xml"));
}
TEST(CompilerConformance, Muscles) { CheckModel("muscles", Local("muscles.xml")); }
// body_gravcomp and jnt_actgravcomp (the gravity compensation bench).
TEST(CompilerConformance, Gravcomp) {
  CheckModel("gravcomp_arm",
             std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/gravcomp/base/arm.xml");
}
TEST(CompilerConformance, SpatialTendons) {
  // wrap_type/objid/prm (side sites, divisors), tendon_length0 and lengthspring.
  for (const char* name : {"wrap_sphere", "wrap_cylinder", "pulley", "armature"}) {
    CheckModel(std::string("tendon_") + name,
               std::string(SIMLAB_SOURCE_DIR) + "/tests/conformance/tendon/base/" + name + ".xml");
  }
}
// Composition: <include> and <attach> (models under compiler_models/compose/).
TEST(CompilerConformance, ComposeAttach) {
  CheckModel("compose_attach", Local("compose_attach.xml"));
}
TEST(CompilerConformance, ComposeInclude) {
  CheckModel("compose_include", Local("compose_include.xml"));
}
// An attached model with other <compiler> settings (angles, Euler sequence, autolimits,
// inertia from geoms, bounds, alignfree): its elements keep their own.
TEST(CompilerConformance, ComposeSettings) {
  CheckModel("compose_settings", Local("compose_settings.xml"));
  CheckModel("compose_settings_nested", Local("compose_settings_nested.xml"));
}
TEST(CompilerConformance, ComposeNested) {
  CheckModel("compose_nested", Local("compose_nested.xml"));
}
// The lesson's gripper, alone and attached to the gantry.
TEST(CompilerConformance, Gripper) {
  CheckModel("gripper", std::string(SIMLAB_SOURCE_DIR) + "/models/gripper.xml");
}
TEST(CompilerConformance, GantryGripper) {
  CheckModel("gantry_gripper", std::string(SIMLAB_SOURCE_DIR) + "/models/gantry_gripper.xml");
}
TEST(CompilerConformance, Equality) { CheckModel("equality", Local("equality.xml")); }
// geom_fluid: the ellipsoid fluid model's coefficients, added mass and inertia.
TEST(CompilerConformance, Fluid) { CheckModel("fluid", Local("fluid.xml")); }

// Flexes: every generated flexcomp shape, pins, bending, 3D elasticity, a rigid flexcomp,
// flexes interpolated from nodes and a <deformable> flex (simlab's model), and MuJoCo's
// flag (cloth, edge equality).
TEST(CompilerConformance, Flexes) {
  CheckModel("flex_shapes", Local("flex/flex_shapes.xml"));
  CheckModel("flex_flag", Corpus("flex/flag.xml"));
}

// Cameras: modes, orientations, frames, defaults and intrinsics (cam_* fields).
TEST(CompilerConformance, Cameras) { CheckModel("cameras", Local("cameras.xml")); }
// Textures (builtin patterns and PNG files), materials and lights.
TEST(CompilerConformance, Visual) { CheckModel("visual", Local("visual.xml")); }

// Trees, dof length scales and sleep policies (explicit, and the compiler's choices).
TEST(CompilerConformance, SleepTrees) { CheckModel("sleep_trees", Local("sleep_trees.xml")); }
// <compiler fusestatic>: static bodies fused into their parents, names that keep them,
// MuJoCo 3.5.1's leftovers (cameras and lights keep their local pose, stale tree nodes).
// Goldens from native MuJoCo (tools/dump_model.mjs --native): the WebAssembly oracle
// crashes on these models.
TEST(CompilerConformance, FuseStatic) {
  CheckModel("fuse_static", Local("fuse_static.xml"));
  CheckModel("fuse_static_refs", Local("fuse_static_refs.xml"));
}
TEST(CompilerConformance, FreeJointAlignment) { CheckModel("align_free", Local("align_free.xml")); }

TEST(CompilerConformance, HFieldFiles) { CheckModel("hfield_files", Local("hfield_files.xml")); }
// Muscle lengthranges MuJoCo finds by simulation: a limited hinge, and arm26's tendons.
TEST(CompilerConformance, LengthRangeBySimulation) {
  CheckModel("lengthrange_sim", Local("lengthrange_sim.xml"));
}
TEST(CompilerConformance, Arm26) { CheckModel("arm26", Corpus("tendon_arm/arm26.xml")); }
// Meshes (tests/meshes): files and inline data, inertia modes, hulls, fitted primitives.
TEST(CompilerConformance, MeshAssets) {
  CheckModel("mesh_assets", std::string(SIMLAB_SOURCE_DIR) + "/tests/meshes/mesh_assets.xml");
}
// Builtin meshes (every shape MuJoCo 3.5 makes) and height fields (hfield_*, geom sizes).
TEST(CompilerConformance, BuiltinMeshesHFields) {
  CheckModel("builtin_hfield", Local("builtin_hfield.xml"));
}
// Fitted primitives; and a point cloud (faces from its hull, maxhullvert) and a torus.
TEST(CompilerConformance, MeshFit) {
  for (const char* name : {"mesh_fit", "mesh_fitaabb", "mesh_cloud"}) {
    CheckModel(name, std::string(SIMLAB_SOURCE_DIR) + "/tests/meshes/" + name + ".xml");
  }
}
// Taxel meshes (tests/sensors/tactile.xml): plates (one with refquat and scale), a wedge
// and inline normals, each with a normal and two tangents per vertex (mesh_normal).
TEST(CompilerConformance, TactileMeshes) {
  CheckModel("tactile", std::string(SIMLAB_SOURCE_DIR) + "/tests/sensors/tactile.xml");
}

// Model statistics (extent, meansize, meanmass, meaninertia, center) as native MuJoCo
// 3.12 computes them at qpos0 (printed from mjModel.stat): the humanoid (its <statistic>
// gives the centre), the car, the lesson's gantry, and a model of one infinite plane
// whose extent comes from MuJoCo's default meansize (its <statistic> then sets 0.05).
TEST(CompilerConformance, StatisticsAsMuJoCo) {
  struct Case {
    std::string path;
    std::array<double, 7> stat;
  };
  const Case cases[] = {
      {Corpus("humanoid/humanoid.xml"),
       {1.6674751155486451, 0.15699535486057806, 2.5527513263513337, 6.5819984714869193, 0, 0, 0.7}},
      {Corpus("car/car.xml"), {0.6, 0.069798263870101782, 0.18101150082346218, 0.20429129610969177, 0, 0, 0}},
      {std::string(SIMLAB_SOURCE_DIR) + "/models/gantry_gripper.xml",
       {1.5004998438475798, 0.047121230647306327, 0.124, 0.17564218181818186, 0, 0, 0.40012496096189504}},
      {Corpus("flex/scene.xml"), {0.4, 0.05, 1, 1, 0, 0, 0}},
  };
  for (const Case& c : cases) {
    Model m = LoadXml(c.path);
    const Statistic& s = m.stat;
    std::array<double, 7> ours = {s.extent, s.meansize, s.meanmass, s.meaninertia, s.center[0], s.center[1], s.center[2]};
    for (int k = 0; k < 7; k++) EXPECT_NEAR(ours[k], c.stat[k], 1e-12 * (1 + std::abs(c.stat[k]))) << c.path << " [" << k << "]";
  }
}

// Skins inline (in <asset> and <deformable>) and from a .skn file: weights normalized over
// the bones, bind quaternions normalized, materials and groups.
TEST(CompilerConformance, Skins) { CheckModel("skins", Local("skins.xml")); }

// Mesh polygons in MuJoCo 3.5.1's order, with and without a hull.
TEST(CompilerConformance, MeshPolygons) { CheckModel("mesh_polygons", Local("mesh_polygons.xml")); }

}  // namespace
}  // namespace simlab
