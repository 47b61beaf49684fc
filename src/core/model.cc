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

int Model::NameToId(ObjType type, const std::string& name) const {
  // Pick the name list of the object kind, then search it.
  const std::vector<std::string>* names = nullptr;
  switch (type) {
    case kObjBody:
    case kObjXBody: names = &body_names; break;
    case kObjJoint: names = &jnt_names; break;
    case kObjGeom: names = &geom_names; break;
    case kObjSite: names = &site_names; break;
    case kObjCamera: names = &cam_names; break;
    case kObjMesh: names = &mesh_names; break;
    case kObjPair: names = &pair_names; break;
    case kObjExclude: names = &exclude_names; break;
    case kObjEquality: names = &eq_names; break;
    case kObjTendon: names = &tendon_names; break;
    case kObjActuator: names = &actuator_names; break;
    case kObjSensor: names = &sensor_names; break;
    case kObjKey: names = &key_names; break;
    default: return -1;
  }
  if (name.empty()) return -1;
  for (size_t i = 0; i < names->size(); i++) {
    if ((*names)[i] == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<FieldView> Model::Fields() {
  std::vector<FieldView> fields;
#define SIMLAB_X(type, name, rows, cols) fields.push_back(MakeFieldView(#name, name, rows, cols));
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
