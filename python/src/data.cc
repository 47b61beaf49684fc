// MjData: every array of the field table as a numpy view of the engine's memory, the
// scalars (time, ncon, nefc...), the contacts and constraint rows of the last step (as
// read-only copies: their arrays change size every step), warnings, copies, named views.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/constraint.h"
#include "wrappers.h"

namespace simlab::python {

namespace {

// A read-only numpy copy of n rows of `cols` numbers.
template <typename T>
py::array ReadOnlyCopy(const T* values, py::ssize_t rows, py::ssize_t cols, bool one_d) {
  std::vector<py::ssize_t> shape = {rows};
  if (!one_d) shape.push_back(cols);
  py::array_t<T> out(shape);
  std::copy(values, values + rows * cols, out.mutable_data());
  out.attr("flags").attr("writeable") = false;
  return out;
}

// ---------------------------------------------------------------- contacts

// One Contact member: a scalar or a fixed array.
#define SIMLAB_CONTACT_FIELDS(X)                                                        \
  X(double, dist, 1) X(double, pos, 3) X(double, frame, 9) X(double, includemargin, 1)  \
  X(double, friction, 5) X(double, solref, kNRef) X(double, solreffriction, kNRef)      \
  X(double, solimp, kNImp) X(double, mu, 1) X(double, H, 36) X(int, dim, 1)             \
  X(int, geom1, 1) X(int, geom2, 1) X(int, geom, 2) X(int, flex, 2) X(int, elem, 2)     \
  X(int, vert, 2) X(int, exclude, 1) X(int, efc_address, 1)

// data.contact: the first ncon contacts of the last collision stage.
struct PyContactList {
  py::object owner;  // the MjData
  Data* data;
  int size() const { return data->ncon; }
};

// One contact: contact `index` of an MjData, read and written where it is (for as long
// as the data has that many contacts), or a detached one (MjContact(), copy.copy).
struct PyContact {
  py::object owner;  // the MjData, or None when detached
  Data* data = nullptr;
  int index = 0;
  Contact detached;

  Contact& Get() {
    if (!data) return detached;
    if (index >= data->ncon) {
      throw py::index_error("contact " + std::to_string(index) + " no longer exists (the data has " +
                            std::to_string(data->ncon) + " contacts now)");
    }
    return data->contact[index];
  }
};

// Pointer to a Contact member as an array (scalars as arrays of one).
template <typename T>
const T* AsArray(const T& member) { return &member; }
template <typename T, size_t N>
const T* AsArray(const T (&member)[N]) { return member; }

// One contact's member as Python sees it: a number, or a read-only array (a copy).
template <typename T>
py::object MemberObject(const T& member) { return py::cast(member); }
template <typename T, size_t N>
py::object MemberObject(const T (&member)[N]) { return ReadOnlyCopy<T>(member, N, 1, true); }

// contact.member = value: a number, or as many numbers as the member has.
template <typename T>
void SetMember(T& member, py::handle value) { member = value.cast<T>(); }
template <typename T, size_t N>
void SetMember(T (&member)[N], py::handle value) {
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.size() != static_cast<py::ssize_t>(N)) {
    throw py::value_error("expected " + std::to_string(N) + " numbers");
  }
  std::copy(a.data(), a.data() + N, member);
}

// Column `cols` numbers of each contact's member, as an (ncon,) or (ncon, cols) array.
template <typename T, typename Getter>
py::array ContactColumn(const PyContactList& list, int cols, Getter get) {
  const int n = list.size();
  std::vector<T> values;
  values.reserve(static_cast<size_t>(n) * cols);
  for (int i = 0; i < n; i++) {
    const T* first = get(list.data->contact[i]);
    values.insert(values.end(), first, first + cols);
  }
  return ReadOnlyCopy(values.data(), n, cols, cols == 1);
}

void DefineContact(py::module_& m) {
  py::class_<PyContact> contact(m, "MjContact");
  contact.def(py::init([] { return PyContact{py::none(), nullptr, 0, Contact{}}; }));
  auto detach = [](PyContact& c) { return PyContact{py::none(), nullptr, 0, c.Get()}; };
  contact.def("__copy__", detach);
  contact.def("__deepcopy__", [detach](PyContact& c, py::dict) { return detach(c); });
#define SIMLAB_X(type, name, cols)                                                   \
  contact.def_property(                                                              \
      #name, [](PyContact& c) { return MemberObject(c.Get().name); },               \
      [](PyContact& c, py::handle value) { SetMember(c.Get().name, value); });
  SIMLAB_CONTACT_FIELDS(SIMLAB_X)
#undef SIMLAB_X
}

void DefineContacts(py::module_& m) {
  DefineContact(m);
  // The list: len, indexing, and each member as a column over all contacts (a copy).
  py::class_<PyContactList> list(m, "MjContactList");
  list.def("__len__", &PyContactList::size);
  list.def("__getitem__", [](const PyContactList& l, int i) {
    if (i < 0) i += l.size();
    if (i < 0 || i >= l.size()) throw py::index_error("contact index out of range");
    return PyContact{l.owner, l.data, i, Contact{}};
  });
  list.def("__getitem__", [](const PyContactList& l, py::slice slice) {
    size_t start, stop, step, count;
    if (!slice.compute(l.size(), &start, &stop, &step, &count)) throw py::error_already_set();
    std::vector<PyContact> out;
    for (size_t k = 0; k < count; k++) {
      out.push_back(PyContact{l.owner, l.data, static_cast<int>(start + k * step), Contact{}});
    }
    return out;
  });
#define SIMLAB_X(type, name, cols)                                        \
  list.def_property_readonly(#name, [](const PyContactList& l) {          \
    return ContactColumn<type>(l, cols, [](const Contact& c) { return AsArray(c.name); }); \
  });
  SIMLAB_CONTACT_FIELDS(SIMLAB_X)
#undef SIMLAB_X
}

