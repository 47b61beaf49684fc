// The Python objects of the simlab module: MjModel and MjData wrap the engine's Model and
// Data; their arrays are numpy views of the engine's memory (no copies).
//
// Lifetimes: the engine's Model and Data are shared between their wrapper and a "keeper"
// capsule, the base of every numpy view into them, so that a view outlives the MjModel or
// MjData it came from without holding that object (which would make a reference cycle
// through the wrapper's cache of named views). MjData keeps its MjModel. Named views
// (model.actuator("grip")) and their arrays are made once and cached in the wrapper, so
// that asking twice gives the same Python objects, as in MuJoCo.
#ifndef SIMLAB_PYTHON_WRAPPERS_H_
#define SIMLAB_PYTHON_WRAPPERS_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <functional>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"
#include "simlab/named.h"
#include "simlab/simlab.h"

namespace simlab::python {

namespace py = pybind11;

// A Python object that keeps `memory` alive as long as any view has it as its base.
template <typename T>
py::capsule Keeper(std::shared_ptr<T> memory) {
  return py::capsule(new std::shared_ptr<T>(std::move(memory)),
                     [](void* p) { delete static_cast<std::shared_ptr<T>*>(p); });
}

// A named object's view (model.actuator("grip"), data.joint(3)): its attributes' numpy
// views, made when first asked for.
struct NamedView {
  Named named;
  bool in_data;                             // a Data view (for its class name)
  py::handle base;                          // the keeper of the memory viewed
  std::map<std::string, py::object> arrays; // attribute -> view, once made
};

// Named views of one Model or Data, made on first use: (kind, id) -> view.
using ViewCache = std::map<std::pair<int, int>, std::unique_ptr<NamedView>>;

struct PyModel {
  std::shared_ptr<Model> model;
  py::capsule keeper;             // the base of every array view into the model
  std::vector<FieldView> fields;  // every array, in table order (views stay valid: the
                                  // arrays of a compiled Model are never resized)
  ViewCache views;
  std::string path;  // the file it was loaded from (from_xml_path), for simlab.lint

  explicit PyModel(Model m)
      : model(std::make_shared<Model>(std::move(m))), keeper(Keeper(model)),
        fields(model->Fields()) {}
  PyModel(PyModel&&) = default;
  PyModel(const PyModel&) = delete;  // views belong to one MjModel; copy its Model instead
};

struct PyData {
  std::shared_ptr<Model> model;  // the model's memory, shared with its MjModel
  py::object model_object;       // the MjModel (data.model)
  std::shared_ptr<Data> memory;  // the engine's Data, shared with the keeper
  Data& data;
  py::capsule keeper;             // the base of every array view into the data
  std::vector<FieldView> fields;  // the fixed-size arrays, in table order
  ViewCache views;

  PyData(const PyModel& m, py::object model_obj)
      : PyData(m.model, std::move(model_obj), std::make_shared<Data>(MakeData(*m.model))) {}
  // A copy of another MjData (mj_copyData, copy.copy): same model, same numbers.
  explicit PyData(const PyData& other)
      : PyData(other.model, other.model_object, std::make_shared<Data>(other.data)) {}

 private:
  PyData(std::shared_ptr<Model> m, py::object model_obj, std::shared_ptr<Data> d)
      : model(std::move(m)), model_object(std::move(model_obj)), memory(std::move(d)),
        data(*memory), keeper(Keeper(memory)), fields(DataFields(*model, data)) {}
};

// An engine error while simulating (a bad state signature, keyframe or id): Python's
// simlab.FatalError, as MuJoCo raises mujoco.FatalError for its mju_error.
class FatalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// f(), with an engine Error turned into a FatalError that names `function`.
template <typename F>
auto OrFatal(const char* function, F f) {
  try {
    return f();
  } catch (const Error& e) {
    throw FatalError(std::string(function) + ": " + e.what());
  }
}

// Whether d was made for a model of m's sizes (MuJoCo requires it of every call).
void CheckCompatible(const PyModel& m, const PyData& d);

// A numpy array over `count` elements at ptr, shaped (rows,) or (rows, cols), whose base
// is `owner` (the array keeps it alive; writes go to the engine's memory).
template <typename T>
py::array ViewOf(T* ptr, std::vector<py::ssize_t> shape, py::handle owner) {
  return py::array(py::dtype::of<T>(), std::move(shape), ptr, owner);
}

// The numpy view of one field, in MuJoCo's shape (FieldView::one_dimensional), based on
// `base` (a keeper).
py::array FieldArray(const FieldView& f, py::handle base);

// Copies `value` into the array `target` (numpy broadcasting; shape errors raise).
void AssignInto(const py::array& target, const py::handle& value);

// The id a view's key names: a name (KeyError if none has it) or an index.
int IdFromKey(const Model& m, ObjType kind, py::handle key);
// Object `id`'s view from the wrapper's cache, made by `make` on first use; the Python
// view keeps `self` (the MjModel or MjData) alive.
template <typename W>
py::object CachedView(W& w, py::object self, ObjType kind, int id,
                      const std::function<Named()>& make) {
  std::unique_ptr<NamedView>& slot = w.views[{kind, id}];
  if (!slot) {
    slot = std::make_unique<NamedView>(NamedView{make(), std::is_same_v<W, PyData>, w.keeper, {}});
  }
  return py::cast(slot.get(), py::return_value_policy::reference_internal, self);
}

// Every array of a field table (as Model::Fields or DataFields list them, for any
// model: only names and shapes are read) as a read-write numpy property of cls. W is
// PyModel or PyData, whose `fields` follow the same table; assigning copies into the array.
template <typename W>
void DefineArrays(py::class_<W>& cls, const std::vector<FieldView>& table) {
  for (size_t i = 0; i < table.size(); i++) {
    cls.def_property(
        table[i].name,
        [i](const W& w) { return FieldArray(w.fields[i], w.keeper); },
        [i](const W& w, py::handle value) { AssignInto(FieldArray(w.fields[i], w.keeper), value); });
  }
}

// cls.actuator("grip"), cls.joint(3)...: a method per kind, under MuJoCo's view name and
// its alternative; make(wrapper, kind, id) builds the view's Named on first use.
template <typename W, typename Make>
void DefineNamedViews(py::class_<W>& cls, std::span<const ObjType> kinds, bool data, Make make) {
  for (ObjType kind : kinds) {
    auto view = [kind, make](py::object self, py::handle key) {
      W& w = self.cast<W&>();
      int id = IdFromKey(*w.model, kind, key);
      return CachedView(w, self, kind, id, [&] { return make(w, kind, id); });
    };
    cls.def(ViewName(kind), view, py::arg("name") = "");
    if (*ViewAltName(kind, data)) cls.def(ViewAltName(kind, data), view, py::arg("name") = "");
  }
}

// Parts of the module, defined in their own files.
void DefineEnums(py::module_& m);
void DefineModel(py::module_& m);
void DefineData(py::module_& m);
void DefineViews(py::module_& m);
void DefineFunctions(py::module_& m);
void DefineRollout(py::module_& m);

}  // namespace simlab::python

#endif  // SIMLAB_PYTHON_WRAPPERS_H_
