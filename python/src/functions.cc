// MuJoCo's mj_* functions, as its Python bindings take them: (model, data, arrays...),
// outputs written into numpy arrays the caller passes. Stepping releases the GIL.
#include <time.h>

#include <string>

#include "engine/engine.h"
#include "simlab/lint.h"
#include "simlab/simlab.h"
#include "simlab/support.h"
#include "wrappers.h"

namespace simlab::python {

namespace {

using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An input of `size` numbers (any array-like; converted to float64).
const double* Input(const InArray& a, py::ssize_t size, const char* name) {
  if (a.size() != size) {
    throw py::type_error(std::string(name) + " must have " + std::to_string(size) +
                         " numbers, not " + std::to_string(a.size()));
  }
  return a.data();
}

// An output the caller passes: a writable, C-contiguous array of `size` numbers of type
// T (float64 or int32), or None where allowed (null).
template <typename T>
T* Output(py::handle a, py::ssize_t size, const char* name, bool allow_none) {
  if (a.is_none()) {
    if (allow_none) return nullptr;
    throw py::type_error(std::string(name) + " must be an array, not None");
  }
  if (!py::isinstance<py::array>(a)) throw py::type_error(std::string(name) + " must be a numpy array");
  py::array arr = py::reinterpret_borrow<py::array>(a);
  if (!arr.dtype().is(py::dtype::of<T>())) {
    throw py::type_error(std::string(name) + " must have dtype " +
                         py::str(py::dtype::of<T>()).cast<std::string>());
  }
  if (!(arr.flags() & py::array::c_style) || !arr.writeable()) {
    throw py::type_error(std::string(name) + " must be C-contiguous and writable");
  }
  if (arr.size() != size) {
    throw py::type_error(std::string(name) + " must have " + std::to_string(size) +
                         " elements, not " + std::to_string(arr.size()));
  }
  return static_cast<T*>(arr.mutable_data());
}

// An engine error raised since d's engine-error count was `errors` (the engine turned it
// into a warning and a reset): FatalError with its message, as MuJoCo's bindings raise
// for the errors that stop MuJoCo.
void RaiseEngineError(const char* function, const Data& d, int errors) {
  if (d.warning[kWarnEngineError].number != errors) {
    throw FatalError(std::string(function) + ": " + d.error);
  }
}

// An object id in range, for functions that index arrays with it.
int CheckedId(int id, int count, const char* what) {
  if (id < 0 || id >= count) {
    throw py::index_error(std::string(what) + " id " + std::to_string(id) + " out of range [0, " +
                          std::to_string(count) + ")");
  }
  return id;
}

// ---------------------------------------------------------------- simulation

void DefineSimulation(py::module_& m) {
  m.def("mj_step", [](const PyModel& mw, PyData& dw, int nstep) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    const int errors = dw.data.warning[kWarnEngineError].number;
    {
      py::gil_scoped_release release;
      for (int i = 0; i < nstep && dw.data.warning[kWarnEngineError].number == errors; i++) {
        Step(model, dw.data);
      }
    }
    RaiseEngineError("mj_step", dw.data, errors);
  }, py::arg("m"), py::arg("d"), py::arg("nstep") = 1,
  "Advances the simulation by one timestep of the model's integrator, nstep times "
  "(the GIL is released meanwhile).");
  // The pipeline stages that take (m, d) and nothing else.
  struct StageFunction {
    const char* name;
    void (*stage)(const Model&, Data&);
    const char* doc;
  };
  const StageFunction stages[] = {
      {"mj_step1", &Step1, "The first half of mj_step: everything up to the velocity stage."},
      {"mj_step2", &Step2, "The second half of mj_step: forces, accelerations, integration."},
      {"mj_forward", &Forward, "Every quantity of the current state, without integrating."},
      {"mj_resetData", &ResetData, "The default state: qpos0, zero velocities and controls."},
      {"mj_fwdPosition", &FwdPosition, "The position stage: kinematics to constraint rows."},
      {"mj_kinematics", &Kinematics, "Body, geom and site poses from qpos."},
      {"mj_comPos", &ComPos, "Centers of mass, composite inertias and motion axes."},
      {"mj_tendon", &Tendon, "Tendon lengths and Jacobians."},
      {"mj_transmission", &Transmission, "Actuator lengths and moment arms."},
      {"mj_subtreeVel", &SubtreeVel, "Subtree linear velocities and angular momenta."},
      {"mj_rnePostConstraint", &RnePostConstraint,
       "Body accelerations and interaction forces (cacc, cfrc_int, cfrc_ext)."},
      {"mj_energyPos", &EnergyPos, "Potential energy into data.energy[0]."},
      {"mj_energyVel", &EnergyVel, "Kinetic energy into data.energy[1]."}};
  for (const StageFunction& f : stages) {
    m.def(f.name, [stage = f.stage, name = f.name](const PyModel& mw, PyData& dw) {
      CheckCompatible(mw, dw);
      const int errors = dw.data.warning[kWarnEngineError].number;
      {
        py::gil_scoped_release release;
        stage(*mw.model, dw.data);
      }
      RaiseEngineError(name, dw.data, errors);
    }, py::arg("m"), py::arg("d"), f.doc);
  }
  // For bench/python/python_overhead.py: a plain C++ loop of Step, timed in thread CPU
  // seconds, so that the module's calls can be compared with the very same machine code.
  m.def("_benchmark_step_loop", [](const PyModel& mw, PyData& dw, int nstep) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    Data& data = dw.data;
    timespec begin, end;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &begin);
    for (int i = 0; i < nstep; i++) Step(model, data);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &end);
    return (end.tv_sec - begin.tv_sec) + 1e-9 * (end.tv_nsec - begin.tv_nsec);
  }, py::arg("m"), py::arg("d"), py::arg("nstep"));
  m.def("mj_resetDataKeyframe", [](const PyModel& mw, PyData& dw, int key) {
    CheckCompatible(mw, dw);
    OrFatal("mj_resetDataKeyframe", [&] { ResetDataKeyframe(*mw.model, dw.data, key); });
  }, py::arg("m"), py::arg("d"), py::arg("key"));
  m.def("mj_copyData", [](py::object dest, const PyModel& mw, const PyData& src) {
    PyData& d = dest.cast<PyData&>();
    CheckCompatible(mw, d);
    CheckCompatible(mw, src);
    d.data = src.data;
    return dest;
  }, py::arg("dest"), py::arg("m"), py::arg("src"));
}