// ---------------------------------------------------------------- warnings

// data.warning[i].number and .lastinfo, read-write views of the Data's counters.
struct PyWarning {
  py::object owner;
  WarningStat* stat;
};
struct PyWarningList {
  py::object owner;
  WarningStat* stats;
};

// A strided view of one member across MuJoCo's kNumMujocoWarnings entries (simlab's
// own two kinds are not in Python's list: an engine error raises FatalError instead).
py::array WarningColumn(const PyWarningList& l, int WarningStat::*member) {
  return py::array(py::dtype::of<int>(), {static_cast<py::ssize_t>(kNumMujocoWarnings)},
                   {static_cast<py::ssize_t>(sizeof(WarningStat))}, &(l.stats[0].*member),
                   l.owner);
}

void DefineWarnings(py::module_& m) {
  py::class_<PyWarning> warning(m, "MjWarningStat");
  warning.def_property(
      "number", [](const PyWarning& w) { return w.stat->number; },
      [](PyWarning& w, int v) { w.stat->number = v; });
  warning.def_property(
      "lastinfo", [](const PyWarning& w) { return w.stat->lastinfo; },
      [](PyWarning& w, int v) { w.stat->lastinfo = v; });
  py::class_<PyWarningList> list(m, "MjWarningStatList");
  list.def("__len__", [](const PyWarningList&) { return static_cast<int>(kNumMujocoWarnings); });
  list.def("__getitem__", [](const PyWarningList& l, int i) {
    if (i < 0 || i >= kNumMujocoWarnings) throw py::index_error("warning index out of range");
    return PyWarning{l.owner, &l.stats[i]};
  });
  list.def_property_readonly("number", [](const PyWarningList& l) {
    return WarningColumn(l, &WarningStat::number);
  });
  list.def_property_readonly("lastinfo", [](const PyWarningList& l) {
    return WarningColumn(l, &WarningStat::lastinfo);
  });
}

// ---------------------------------------------------------------- MjData

// time, counts, energy, model, warnings, contacts, copies.
void DefineDataBasics(py::class_<PyData>& cls) {
  cls.def(py::init([](py::object model) {
            return std::make_unique<PyData>(model.cast<const PyModel&>(), model);
          }),
          py::arg("model"));
  cls.def("__copy__", [](const PyData& d) { return std::make_unique<PyData>(d); });
  cls.def("__deepcopy__", [](const PyData& d, py::dict) { return std::make_unique<PyData>(d); });
  cls.def_property_readonly("model", [](const PyData& d) { return d.model_object; });
  cls.def_property(
      "time", [](const PyData& d) { return d.data.time; },
      [](PyData& d, double t) { d.data.time = t; });
  cls.def_property_readonly("energy", [](const PyData& d) {
    return ViewOf(d.data.energy, {2}, d.keeper);
  });
#define SIMLAB_COUNT(name) \
  cls.def_property_readonly(#name, [](const PyData& d) { return d.data.name; });
  SIMLAB_COUNT(ncon) SIMLAB_COUNT(nefc) SIMLAB_COUNT(ne) SIMLAB_COUNT(nf) SIMLAB_COUNT(nl)
  SIMLAB_COUNT(nisland) SIMLAB_COUNT(solver_niter)
#undef SIMLAB_COUNT
  cls.def_property_readonly("warning", [](py::object self) {
    return PyWarningList{self, self.cast<PyData&>().data.warning};
  });
  cls.def_property_readonly("contact", [](py::object self) {
    return PyContactList{self, &self.cast<PyData&>().data};
  });
}

// Constraint rows (nefc of them): read-only copies. efc_J is given as the dense nefc x nv
// matrix whatever its layout in Data (compressed rows from 60 dofs on); efc_J_colind and
// the rows' efc_J_rownnz/rowadr give the layout.
void DefineConstraintRows(py::class_<PyData>& cls) {
#define SIMLAB_X(type, name, cols)                                                    \
  cls.def_property_readonly(#name, [](const PyData& d) {                             \
    return ReadOnlyCopy<type>(d.data.name.data(), d.data.nefc, (cols), (cols) == 1);  \
  });
  SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  cls.def_property_readonly("efc_J", [](const PyData& d) {
    const int nv = d.model->nv;
    std::vector<double> dense(static_cast<size_t>(d.data.nefc) * nv);
    for (int r = 0; r < d.data.nefc; r++) {
      EfcRowDense(*d.model, d.data, r, dense.data() + static_cast<size_t>(r) * nv);
    }
    return ReadOnlyCopy<double>(dense.data(), d.data.nefc, nv, false);
  });
  cls.def_property_readonly("efc_J_colind", [](const PyData& d) {
    return ReadOnlyCopy<int>(d.data.efc_J_colind.data(), d.data.nJ, 1, true);
  });
  cls.def_property_readonly("nJ", [](const PyData& d) { return d.data.nJ; });
}

}  // namespace

void DefineData(py::module_& m) {
  DefineContacts(m);
  DefineWarnings(m);
  py::class_<PyData> cls(m, "MjData");
  DefineDataBasics(cls);
  Model empty;
  Data no_data;
  DefineArrays(cls, DataFields(empty, no_data));
  DefineConstraintRows(cls);
  DefineNamedViews(cls, DataViewKinds(), true, [](PyData& w, ObjType kind, int id) {
    return DataObject(*w.model, w.data, kind, id);
  });
}

}  // namespace simlab::python
