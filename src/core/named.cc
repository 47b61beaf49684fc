// Named access generated from the field tables: which arrays a kind's view holds, under
// which attribute names, and each object's slice of them (see simlab/named.h).
#include "simlab/named.h"

#include <algorithm>
#include <string>
#include <vector>

namespace simlab {

namespace {

// A view of one kind: the row counts of the arrays it slices, and the prefixes stripped
// from their names, tried in order ("" keeps the whole name; it must come last).
struct ViewSpec {
  ObjType kind;
  std::vector<std::string_view> sizes;
  std::vector<std::string_view> prefixes;
};

// The views MuJoCo's bindings offer on mjModel.
const std::vector<ViewSpec>& ModelViews() {
  static const std::vector<ViewSpec> views = {
      {kObjActuator, {"nactuator", "nu", "nout"}, {"actuator_"}},
      {kObjBody, {"nbody"}, {"body_"}},
      {kObjCamera, {"ncam"}, {"cam_"}},
      {kObjEquality, {"neq"}, {"eq_"}},
      {kObjExclude, {"nexclude"}, {"exclude_"}},
      {kObjGeom, {"ngeom"}, {"geom_"}},
      {kObjHfield, {"nhfield", "nhfielddata"}, {"hfield_"}},
      {kObjJoint, {"njnt", "nq", "nv"}, {"jnt_", "dof_", ""}},
      {kObjMesh, {"nmesh"}, {"mesh_"}},
      {kObjSkin, {"nskin"}, {"skin_"}},
      {kObjPair, {"npair"}, {"pair_"}},
      {kObjSensor, {"nsensor"}, {"sensor_"}},
      {kObjSite, {"nsite"}, {"site_"}},
      {kObjTendon, {"ntendon"}, {"tendon", "ten_"}},
      {kObjKey, {"nkey"}, {"key_"}},
  };
  return views;
}

// The views MuJoCo's bindings offer on mjData.
const std::vector<ViewSpec>& DataViews() {
  static const std::vector<ViewSpec> views = {
      {kObjActuator, {"nactuator", "nu", "nout"}, {"actuator_", ""}},
      {kObjBody, {"nbody"}, {""}},
      {kObjCamera, {"ncam"}, {"cam_"}},
      {kObjGeom, {"ngeom"}, {"geom_"}},
      {kObjJoint, {"njnt", "nq", "nv"}, {""}},
      {kObjSensor, {"nsensordata"}, {"sensor"}},
      {kObjSite, {"nsite"}, {"site_"}},
      {kObjTendon, {"ntendon"}, {"ten_"}},
  };
  return views;
}

std::vector<ObjType> KindsOf(const std::vector<ViewSpec>& views) {
  std::vector<ObjType> kinds;
  for (const ViewSpec& v : views) kinds.push_back(v.kind);
  return kinds;
}

const ViewSpec* FindView(const std::vector<ViewSpec>& views, ObjType kind) {
  for (const ViewSpec& v : views) {
    if (v.kind == kind) return &v;
  }
  return nullptr;
}

// The attribute name of `field` in a view with these prefixes, or "" if none applies.
std::string AttributeName(std::string_view field, const std::vector<std::string_view>& prefixes) {
  for (std::string_view prefix : prefixes) {
    if (field.size() > prefix.size() && field.substr(0, prefix.size()) == prefix) {
      return std::string(field.substr(prefix.size()));
    }
  }
  return "";
}

// Numbers of qpos and of dofs a joint of this type has.
int JointQposCount(int type) { return type == kJointFree ? 7 : type == kJointBall ? 4 : 1; }
int JointDofCount(int type) { return type == kJointFree ? 6 : type == kJointBall ? 3 : 1; }

// Where object `id`'s rows of `f` start (in elements) and the slice's shape.
void Locate(const Model& m, const FieldView& f, int id, Slice* s) {
  std::string_view rows = f.rows_name;
  int first_row = id, nrows = -1;  // nrows -1: one row, shaped (cols,)
  // Rows counted by something other than the objects: find the object's rows.
  if (rows == "nq") {
    first_row = m.jnt_qposadr[id], nrows = JointQposCount(m.jnt_type[id]);
  } else if (rows == "nv") {
    first_row = m.jnt_dofadr[id], nrows = JointDofCount(m.jnt_type[id]);
  } else if (rows == "nu" || rows == "nout") {
    // An actuator's controls and force outputs: one row as one row, several as a block.
    bool controls = rows == "nu";
    first_row = controls ? m.actuator_ctrladr[id] : m.actuator_outadr[id];
    int count = controls ? m.actuator_ctrlnum[id] : m.actuator_outnum[id];
    nrows = count == 1 ? -1 : count;
  } else if (rows == "nsensordata") {
    first_row = m.sensor_adr[id], nrows = m.sensor_dim[id];
  } else if (rows == "nhfielddata") {
    first_row = m.hfield_adr[id];
    s->ndim = 2, s->shape[0] = m.hfield_nrow[id], s->shape[1] = m.hfield_ncol[id];
  }
  // The shape: (cols,) for one row, (nrows,) or (nrows, cols) for several.
  if (rows != "nhfielddata") {
    if (nrows < 0) s->ndim = 1, s->shape[0] = f.cols;
    else if (f.cols == 1) s->ndim = 1, s->shape[0] = nrows;
    else s->ndim = 2, s->shape[0] = nrows, s->shape[1] = f.cols;
  }
  size_t offset = static_cast<size_t>(first_row) * f.cols;
  if (f.is_int) s->ints = f.ints + offset;
  else s->doubles = f.doubles + offset;
}

// The slices of object `id` of the arrays `fields` that belong to `view`.
std::vector<Slice> SlicesOf(const Model& m, const std::vector<FieldView>& fields,
                            const ViewSpec& view, int id) {
  std::vector<Slice> slices;
  for (const FieldView& f : fields) {
    // Only arrays whose rows this view counts, under a name not taken already.
    if (std::find(view.sizes.begin(), view.sizes.end(), f.rows_name) == view.sizes.end()) continue;
    Slice s;
    s.attr = AttributeName(f.name, view.prefixes);
    if (s.attr.empty()) continue;
    bool taken = std::any_of(slices.begin(), slices.end(),
                             [&](const Slice& other) { return other.attr == s.attr; });
    if (taken) continue;
    s.field = f.name;
    s.is_int = f.is_int;
    Locate(m, f, id, &s);
    slices.push_back(std::move(s));
  }
  return slices;
}

// Object count of a kind (from its name list).
int CountOf(const Model& m, ObjType kind) {
  const std::vector<std::string>* names = m.Names(kind);
  return names ? static_cast<int>(names->size()) : 0;
}

void CheckId(const Model& m, ObjType kind, int id) {
  int n = CountOf(m, kind);
  if (id < 0 || id >= n) {
    throw BadIndex("Invalid index " + std::to_string(id) + ". Valid indices from 0 to " +
                   std::to_string(n - 1));
  }
}

const ViewSpec& ViewOrThrow(const std::vector<ViewSpec>& views, ObjType kind, const char* what) {
  const ViewSpec* view = FindView(views, kind);
  if (!view) throw BadIndex(std::string("no ") + what + " view for " + ObjTypeName(kind));
  return *view;
}

std::string NameOf(const Model& m, ObjType kind, int id) { return (*m.Names(kind))[id]; }

}  // namespace

// ---------------------------------------------------------------- Slice

std::span<double> Slice::Doubles() const {
  if (is_int) throw BadIndex(attr + " holds integers");
  return {doubles, size()};
}

std::span<int> Slice::Ints() const {
  if (!is_int) throw BadIndex(attr + " holds real numbers");
  return {ints, size()};
}

double& Slice::operator[](size_t k) const {
  if (k >= size()) {
    throw BadIndex(attr + "[" + std::to_string(k) + "]: it has " + std::to_string(size()) +
                   " numbers");
  }
  return Doubles()[k];
}

// ---------------------------------------------------------------- Named

const Slice* Named::Find(std::string_view attr) const {
  for (const Slice& s : slices_) {
    if (s.attr == attr) return &s;
  }
  return nullptr;
}

const Slice& Named::operator[](std::string_view attr) const {
  if (const Slice* s = Find(attr)) return *s;
  std::string known;
  for (const Slice& s : slices_) known += (known.empty() ? "" : ", ") + s.attr;
  throw BadIndex(std::string(ObjTypeName(kind_)) + " view has no attribute '" +
                 std::string(attr) + "' (it has " + known + ")");
}

// ---------------------------------------------------------------- kinds and names

std::span<const ObjType> ModelViewKinds() {
  static const std::vector<ObjType> kinds = KindsOf(ModelViews());
  return kinds;
}

std::span<const ObjType> DataViewKinds() {
  static const std::vector<ObjType> kinds = KindsOf(DataViews());
  return kinds;
}

const char* ViewName(ObjType kind) {
  switch (kind) {
    case kObjCamera: return "cam";
    case kObjEquality: return "eq";
    case kObjJoint: return "jnt";
    default: return ObjTypeName(kind);
  }
}

const char* ViewAltName(ObjType kind, bool data) {
  switch (kind) {
    case kObjCamera: return "camera";
    case kObjEquality: return "equality";
    case kObjJoint: return "joint";
    case kObjKey: return "keyframe";
    case kObjTendon: return data ? "ten" : "";
    default: return "";
  }
}

int IdOf(const Model& m, ObjType kind, const std::string& name) {
  int id = m.NameToId(kind, name);
  if (id >= 0) return id;
  // MuJoCo's message: the name, then every valid name in order.
  std::vector<std::string> valid;
  if (const std::vector<std::string>* names = m.Names(kind)) {
    for (const std::string& n : *names) {
      if (!n.empty()) valid.push_back(n);
    }
  }
  std::sort(valid.begin(), valid.end());
  std::string list;
  for (const std::string& n : valid) list += (list.empty() ? "'" : ", '") + n + "'";
  throw UnknownName("Invalid name '" + name + "'. Valid names: [" + list + "]");
}

// ---------------------------------------------------------------- views

Named ModelObject(Model& m, ObjType kind, int id) {
  const ViewSpec& view = ViewOrThrow(ModelViews(), kind, "model");
  CheckId(m, kind, id);
  return Named(kind, id, NameOf(m, kind, id), SlicesOf(m, m.Fields(), view, id));
}

Named ModelObject(Model& m, ObjType kind, const std::string& name) {
  ViewOrThrow(ModelViews(), kind, "model");
  return ModelObject(m, kind, IdOf(m, kind, name));
}

Named DataObject(const Model& m, Data& d, ObjType kind, int id) {
  const ViewSpec& view = ViewOrThrow(DataViews(), kind, "data");
  CheckId(m, kind, id);
  return Named(kind, id, NameOf(m, kind, id), SlicesOf(m, DataFields(m, d), view, id));
}

Named DataObject(const Model& m, Data& d, ObjType kind, const std::string& name) {
  ViewOrThrow(DataViews(), kind, "data");
  return DataObject(m, d, kind, IdOf(m, kind, name));
}

}  // namespace simlab
