// The compiler's driver, and the public loading functions.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "compiler/compiler.h"
#include "simlab/plugin.h"
#include "mjcf/assets.h"
#include "mjcf/error.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"
#include "simlab/simlab.h"

namespace simlab {

namespace compiler {

namespace {

// Sizes of everything outside the tree.
void SectionSizes(const mjcf::ModelSpec& spec, Model* m) {
  m->ntendon = static_cast<int>(spec.tendons.size());
  m->nwrap = 0;
  for (const mjcf::TendonSpec& t : spec.tendons) m->nwrap += static_cast<int>(t.wraps.size());
  m->nactuator = static_cast<int>(spec.actuators.size());
  m->nu = m->nout = m->na = 0;
  for (const mjcf::ActuatorSpec& a : spec.actuators) {
    ActuatorShape shape = ActuatorShapeOf(a);
    m->nu += shape.ctrlnum;
    m->nout += shape.outnum;
    m->na += shape.actnum;
  }
  m->nkey = static_cast<int>(spec.keys.size());
  m->neq = static_cast<int>(spec.equalities.size());
  m->npair = static_cast<int>(spec.pairs.size());
  m->nexclude = static_cast<int>(spec.excludes.size());
  m->nsensor = static_cast<int>(spec.sensors.size());
  m->nplugin = static_cast<int>(spec.plugin_instances.size() + spec.implicit_instances.size());
  m->nuser_sensor = NUserSensor(spec);

  // <size nuser_sensor> numbers for each sensor: within the budget of one array.
  uint64_t bytes = mjcf::MulBytes(mjcf::MulBytes(m->nsensor, m->nuser_sensor), sizeof(double));
  if (bytes > mjcf::kMaxArrayBytes) {
    std::string request = mjcf::AttrText("nuser_sensor", std::to_string(m->nuser_sensor)) +
                          " for " + std::to_string(m->nsensor) + " sensors";
    mjcf::ThrowAt(spec.size_src, mjcf::OverBudget(request, bytes, "sensor user numbers",
                                                  mjcf::kMaxArrayBytes));
  }
}

// Every array of the Model together, from the field table and the sizes, before they
// are allocated: within the budget of one Model (the largest array is named).
void CheckModelBudget(const mjcf::ModelSpec& spec, const Model& m) {
#define SIMLAB_X(size) [[maybe_unused]] uint64_t size = static_cast<uint64_t>(m.size);
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  nmocap3 = 3 * nmocap;
  nmocap4 = 4 * nmocap;
  uint64_t total = 0, largest = 0;
  const char* largest_name = "";
#define SIMLAB_X(type, name, rows, cols)                                        \
  {                                                                             \
    uint64_t bytes = mjcf::MulBytes(mjcf::MulBytes(rows, cols), sizeof(type)); \
    total = mjcf::AddBytes(total, bytes);                                       \
    if (bytes > largest) largest = bytes, largest_name = #name;                 \
  }
  SIMLAB_MODEL_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  if (total <= mjcf::kMaxModelBytes) return;
  mjcf::ThrowAt({spec.file, 0, "", ""},
                "the model is too large: its arrays need " + mjcf::ByteSize(total) +
                    " (the largest, " + largest_name + ", " + mjcf::ByteSize(largest) +
                    "), over the " + mjcf::ByteSize(mjcf::kMaxModelBytes) +
                    " budget of one Model");
}

// Body pairs are ordered and found by MuJoCo's signature (body1 << 16) + body2 in an int
// (pair_signature, exclude_signature, the broad phase), which holds body ids below
// 32768 only.
constexpr int kMaxBodies = 32768;
void CheckBodyCount(const mjcf::ModelSpec& spec, const CompileState& state) {
  if (state.bodies.size() <= static_cast<size_t>(kMaxBodies)) return;
  mjcf::ThrowAt({spec.file, 0, "", ""},
                "too many bodies: the model has " + std::to_string(state.bodies.size()) +
                    " (the world included), more than the " + std::to_string(kMaxBodies) +
                    " that MuJoCo's body-pair signatures (body1 << 16) + body2 can number");
}

// The Data the model will need, within the budget of one Data (MakeData refuses more;
// here the message names the model's file). Before the constants, which make a Data.
void CheckDataBudget(const mjcf::ModelSpec& spec, const Model& m) {
  std::string over = DataOverBudget(m);
  if (!over.empty()) mjcf::ThrowAt({spec.file, 0, "", ""}, over);
}

// The sources of the tree's elements (in compiled order) and of the sections' (in the
// spec's order, which the compiler keeps).
void CollectSources(const mjcf::ModelSpec& spec, const CompileState& state, ElementSources* out) {
  for (const BodyState& b : state.bodies) {
    out->body.push_back(b.spec ? b.spec->src : mjcf::Source{spec.file, 0, "worldbody", "world"});
  }
  for (const JointState& j : state.joints) out->joint.push_back(j.spec->src);
  for (const GeomState& g : state.geoms) out->geom.push_back(g.spec->src);
  for (const SiteState& s : state.sites) out->site.push_back(s.spec->src);
  for (const mjcf::TendonSpec& t : spec.tendons) out->tendon.push_back(t.src);
  for (const mjcf::ActuatorSpec& a : spec.actuators) out->actuator.push_back(a.src);
  for (const mjcf::EqualitySpec& e : spec.equalities) out->equality.push_back(e.src);
  for (const mjcf::KeySpec& k : spec.keys) out->key.push_back(k.src);
}

// Trees marked sleep="init" must be able to start asleep (with their whole island): a
// reset tells, as MuJoCo's compiler does. The error points at the first body marked init.
void CheckInitialSleep(const CompileState& state, const Model& m) {
  if (!(m.opt.enableflags & kEnableSleep)) return;
  auto first = std::find(m.tree_sleep_policy.begin(), m.tree_sleep_policy.end(), kSleepInit);
  if (first == m.tree_sleep_policy.end()) return;
  try {
    Data d = MakeData(m);
  } catch (const Error& e) {
    int body = m.tree_bodyadr[first - m.tree_sleep_policy.begin()];
    mjcf::ThrowAt(state.bodies[body].spec->src, e.what());
  }
}

}  // namespace

Model Compile(const mjcf::ModelSpec& spec, ElementSources* sources) {
  // The tree: flatten, compile bodies and their elements, check masses.
  CompileState state;
  FlattenTree(spec, &state);
  CheckBodyCount(spec, state);
  CompileMeshes(spec, &state);
  CompileHFields(spec, &state);
  std::vector<TextureImage> textures = CompileTextures(spec);
  CompileBodies(&state);
  FuseStaticBodies(spec, &state);
  CompileSkins(spec, &state);
  CompileFlexes(spec, &state);
  CheckMovingBodies(state);
  CheckHFieldCollisions(spec, state);
  CheckSdfCollisions(spec, state);

  // Sizes, then every array.
  Model m;
  CompileOption(spec, &m);
  m.release = state.release;
  m.vis = spec.vis;
  TreeSizes(state, &m);
  m.ncam = CameraCount(state);
  MeshSizes(state, &m);
  HFieldSizes(state, &m);
  SkinSizes(state, &m);
  FlexSizes(state, &m);
  VisualSizes(spec, state, textures, &m);
  SectionSizes(spec, &m);
  CheckModelBudget(spec, m);
  m.Allocate();
  LayoutTree(state, &m);
  CompileCameras(spec, state, &m);
  LayoutMeshes(state, &m);
  LayoutHFields(state, &m);
  LayoutSkins(state, &m);
  LayoutFlexes(spec, state, &m);
  LayoutVisual(spec, state, textures, &m);
  CompileTendons(spec, state, &m);
  CompileEqualities(spec, &m);
  CompileContacts(spec, &m);
  CompileBodyBvh(&m, state);
  CompileFlexBvh(&m, state);
  CompileActuators(spec, state, &m);
  CompileTrees(state, &m);
  CompilePlugins(spec, state, &m);
  CompileKeyframes(spec, state, &m);
  CompileSensors(spec, &m);
  CheckDataBudget(spec, m);

  // Whole-model adjustments and constants at qpos0, computed with nothing asleep.
  int enableflags = m.opt.enableflags;
  m.opt.enableflags &= ~kEnableSleep;
  if (spec.compiler.settotalmass > 0) SetTotalMass(spec.compiler.settotalmass, &m);
  // (the first Data made runs the plugins' init: a bad configuration fails here)
  try {
    ComputeConstants(&m);
  } catch (const PluginInitError& e) {
    mjcf::ThrowAt(PluginInstanceSource(spec, e.instance), e.what());
  }
  CamLightConstants(&m);
  EqualityConstants(&m);
  AutoSpringDamper(state, &m);
  ComputeLengthRanges(spec, &m);
  m.opt.enableflags = enableflags;
  CheckInitialSleep(state, m);

  // Statistics the model gives replace the computed ones (after the length ranges,
  // which MuJoCo simulates with the computed meaninertia).
  if (!std::isnan(spec.meaninertia)) m.stat.meaninertia = spec.meaninertia;
  if (!std::isnan(spec.meanmass)) m.stat.meanmass = spec.meanmass;
  if (!std::isnan(spec.meansize)) m.stat.meansize = spec.meansize;
  if (!std::isnan(spec.extent)) m.stat.extent = spec.extent;
  if (!std::isnan(spec.center[0])) m.stat.center = spec.center;
  m.IndexNames();
  if (sources) CollectSources(spec, state, sources);
  return m;
}

}  // namespace compiler

Model LoadXmlString(const std::string& xml, const std::string& filename) {
  mjcf::ModelSpec spec = mjcf::ReadMjcf(xml, filename);
  return compiler::Compile(spec);
}

Model LoadXmlString(const std::string& xml, const std::string& filename, const Assets& assets) {
  // The assets, keyed by file name, go with the spec to every file the load reads.
  auto files = std::make_shared<const mjcf::AssetFiles>(assets);
  mjcf::ModelSpec spec = mjcf::ReadMjcf(xml, filename, files);
  return compiler::Compile(spec);
}

Model LoadXml(const std::string& path) { return compiler::Compile(mjcf::ReadMjcfFile(path)); }

}  // namespace simlab
