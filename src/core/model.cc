// Model storage generated from the field table: allocation, names, field views.
#include <string>
#include <vector>

#include "core/field_view.h"
#include "simlab/model.h"
#include "simlab/simlab.h"

namespace simlab {

void Model::Allocate() {
  nmocap3 = 3 * nmocap;
  nmocap4 = 4 * nmocap;
#define SIMLAB_X(type, name, rows, cols) name.assign(static_cast<size_t>(rows) * (cols), type{});
  SIMLAB_MODEL_FIELDS(SIMLAB_X)
#undef SIMLAB_X
#define SIMLAB_X(kind, count) kind##_names.resize(count);
  SIMLAB_MODEL_NAMED(SIMLAB_X)
#undef SIMLAB_X
}

const std::vector<std::string>* Model::Names(ObjType type) const {
  switch (type) {
    case kObjBody:
    case kObjXBody: return &body_names;
    case kObjJoint: return &jnt_names;
    case kObjGeom: return &geom_names;
    case kObjSite: return &site_names;
    case kObjCamera: return &cam_names;
    case kObjMesh: return &mesh_names;
    case kObjHfield: return &hfield_names;
    case kObjSkin: return &skin_names;
    case kObjLight: return &light_names;
    case kObjTexture: return &tex_names;
    case kObjMaterial: return &mat_names;
    case kObjPair: return &pair_names;
    case kObjExclude: return &exclude_names;
    case kObjEquality: return &eq_names;
    case kObjTendon: return &tendon_names;
    case kObjActuator: return &actuator_names;
    case kObjSensor: return &sensor_names;
    case kObjKey: return &key_names;
    default: return nullptr;
  }
}

int Model::NameToId(ObjType type, const std::string& name) const {
  const std::vector<std::string>* names = Names(type);
  if (!names || name.empty()) return -1;
  // By hash when the tables are built for these names.
  if (static_cast<size_t>(type) < name_index.size()) {
    const auto& index = name_index[type];
    auto found = index.find(name);
    return found == index.end() ? -1 : found->second;
  }
  // A model put together by hand: scan the names.
  for (size_t i = 0; i < names->size(); i++) {
    if ((*names)[i] == name) return static_cast<int>(i);
  }
  return -1;
}

void Model::IndexNames() {
  // One table per object kind that has names; the first of equal names wins.
  name_index.assign(kObjPlugin + 1, {});
  for (int type = 0; type <= kObjPlugin; type++) {
    const std::vector<std::string>* names = Names(static_cast<ObjType>(type));
    if (!names) continue;
    for (size_t i = 0; i < names->size(); i++) {
      if (!(*names)[i].empty()) name_index[type].emplace((*names)[i], static_cast<int>(i));
    }
  }
}

std::vector<FieldView> Model::Fields() {
  std::vector<FieldView> fields;
#define SIMLAB_X(type, name, rows, cols) fields.push_back(MakeFieldView(#name, #rows, #cols, name, rows, cols));
  SIMLAB_MODEL_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  return fields;
}

}  // namespace simlab

namespace simlab {

int NameToId(const Model& m, ObjType type, const std::string& name) {
  return m.NameToId(type, name);
}

const char* ReferenceVersion() { return "MuJoCo 3.5.1"; }

}  // namespace simlab