// ---------------------------------------------------------------- names

void DefineNames(py::module_& m) {
  m.def("mj_name2id", [](const PyModel& mw, int type, const std::string& name) {
    return mw.model->NameToId(static_cast<ObjType>(type), name);
  }, py::arg("m"), py::arg("type"), py::arg("name"));
  m.def("mj_id2name", [](const PyModel& mw, int type, int id) -> py::object {
    const std::vector<std::string>* names = mw.model->Names(static_cast<ObjType>(type));
    if (!names || id < 0 || id >= static_cast<int>(names->size()) || (*names)[id].empty()) {
      return py::none();
    }
    return py::str((*names)[id]);
  }, py::arg("m"), py::arg("type"), py::arg("id"));
}

// ---------------------------------------------------------------- Jacobians

void DefineJacobians(py::module_& m) {
  m.def("mj_jac", [](const PyModel& mw, const PyData& dw, py::handle jacp, py::handle jacr,
                     const InArray& point, int body) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    CheckedId(body, model.nbody, "body");
    Jac(model, dw.data, Output<double>(jacp, 3 * model.nv, "jacp", true),
        Output<double>(jacr, 3 * model.nv, "jacr", true), Input(point, 3, "point"), body);
  }, py::arg("m"), py::arg("d"), py::arg("jacp"), py::arg("jacr"), py::arg("point"),
     py::arg("body"));
  // Jacobians at an object's frame: (m, d, jacp, jacr, id).
  using Frame = void (*)(const Model&, const Data&, double*, double*, int);
  struct FrameJacobian {
    const char* name;
    Frame function;
    const char* id_name;
    int Model::*count;
  };
  const FrameJacobian frames[] = {{"mj_jacBody", &JacBody, "body", &Model::nbody},
                                  {"mj_jacBodyCom", &JacBodyCom, "body", &Model::nbody},
                                  {"mj_jacSite", &JacSite, "site", &Model::nsite},
                                  {"mj_jacGeom", &JacGeom, "geom", &Model::ngeom}};
  for (const FrameJacobian& f : frames) {
    m.def(f.name, [f](const PyModel& mw, const PyData& dw, py::handle jacp, py::handle jacr,
                      int id) {
      CheckCompatible(mw, dw);
      const Model& model = *mw.model;
      CheckedId(id, model.*f.count, f.id_name);
      f.function(model, dw.data, Output<double>(jacp, 3 * model.nv, "jacp", true),
                 Output<double>(jacr, 3 * model.nv, "jacr", true), id);
    }, py::arg("m"), py::arg("d"), py::arg("jacp"), py::arg("jacr"), py::arg(f.id_name));
  }
}

// ---------------------------------------------------------------- contacts, rays, M

