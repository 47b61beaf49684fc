// MjModel: loading (from_xml_path, from_xml_string with assets), sizes, every array of
// the field table as a numpy view, model.opt and model.stat, and named views.
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "simlab/simlab.h"
#include "wrappers.h"

namespace simlab::python {

namespace {

// {file name: bytes} from Python.
Assets AssetsFrom(const std::optional<py::dict>& assets) {
  Assets out;
  if (!assets) return out;
  for (const auto& [name, bytes] : *assets) {
    if (!py::isinstance<py::bytes>(bytes) && !py::isinstance<py::str>(bytes)) {
      throw py::type_error("assets values must be bytes (asset '" +
                           py::str(name).cast<std::string>() + "')");
    }
    out[py::str(name).cast<std::string>()] = bytes.cast<std::string>();
  }
  return out;
}

PyModel FromXmlString(const std::string& xml, const std::optional<py::dict>& assets) {
  Assets files = AssetsFrom(assets);
  py::gil_scoped_release release;
  return PyModel(LoadXmlString(xml, "<string>", files));
}

PyModel FromXmlPath(const std::string& path, const std::optional<py::dict>& assets) {
  Assets files = AssetsFrom(assets);
  py::gil_scoped_release release;
  if (files.empty()) {
    PyModel loaded(LoadXml(path));
    loaded.path = path;
    return loaded;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return PyModel(LoadXmlString(text.str(), path, files));
}

// A scalar option as a read-write property of MjOption (or MjStatistic).
template <typename Cls, typename Struct, typename T>
void Scalar(Cls& cls, const char* name, T Struct::*member) {
  cls.def_property(
      name, [member](const typename Cls::type& w) { return w.get()->*member; },
      [member](typename Cls::type& w, T value) { w.get()->*member = value; });
}

// A fixed-size array option as a numpy view (assigning copies into it).
template <typename Cls, typename Struct, size_t N>
void Array(Cls& cls, const char* name, std::array<double, N> Struct::*member) {
  cls.def_property(
      name,
      [member](py::object self) {
        auto& w = self.cast<typename Cls::type&>();
        return ViewOf((w.get()->*member).data(), {static_cast<py::ssize_t>(N)}, self);
      },
      [member](py::object self, py::handle value) {
        auto& w = self.cast<typename Cls::type&>();
        AssignInto(ViewOf((w.get()->*member).data(), {static_cast<py::ssize_t>(N)}, self), value);
      });
}

// model.opt and model.stat: views of the model's Option and Statistic.
template <typename Struct>
struct PartOfModel {
  Struct* part;
  py::object owner;  // the MjModel
  Struct* get() const { return part; }
};
using PyOption = PartOfModel<Option>;
using PyStatistic = PartOfModel<Statistic>;

void DefineOption(py::module_& m) {
  py::class_<PyOption> cls(m, "MjOption");
  Scalar(cls, "timestep", &Option::timestep);
  Scalar(cls, "impratio", &Option::impratio);
  Scalar(cls, "tolerance", &Option::tolerance);
  Scalar(cls, "ls_tolerance", &Option::ls_tolerance);
  Scalar(cls, "noslip_tolerance", &Option::noslip_tolerance);
  Scalar(cls, "ccd_tolerance", &Option::ccd_tolerance);
  Array(cls, "gravity", &Option::gravity);
  Array(cls, "wind", &Option::wind);
  Array(cls, "magnetic", &Option::magnetic);
  Scalar(cls, "density", &Option::density);
  Scalar(cls, "viscosity", &Option::viscosity);
  Scalar(cls, "o_margin", &Option::o_margin);
  Array(cls, "o_solref", &Option::o_solref);
  Array(cls, "o_solimp", &Option::o_solimp);
  Array(cls, "o_friction", &Option::o_friction);
  Scalar(cls, "integrator", &Option::integrator);
  Scalar(cls, "cone", &Option::cone);
  Scalar(cls, "jacobian", &Option::jacobian);
  Scalar(cls, "solver", &Option::solver);
  Scalar(cls, "iterations", &Option::iterations);
  Scalar(cls, "ls_iterations", &Option::ls_iterations);
  Scalar(cls, "noslip_iterations", &Option::noslip_iterations);
  Scalar(cls, "ccd_iterations", &Option::ccd_iterations);
  Scalar(cls, "sdf_initpoints", &Option::sdf_initpoints);
  Scalar(cls, "sdf_iterations", &Option::sdf_iterations);
  Scalar(cls, "disableflags", &Option::disableflags);
  Scalar(cls, "enableflags", &Option::enableflags);
  Scalar(cls, "disableactuator", &Option::disableactuator);
}

void DefineStatistic(py::module_& m) {
  py::class_<PyStatistic> cls(m, "MjStatistic");
  Scalar(cls, "meaninertia", &Statistic::meaninertia);
  Scalar(cls, "meanmass", &Statistic::meanmass);
  Scalar(cls, "meansize", &Statistic::meansize);
  Scalar(cls, "extent", &Statistic::extent);
  Array(cls, "center", &Statistic::center);
}

// Loading, copies, sizes, options.
void DefineModelBasics(py::class_<PyModel>& cls) {
  cls.def_static("from_xml_string", &FromXmlString, py::arg("xml"),
                 py::arg("assets") = py::none());
  cls.def_static("from_xml_path", &FromXmlPath, py::arg("filename"),
                 py::arg("assets") = py::none());
  cls.def("__copy__", [](const PyModel& w) { return PyModel(*w.model); });
  cls.def("__deepcopy__", [](const PyModel& w, py::dict) { return PyModel(*w.model); });
#define SIMLAB_X(size) \
  cls.def_property_readonly(#size, [](const PyModel& w) { return w.model->size; });
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  cls.def_property_readonly("opt", [](py::object self) {
    return PyOption{&self.cast<PyModel&>().model->opt, self};
  });
  cls.def_property_readonly("stat", [](py::object self) {
    return PyStatistic{&self.cast<PyModel&>().model->stat, self};
  });
}



}  // namespace

void DefineModel(py::module_& m) {
  DefineOption(m);
  DefineStatistic(m);
  py::class_<PyModel> cls(m, "MjModel");
  DefineModelBasics(cls);
  DefineArrays(cls, Model().Fields());
  DefineNamedViews(cls, ModelViewKinds(), false, [](PyModel& w, ObjType kind, int id) {
    return ModelObject(*w.model, kind, id);
  });
}

}  // namespace simlab::python
