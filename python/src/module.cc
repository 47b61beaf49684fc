// The compiled part of the `simlab` Python package (simlab._simlab): MuJoCo's Python API
// on the simlab engine. The package's __init__.py re-exports it as `simlab`.
#include "simlab/named.h"
#include "simlab/simlab.h"
#include "wrappers.h"

namespace simlab::python {
namespace {

// Engine errors as MuJoCo's bindings raise them: an unknown name is a KeyError, an index
// out of range an IndexError, a model that does not load a ValueError (file:line: what).
void TranslateErrors() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UnknownName& e) {
      PyErr_SetString(PyExc_KeyError, e.what());
    } catch (const BadIndex& e) {
      PyErr_SetString(PyExc_IndexError, e.what());
    } catch (const Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace
}  // namespace simlab::python

PYBIND11_MODULE(_simlab, m) {
  using namespace simlab::python;
  m.doc() = "simlab: MuJoCo's Python API on the simlab engine";
  py::register_exception<FatalError>(m, "FatalError");
  TranslateErrors();
  DefineEnums(m);
  DefineViews(m);
  DefineModel(m);
  DefineData(m);
  DefineFunctions(m);
  DefineRollout(m);
  m.attr("REFERENCE_VERSION") = simlab::ReferenceVersion();
}