void DefineQueries(py::module_& m) {
  m.def("mj_contactForce", [](const PyModel& mw, const PyData& dw, int id, py::handle result) {
    CheckCompatible(mw, dw);
    CheckedId(id, dw.data.ncon, "contact");
    ContactForceInFrame(*mw.model, dw.data, id, Output<double>(result, 6, "result", false));
  }, py::arg("m"), py::arg("d"), py::arg("id"), py::arg("result"));
  m.def("mj_ray", [](const PyModel& mw, const PyData& dw, const InArray& pnt, const InArray& vec,
                     py::handle geomgroup, int flg_static, int bodyexclude, py::handle geomid,
                     py::handle normal) {
    CheckCompatible(mw, dw);
    // geomgroup: None for every group, else 6 flags.
    unsigned char groups[6];
    const unsigned char* group_ptr = nullptr;
    if (!geomgroup.is_none()) {
      auto g = py::array_t<unsigned char, py::array::c_style | py::array::forcecast>::ensure(
          geomgroup);
      if (!g || g.size() != 6) throw py::type_error("geomgroup must be None or 6 flags");
      std::copy(g.data(), g.data() + 6, groups);
      group_ptr = groups;
    }
    int hit = -1;
    double distance = RayCast(*mw.model, dw.data, Input(pnt, 3, "pnt"), Input(vec, 3, "vec"),
                              group_ptr, flg_static != 0, bodyexclude, &hit,
                              Output<double>(normal, 3, "normal", true));
    if (int* out = Output<int>(geomid, 1, "geomid", true)) *out = hit;
    return distance;
  }, py::arg("m"), py::arg("d"), py::arg("pnt"), py::arg("vec"), py::arg("geomgroup"),
     py::arg("flg_static"), py::arg("bodyexclude"), py::arg("geomid"),
     py::arg("normal") = py::none());
  m.def("mj_rayFlex", [](const PyModel& mw, const PyData& dw, int flex_layer, int flg_vert,
                         int flg_edge, int flg_face, int flg_skin, int flexid, const InArray& pnt,
                         const InArray& vec, py::handle vertid, py::handle normal) {
    CheckCompatible(mw, dw);
    CheckedId(flexid, mw.model->nflex, "flex");
    int hit = -1;
    double distance = RayCastFlex(*mw.model, dw.data, flex_layer, flg_vert != 0, flg_edge != 0,
                                  flg_face != 0, flg_skin != 0, flexid, Input(pnt, 3, "pnt"),
                                  Input(vec, 3, "vec"), &hit,
                                  Output<double>(normal, 3, "normal", true));
    if (int* out = Output<int>(vertid, 1, "vertid", true); out && distance >= 0) *out = hit;
    return distance;
  }, py::arg("m"), py::arg("d"), py::arg("flex_layer"), py::arg("flg_vert"), py::arg("flg_edge"),
     py::arg("flg_face"), py::arg("flg_skin"), py::arg("flexid"), py::arg("pnt"), py::arg("vec"),
     py::arg("vertid"), py::arg("normal") = py::none());
  m.def("mj_fullM", [](const PyModel& mw, py::handle dst, const InArray& M) {
    const Model& model = *mw.model;
    FullM(model, Output<double>(dst, model.nv * model.nv, "dst", false), Input(M, model.nM, "M"));
  }, py::arg("m"), py::arg("dst"), py::arg("M"));
  m.def("mj_mulM", [](const PyModel& mw, const PyData& dw, py::handle res, const InArray& vec) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    MulM(model, dw.data, Output<double>(res, model.nv, "res", false), Input(vec, model.nv, "vec"));
  }, py::arg("m"), py::arg("d"), py::arg("res"), py::arg("vec"));
}

// ---------------------------------------------------------------- state and history

// Optional input of exactly `size` numbers: null for None.
const double* OptionalInput(const py::object& value, py::ssize_t size, const char* name,
                            InArray* keep) {
  if (value.is_none()) return nullptr;
  *keep = InArray::ensure(value);
  if (!*keep) throw py::type_error(std::string(name) + " must be an array of numbers");
  return Input(*keep, size, name);
}

