// The compiler's driver, and the public loading functions.
#include <cmath>
#include <fstream>
#include <sstream>

#include "compiler/compiler.h"
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
  m->nu = static_cast<int>(spec.actuators.size());
  m->na = 0;
  for (const mjcf::ActuatorSpec& a : spec.actuators) m->na += ActuatorActDim(a);
  m->nkey = static_cast<int>(spec.keys.size());
  m->neq = static_cast<int>(spec.equalities.size());
  m->npair = static_cast<int>(spec.pairs.size());
  m->nexclude = static_cast<int>(spec.excludes.size());
  m->nsensor = static_cast<int>(spec.sensors.size());
  m->nuser_sensor = NUserSensor(spec);
}

}  // namespace

Model Compile(const mjcf::ModelSpec& spec) {
  // The tree: flatten, compile bodies and their elements, check masses.
  CompileState state;
  FlattenTree(spec, &state);
  CompileMeshes(spec, &state);
  CompileHFields(spec, &state);
  CompileBodies(&state);
  CheckMovingBodies(state);
  CheckHFieldCollisions(spec, state);

  // Sizes, then every array.
  Model m;
  CompileOption(spec, &m);
  TreeSizes(state, &m);
  m.ncam = CameraCount(state);
  MeshSizes(state, &m);
  HFieldSizes(state, &m);
  SectionSizes(spec, &m);
  m.Allocate();
  LayoutTree(state, &m);
  CompileCameras(spec, state, &m);
  LayoutMeshes(state, &m);
  LayoutHFields(state, &m);
  CompileTendons(spec, state, &m);
  CompileEqualities(spec, &m);
  CompileContacts(spec, &m);
  CompileActuators(spec, state, &m);
  CompileKeyframes(spec, state, &m);
  CompileSensors(spec, &m);

  // Whole-model adjustments and constants at qpos0.
  if (spec.compiler.settotalmass > 0) SetTotalMass(spec.compiler.settotalmass, &m);
  ComputeConstants(&m);
  CameraConstants(&m);
  EqualityConstants(&m);
  AutoSpringDamper(state, &m);
  ComputeLengthRanges(spec, &m);

  // Statistics the model gives replace the computed ones (after the length ranges,
  // which MuJoCo simulates with the computed meaninertia).
  if (!std::isnan(spec.meaninertia)) m.stat.meaninertia = spec.meaninertia;
  m.IndexNames();
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

Model LoadXml(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read file");
  return LoadXmlString(text.str(), path);
}

}  // namespace simlab
