// numpy views of engine arrays, and named views (model.actuator("grip"), data.joint(3))
// made from the engine's field tables (simlab/named.h).
#include <functional>
#include <memory>
#include <algorithm>
#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include "wrappers.h"

namespace simlab::python {

// ---------------------------------------------------------------- arrays

py::array FieldArray(const FieldView& f, py::handle base) {
  std::vector<py::ssize_t> shape = {f.rows};
  if (!f.one_dimensional()) shape.push_back(f.cols);
  // An empty array owns its (empty) memory: a null pointer cannot carry a base.
  if (static_cast<size_t>(f.rows) * f.cols == 0) {
    return f.is_int ? py::array(py::dtype::of<int>(), shape)
                    : py::array(py::dtype::of<double>(), shape);
  }
  return f.is_int ? ViewOf(f.ints, shape, base) : ViewOf(f.doubles, shape, base);
}

void AssignInto(const py::array& target, const py::handle& value) {
  target.attr("__setitem__")(py::ellipsis(), value);
}

void CheckCompatible(const PyModel& m, const PyData& d) {
  if (m.model == d.model) return;
  // Another model object: it must have the sizes d was made for.
  const Model& a = *m.model;
  const Model& b = *d.model;
  bool same = true;
#define SIMLAB_X(size) same = same && a.size == b.size;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  if (!same) throw py::value_error("MjData was made for a model of other sizes");
}

// ---------------------------------------------------------------- named views

namespace {

// The numpy view of one attribute of a named object, based on `base`.
py::array SliceArray(const Slice& s, py::handle base) {
  std::vector<py::ssize_t> shape = {s.shape[0]};
  if (s.ndim == 2) shape.push_back(s.shape[1]);
  if (s.size() == 0) {
    return s.is_int ? py::array(py::dtype::of<int>(), shape)
                    : py::array(py::dtype::of<double>(), shape);
  }
  return s.is_int ? ViewOf(s.ints, shape, base) : ViewOf(s.doubles, shape, base);
}

// view.attr: the attribute's array, made once and kept (so it is the same object
// every time, as in MuJoCo).
py::object Attribute(NamedView& v, const std::string& attr) {
  auto cached = v.arrays.find(attr);
  if (cached != v.arrays.end()) return cached->second;
  const Slice* s = v.named.Find(attr);
  if (!s) {
    throw py::attribute_error("'" + std::string(ViewName(v.named.kind())) +
                              "' view has no attribute '" + attr + "'");
  }
  return v.arrays[attr] = SliceArray(*s, v.base);
}

// view.attr = value writes into the slice (the id and name cannot be set).
void SetAttribute(NamedView& v, const std::string& attr, py::handle value) {
  if (attr == "id" || attr == "name") throw py::attribute_error("can't set attribute '" + attr + "'");
  AssignInto(Attribute(v, attr), value);
}

// The class name MuJoCo gives such a view: _MjDataGeomViews, _MjModelActuatorViews...
std::string ClassName(const NamedView& v) {
  std::string kind = ObjTypeName(v.named.kind());
  if (v.named.kind() == kObjKey) kind = "keyframe";
  kind[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(kind[0])));
  return std::string(v.in_data ? "_MjData" : "_MjModel") + kind + "Views";
}

// "<_MjDataGeomViews\n  id: 1\n  name: 'box'\n  xmat: array([...])\n  ...\n>": the id,
// the name and every attribute in alphabetical order.
std::string Repr(NamedView& v) {
  std::vector<std::string> attrs;
  for (const Slice& s : v.named.attributes()) attrs.push_back(s.attr);
  std::sort(attrs.begin(), attrs.end());
  std::string text = "<" + ClassName(v) + "\n  id: " + std::to_string(v.named.id()) +
                     "\n  name: " + py::repr(py::str(v.named.name())).cast<std::string>();
  for (const std::string& attr : attrs) {
    text += "\n  " + attr + ": " + py::repr(Attribute(v, attr)).cast<std::string>();
  }
  return text + "\n>";
}

}  // namespace

int IdFromKey(const Model& m, ObjType kind, py::handle key) {
  if (py::isinstance<py::str>(key)) return IdOf(m, kind, key.cast<std::string>());
  if (py::isinstance<py::bool_>(key) || !py::hasattr(key, "__index__")) {
    throw py::type_error(std::string(ViewName(kind)) + "() takes a name (str) or an index (int)");
  }
  return key.attr("__index__")().cast<int>();
}

void DefineViews(py::module_& m) {
  py::class_<NamedView> view(m, "_MjNamedView");
  view.def_property_readonly("id", [](const NamedView& v) { return v.named.id(); });
  view.def_property_readonly("name", [](const NamedView& v) { return v.named.name(); });
  view.def("__getattr__", &Attribute);
  view.def("__setattr__", &SetAttribute);
  view.def("__dir__", [](const NamedView& v) {
    std::vector<std::string> names = {"id", "name"};
    for (const Slice& s : v.named.attributes()) names.push_back(s.attr);
    return names;
  });
  view.def("__repr__", &Repr);
}

}  // namespace simlab::python