// Delay buffers of actuators and sensors (nsample samples of 1 or sensor_dim numbers).
void DefineHistory(py::module_& m) {
  m.def("mj_initCtrlHistory", [](const PyModel& mw, PyData& dw, int id, const py::object& times,
                                 const py::object& values) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    const int n = model.actuator_history[2 * CheckedId(id, model.nactuator, "actuator")];
    InArray t, v;
    const double* tp = OptionalInput(times, n, "times", &t);
    const double* vp = OptionalInput(values, n, "values", &v);
    OrFatal("mj_initCtrlHistory", [&] { InitCtrlHistory(model, dw.data, id, tp, vp); });
  }, py::arg("m"), py::arg("d"), py::arg("id"), py::arg("times"), py::arg("values"));
  m.def("mj_initSensorHistory", [](const PyModel& mw, PyData& dw, int id, const py::object& times,
                                   const py::object& values, double phase) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    const int n = model.sensor_history[2 * CheckedId(id, model.nsensor, "sensor")];
    InArray t, v;
    const double* tp = OptionalInput(times, n, "times", &t);
    const double* vp = OptionalInput(values, n * model.sensor_dim[id], "values", &v);
    if (vp && v.ndim() == 2 && (v.shape(0) != n || v.shape(1) != model.sensor_dim[id])) {
      throw py::type_error("values must be nsample x sensor_dim");
    }
    OrFatal("mj_initSensorHistory",
            [&] { InitSensorHistory(model, dw.data, id, tp, vp, phase); });
  }, py::arg("m"), py::arg("d"), py::arg("id"), py::arg("times"), py::arg("values"),
     py::arg("phase"));
  m.def("mj_readSensor", [](const PyModel& mw, const PyData& dw, int id, double time,
                            py::handle result, int interp) {
    CheckCompatible(mw, dw);
    const Model& model = *mw.model;
    double* out = Output<double>(result, model.sensor_dim[CheckedId(id, model.nsensor, "sensor")],
                                 "result", false);
    OrFatal("mj_readSensor", [&] { ReadSensor(model, dw.data, id, time, out, interp); });
  }, py::arg("m"), py::arg("d"), py::arg("id"), py::arg("time"), py::arg("result"),
     py::arg("interp"));
}

void DefineState(py::module_& m) {
  // simlab.lint(model or path, key=-1): the findings of simlab lint (simlab/lint.h) as a
  // list of dicts {check, severity, element, kind, id, file, line, numbers, meaning, advice}.
  m.def("lint", [](const py::object& model, int key) {
    std::string path;
    if (py::isinstance<PyModel>(model)) {
      path = model.cast<const PyModel&>().path;
      if (path.empty()) {
        throw py::value_error("lint reads the model's file: load it with MjModel.from_xml_path "
                              "(without assets), or pass the file's path");
      }
    } else {
      path = py::str(model).cast<std::string>();
    }
    LintReport report;
    {
      py::gil_scoped_release release;
      report = LintFile(path, key);
    }
    py::list findings;
    for (const LintFinding& f : report.findings) {
      py::dict one;
      one["check"] = f.check;
      one["severity"] = LintSeverityName(f.severity);
      one["element"] = f.element;
      one["kind"] = f.kind;
      one["id"] = f.id;
      one["file"] = f.file;
      one["line"] = f.line;
      one["numbers"] = f.numbers;
      one["meaning"] = f.meaning;
      one["advice"] = f.advice;
      findings.append(one);
    }
    return findings;
  }, py::arg("model"), py::arg("key") = -1);

  m.def("mj_stateSize", [](const PyModel& mw, int spec) {
    return OrFatal("mj_stateSize", [&] { return StateSize(*mw.model, spec); });
  }, py::arg("m"), py::arg("spec"));
  m.def("mj_getState", [](const PyModel& mw, const PyData& dw, py::handle state, int spec) {
    CheckCompatible(mw, dw);
    int n = OrFatal("mj_getState", [&] { return StateSize(*mw.model, spec); });
    GetState(*mw.model, dw.data, Output<double>(state, n, "state", false), spec);
  }, py::arg("m"), py::arg("d"), py::arg("state"), py::arg("spec"));
  m.def("mj_setState", [](const PyModel& mw, PyData& dw, const InArray& state, int spec) {
    CheckCompatible(mw, dw);
    int n = OrFatal("mj_setState", [&] { return StateSize(*mw.model, spec); });
    SetState(*mw.model, dw.data, Input(state, n, "state"), spec);
  }, py::arg("m"), py::arg("d"), py::arg("state"), py::arg("spec"));
  DefineHistory(m);
  m.def("mj_readCtrl", [](const PyModel& mw, const PyData& dw, int id, double time, int interp) {
    CheckCompatible(mw, dw);
    return OrFatal("mj_readCtrl", [&] { return ReadCtrl(*mw.model, dw.data, id, time, interp); });
  }, py::arg("m"), py::arg("d"), py::arg("id"), py::arg("time"), py::arg("interp"));
}

}  // namespace

void DefineFunctions(py::module_& m) {
  DefineSimulation(m);
  DefineNames(m);
  DefineJacobians(m);
  DefineQueries(m);
  DefineState(m);
}

}  // namespace simlab::python
