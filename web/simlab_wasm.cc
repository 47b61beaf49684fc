// The engine for JavaScript (embind), built by tools/build_wasm.sh into
// web/dist/simlab.mjs + simlab.wasm. One Simulation owns a compiled Model and its Data:
//
//   import createSimlab from './dist/simlab.mjs';
//   const simlab = await createSimlab();           // in node: createSimlab({wasmBinary})
//   const sim = new simlab.Simulation('gantry_gripper.xml', xml, {'gripper.xml': text});
//   sim.resetKeyframe(0);                          // or resetKeyframe('home')
//   sim.setData('ctrl', [0.12, 0, 0, 0.04]);
//   sim.step(10);
//   sim.data('qpos');                              // Float64Array copy, MuJoCo's names
//   const id = sim.dataId('xpos');                 // once; then, allocation-free:
//   sim.dataViewAt(id);                            // a view into wasm memory
//   sim.delete();                                  // embind objects are freed by hand
//
// Every failure (bad MJCF, unknown name, index out of range) is thrown as a JavaScript
// Error whose message is simlab::Error's ("file:line: <element>: problem"). The full
// API is listed in web/README.md.
#include <emscripten/bind.h>
#include <emscripten/val.h>
#include <sys/stat.h>

#include <exception>
#include <fstream>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/field_view.h"
#include "engine/engine.h"
#include "simlab/perturb.h"
#include "simlab/lint.h"
#include "simlab/simlab.h"
#include "simlab/state_history.h"

namespace simlab::web {
namespace {

using emscripten::val;

// ---------------------------------------------------------------- errors

// Throws a JavaScript Error carrying the message. Call it outside any try block, with
// nothing else owned by the calling frame (a JS exception skips C++ destructors).
[[noreturn]] void ThrowJs(const std::string& message) {
  val::global("Error").new_(message).throw_();
}

// Runs body(); a C++ exception from it becomes a JavaScript Error with the same text.
template <typename Body>
auto Guarded(Body&& body) -> decltype(body()) {
  std::string message;
  try {
    return body();
  } catch (const std::exception& e) {
    message = e.what();
  }
  ThrowJs(message);
}

// ---------------------------------------------------------------- the in-memory files

// Creates every folder on the way to `path` (an absolute path in emscripten's MEMFS).
void MakeParentFolders(const std::string& path) {
  for (size_t slash = path.find('/', 1); slash != std::string::npos;
       slash = path.find('/', slash + 1)) {
    mkdir(path.substr(0, slash).c_str(), 0777);
  }
}

// Writes one file: a JS string as UTF-8, or a Uint8Array / ArrayBuffer as bytes.
void WriteMemFile(const std::string& path, const val& content) {
  std::string bytes;
  if (content.isString()) {
    bytes = content.as<std::string>();
  } else {
    val array = val::global("Uint8Array").new_(content);
    std::vector<uint8_t> raw = emscripten::convertJSArrayToNumberVector<uint8_t>(array);
    bytes.assign(raw.begin(), raw.end());
  }
  MakeParentFolders(path);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw Error(path + ": cannot write to the in-memory file system");
}

// A relative path that stays inside its model folder (no "..", not absolute).
bool IsSafeRelativePath(const std::string& path) {
  if (path.empty() || path[0] == '/') return false;
  return path != ".." && path.rfind("../", 0) != 0 && path.find("/../") == std::string::npos;
}

// Each model gets a fresh folder, so that files of earlier models never leak in.
std::string NextModelFolder() {
  static int count = 0;
  return "/simlab/model" + std::to_string(count++);
}

// A loader message names files as the caller did ("gantry.xml:3: ..."), without the
// in-memory folder they were written to.
std::string WithoutFolder(std::string message, const std::string& folder) {
  for (size_t at = message.find(folder); at != std::string::npos; at = message.find(folder, at)) {
    message.erase(at, folder.size());
  }
  return message;
}

// ---------------------------------------------------------------- arrays as JS values

// A copy of a field as a Float64Array or Int32Array.
val CopyOf(const FieldView& f) {
  size_t n = static_cast<size_t>(f.rows) * f.cols;
  if (f.is_int) return val::global("Int32Array").new_(emscripten::typed_memory_view(n, f.ints));
  return val::global("Float64Array").new_(emscripten::typed_memory_view(n, f.doubles));
}

// A view into wasm memory (valid until the memory grows or the array is resized).
val ViewOf(const FieldView& f) {
  size_t n = static_cast<size_t>(f.rows) * f.cols;
  if (f.is_int) return val(emscripten::typed_memory_view(n, f.ints));
  return val(emscripten::typed_memory_view(n, f.doubles));
}

// Index of the field named `name` in `fields`, or -1 (compares in place, allocates nothing).
int IndexOfField(const std::vector<FieldView>& fields, const std::string& name) {
  for (size_t i = 0; i < fields.size(); i++) {
    if (name == fields[i].name) return static_cast<int>(i);
  }
  return -1;
}

// The field named `name`; the error names the owner (Model or Data).
const FieldView& FindField(const std::vector<FieldView>& fields, const std::string& name,
                           const char* owner) {
  const int index = IndexOfField(fields, name);
  if (index < 0) throw Error(std::string("no ") + owner + " array named '" + name + "'");
  return fields[index];
}

val NamesOf(const std::vector<FieldView>& fields) {
  val names = val::array();
  for (const FieldView& f : fields) names.call<void>("push", std::string(f.name));
  return names;
}

// { rows, cols, type } of a field.
val ShapeOf(const FieldView& f) {
  val shape = val::object();
  shape.set("rows", f.rows);
  shape.set("cols", f.cols);
  shape.set("type", std::string(f.is_int ? "int" : "double"));
  return shape;
}

// A JS object of named numbers ({timestep: 0.002, ...}).
// A JS array of n numbers.
val NumberArray(const double* values, int n) {
  val out = val::array();
  for (int i = 0; i < n; i++) out.call<void>("push", values[i]);
  return out;
}

val NumbersObject(std::initializer_list<std::pair<const char*, double>> entries) {
  val object = val::object();
  for (const auto& [name, value] : entries) object.set(name, value);
  return object;
}

val VectorToJs(const double* values, int n) {
  return val::global("Float64Array").new_(emscripten::typed_memory_view(n, values));
}

// ---------------------------------------------------------------- contacts as one array

// Numbers per contact in contactData(): pos(3) frame(9) force(6) geom1 geom2 dist dim.
constexpr int kContactStride = 22;
constexpr int kContactPos = 0, kContactFrame = 3, kContactForce = 12, kContactGeom1 = 18,
              kContactGeom2 = 19, kContactDist = 20, kContactDim = 21;

// Writes contact i of `d` into row `out` (kContactStride numbers).
void WriteContactRow(const Model& m, const Data& d, int i, double* out) {
  const Contact& c = d.contact[i];
  for (int k = 0; k < 3; k++) out[kContactPos + k] = c.pos[k];
  for (int k = 0; k < 9; k++) out[kContactFrame + k] = c.frame[k];
  ContactForce(m, d, i, out + kContactForce);
  out[kContactGeom1] = c.geom[0];
  out[kContactGeom2] = c.geom[1];
  out[kContactDist] = c.dist;
  out[kContactDim] = c.dim;
}

// ---------------------------------------------------------------- names of objects

// The name list of an object kind, by its mjtObj keyword ("joint", "camera", "equality")
// or MuJoCo's field prefix ("body", "jnt", "cam", "eq", "actuator", "key"...).
const std::vector<std::string>* NamesOfKind(const Model& m, const std::string& kind) {
  return m.Names(ObjTypeFromName(kind));
}

const std::vector<std::string>& NamesOfKindOrThrow(const Model& m, const std::string& kind) {
  const std::vector<std::string>* names = NamesOfKind(m, kind);
  if (!names) throw Error("unknown object kind '" + kind + "'");
  return *names;
}

// ---------------------------------------------------------------- the simulation

class Simulation {
 public:
  // Compiles `xml`, written as `filename` into a fresh in-memory folder beside `files`
  // ({relative path: text or bytes}: attached, included and asset files). The model is
  // compiled before the object exists, so a bad file leaves nothing half-built.
  static Simulation* Create(const std::string& filename, const std::string& xml,
                            const val& files) {
    return Guarded([&] {
      std::string folder;
      simlab::Model model = Load(filename, xml, files, &folder);
      auto* sim = new Simulation(std::move(model));
      sim->folder_ = folder;
      sim->filename_ = filename;
      return sim;
    });
  }
  static Simulation* CreateWithoutFiles(const std::string& filename, const std::string& xml) {
    return Create(filename, xml, val::object());
  }

  // ---- state
  // Engine errors (std::exception) reach JavaScript as Errors with their message.
  // A reset starts the history anew from the reset state.
  void Reset() {
    Guarded([&] {
      ResetData(m_, d_);
      RestartHistory();
      return 0;
    });
  }
  void ResetKeyframe(const val& key) {
    Guarded([&] {
      ResetDataKeyframe(m_, d_, KeyIndex(key));
      RestartHistory();
      return 0;
    });
  }
  void Forward() {
    Guarded([&] {
      simlab::Forward(m_, d_);
      return 0;
    });
  }
  // Each step is recorded in the history (stepping on from a scrubbed-back state drops
  // the states after it).
  void Step(int n) {
    Guarded([&] {
      for (int i = 0; i < n; i++) {
        // (a mouse perturbation's springs act in every step)
        ApplyPerturbForce(m_, d_, perturb_);
        simlab::Step(m_, d_);
        history_.Record(m_, d_);
      }
      return 0;
    });
  }
  void StepOnce() { Step(1); }
  double Time() const { return d_.time; }

  // ---- the history of the last seconds (simlab/state_history.h), as simulate's
  // {size, back, capacity, oldest, newest}: states kept, how far back the state now is,
  // and the times of the oldest and newest.
  val History() const {
    return NumbersObject({{"size", history_.size()}, {"back", history_.back()},
                          {"capacity", history_.capacity()},
                          {"oldest", history_.TimeAt(history_.size() - 1)},
                          {"newest", history_.TimeAt(0)}});
  }
  // Loads the state `back` states before the newest and runs forward (for drawing).
  void Scrub(int back) {
    Guarded([&] {
      history_.Load(m_, d_, back);
      simlab::Forward(m_, d_);
      return 0;
    });
  }
  void SetTime(double t) { d_.time = t; }

  // ---- arrays by name (looked up in tables built once: no allocation in wasm memory)
  val Data(const std::string& name) {
    return Guarded([&] { return CopyOf(DataField(name)); });
  }
  val DataView(const std::string& name) {
    return Guarded([&] { return ViewOf(DataField(name)); });
  }
  val ModelArray(const std::string& name) {
    return Guarded([&] { return CopyOf(FindField(model_fields_, name, "Model")); });
  }
  val ModelView(const std::string& name) {
    return Guarded([&] { return ViewOf(FindField(model_fields_, name, "Model")); });
  }
  val DataShape(const std::string& name) {
    return Guarded([&] { return ShapeOf(DataField(name)); });
  }
  val ModelShape(const std::string& name) {
    return Guarded([&] { return ShapeOf(FindField(model_fields_, name, "Model")); });
  }
  val DataNames() { return NamesOf(data_fields_); }
  val ModelNames() { return NamesOf(model_fields_); }

  // A Data array's number (-1 if there is none), for dataViewAt: a number crosses into
  // wasm without the name string embind would copy into wasm memory on every call.
  int DataId(const std::string& name) const { return IndexOfField(data_fields_, name); }
  val DataViewAt(int id) {
    return Guarded([&] {
      if (id < 0 || id >= static_cast<int>(data_fields_.size())) {
        throw Error("Data array id " + std::to_string(id) + " out of range");
      }
      RefreshRowFields();
      return ViewOf(data_fields_[id]);
    });
  }

  // Overwrites a Data array with `values` (an Array or typed array of its full size).
  void SetData(const std::string& name, const val& values) {
    Guarded([&] {
      WriteAll(DataField(name),
               emscripten::convertJSArrayToNumberVector<double>(values));
      return 0;
    });
  }
  // Writes one number: data.NAME[index] = value.
  void SetDataAt(const std::string& name, int index, double value) {
    Guarded([&] {
      const FieldView& f = DataField(name);
      CheckIndex(f, index);
      if (f.is_int) {
        f.ints[index] = static_cast<int>(value);
      } else {
        f.doubles[index] = value;
      }
      return 0;
    });
  }

  // ---- sizes, options, names
  val Sizes() const {
    val sizes = val::object();
#define SIMLAB_X(size) sizes.set(#size, m_.size);
    SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
    return sizes;
  }
  val Option() const;
  val Statistic() const;
  // Scalars of Data: ncon, nefc, ne, nf, nl, nisland, solver_niter, nreset, energy.
  val Counts() const;
  // The warnings counted since the last reset: [{kind, name, number, lastinfo, message}]
  // (message: an engine error's text), and their total, cheap to poll every frame.
  val Warnings() const;
  int WarningTotal() const {
    int total = 0;
    for (const WarningStat& w : d_.warning) total += w.number;
    return total;
  }
  int NameToId(const std::string& kind, const std::string& name) const {
    return Guarded([&] {
      NamesOfKindOrThrow(m_, kind);  // a known kind
      return m_.NameToId(ObjTypeFromName(kind), name);
    });
  }
  std::string IdToName(const std::string& kind, int id) const {
    return Guarded([&] {
      const std::vector<std::string>& names = NamesOfKindOrThrow(m_, kind);
      if (id < 0 || id >= static_cast<int>(names.size())) {
        throw Error(kind + " id " + std::to_string(id) + " out of range (" +
                    std::to_string(names.size()) + " of them)");
      }
      return names[id];
    });
  }
  // The active contacts: [{geom1, geom2, dist, pos, frame, dim, efc_address, force}],
  // ---- the mouse perturbation (simlab/perturb.h), applied before every step
  // Selects `body` at point (x, y, z) of its frame (a body of 0 or less: none), with
  // references at its pose now; returns the mass the point moves with.
  double PerturbSelect(int body, double x, double y, double z) {
    return Guarded([&] {
      PerturbStop();
      perturb_ = {};
      if (body <= 0 || body >= m_.nbody) return 0.0;
      perturb_.select = body;
      perturb_.localpos = {x, y, z};
      InitPerturb(m_, d_, &perturb_);
      return perturb_.localmass;
    });
  }
  // Starts pulling (flags: 1 translate, 2 rotate) from the body's pose now.
  void PerturbStart(int flags) {
    if (perturb_.select <= 0) return;
    InitPerturb(m_, d_, &perturb_);
    perturb_.active = flags & (kPerturbTranslate | kPerturbRotate);
  }
  void PerturbMoveTo(double x, double y, double z) { perturb_.refselpos = {x, y, z}; }
  void PerturbTurnTo(double w, double x, double y, double z) { perturb_.refquat = {w, x, y, z}; }
  // Stops pulling: the body's applied force goes back to zero.
  void PerturbStop() {
    if (perturb_.select > 0 && perturb_.active) {
      std::fill_n(&d_.xfrc_applied[6 * perturb_.select], 6, 0.0);
    }
    perturb_.active = 0;
  }
  // {select, active, localmass, selpos (the point now, world), refselpos, refquat}.
  val PerturbState() const;
  // What viewers read of <visual>: {fovy, azimuth, elevation, stiffness, stiffnessrot,
  // znear, zfar, headlight: {ambient, diffuse, specular, active}, haze}.
  val Visual() const {
    const simlab::Visual& v = m_.vis;
    val out = NumbersObject({{"fovy", v.global.fovy}, {"azimuth", v.global.azimuth},
                             {"elevation", v.global.elevation}, {"stiffness", v.map.stiffness},
                             {"stiffnessrot", v.map.stiffnessrot}, {"znear", v.map.znear},
                             {"zfar", v.map.zfar}});
    val headlight = val::object();
    headlight.set("ambient", NumberArray(v.headlight.ambient.data(), 3));
    headlight.set("diffuse", NumberArray(v.headlight.diffuse.data(), 3));
    headlight.set("specular", NumberArray(v.headlight.specular.data(), 3));
    headlight.set("active", v.headlight.active);
    out.set("headlight", headlight);
    out.set("haze", NumberArray(v.rgba.haze.data(), 4));
    return out;
  }

  // simlab lint's findings for the model's file at keyframe `key` (-1: none): [{check,
  // severity, element, kind, id, file, line, numbers, meaning, advice}], file names as
  // the caller gave them.
  val Lint(int key) const {
    return Guarded([&] {
      const LintReport report = LintFile(folder_ + "/" + filename_, key);
      val list = val::array();
      for (const LintFinding& f : report.findings) {
        val one = val::object();
        one.set("check", f.check);
        one.set("severity", std::string(LintSeverityName(f.severity)));
        one.set("element", f.element);
        one.set("kind", f.kind);
        one.set("id", f.id);
        one.set("file", WithoutFolder(f.file, folder_ + "/"));
        one.set("line", f.line);
        one.set("numbers", f.numbers);
        one.set("meaning", f.meaning);
        one.set("advice", f.advice);
        list.call<void>("push", one);
      }
      return list;
    });
  }

  // force being the 6 numbers of MuJoCo's mj_contactForce (contact frame).
  val Contacts() const;
  // The same as one view of ncon x kContactStride numbers (a buffer kept by the
  // simulation; it grows wasm memory only when more contacts than ever before exist).
  val ContactData();

 private:
  explicit Simulation(simlab::Model&& m)
      : m_(std::move(m)), d_(MakeData(m_)),
        history_(m_, StateHistory::CapacityFor(m_, kHistorySeconds)), model_fields_(m_.Fields()),
        data_fields_(DataFields(m_, d_)), first_row_field_(data_fields_.size()) {
    data_fields_.resize(first_row_field_ + kRowFieldCount);
    RefreshRowFields();
    history_.Record(m_, d_);
  }
  void RestartHistory() {
    history_.Clear();
    history_.Record(m_, d_);
  }
  static simlab::Model Load(const std::string& filename, const std::string& xml,
                            const val& files, std::string* folder);
  int KeyIndex(const val& key) const;
  void RefreshRowFields();
  const FieldView& DataField(const std::string& name) {
    RefreshRowFields();
    return FindField(data_fields_, name, "Data");
  }
  static void CheckIndex(const FieldView& f, int index);
  static void WriteAll(const FieldView& f, const std::vector<double>& values);

  // The constraint-row arrays (efc_*), counted from the table.
  static constexpr size_t kRowFieldCount = 2  // efc_J, efc_J_colind
#define SIMLAB_X(type, name, cols) +1
      SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
      ;

  simlab::Model m_;
  simlab::Data d_;
  simlab::Perturb perturb_;
  // The last kHistorySeconds of simulated time (at most 64 MiB of states).
  static constexpr double kHistorySeconds = 10;
  StateHistory history_;
  // Name -> array tables, built once. Model arrays never move and Data's own arrays are
  // allocated once by MakeData; the efc_* arrays (after first_row_field_) are resized by
  // every step, so their pointers and row counts are read again before each lookup.
  std::vector<FieldView> model_fields_;
  std::vector<FieldView> data_fields_;
  size_t first_row_field_;
  std::vector<double> contact_rows_;  // contactData()'s buffer (capacity only grows)
  std::string folder_, filename_;     // where the model's files are in the in-memory files
};

simlab::Model Simulation::Load(const std::string& filename, const std::string& xml,
                              const val& files, std::string* folder_out) {
  // Every file goes below one fresh folder; the main file is loaded from there, so
  // relative file= attributes resolve as on disk (and stay there, for lint).
  if (!IsSafeRelativePath(filename)) throw Error(filename + ": the model needs a relative name");
  const std::string folder = NextModelFolder();
  *folder_out = folder;
  val paths = val::global("Object").call<val>("keys", files);
  const int n = paths["length"].as<int>();
  for (int i = 0; i < n; i++) {
    std::string path = paths[i].as<std::string>();
    if (!IsSafeRelativePath(path)) throw Error(path + ": extra files need relative paths");
    WriteMemFile(folder + "/" + path, files[path]);
  }
  WriteMemFile(folder + "/" + filename, val(xml));
  try {
    return LoadXml(folder + "/" + filename);
  } catch (const Error& e) {
    throw Error(WithoutFolder(e.what(), folder + "/"));
  }
}

// A keyframe by index, or by name.
int Simulation::KeyIndex(const val& key) const {
  if (key.isNumber()) return key.as<int>();
  if (!key.isString()) throw Error("a keyframe is chosen by index or name");
  std::string name = key.as<std::string>();
  int k = m_.NameToId(kObjKey, name);
  if (k < 0) throw Error("no keyframe named '" + name + "'");
  return k;
}

// Points the efc_* entries of the Data table at the current rows (nefc of them; efc_J
// and efc_J_colind have nJ entries: nefc x nv below 60 dofs, compressed rows from 60 on).
// Plain stores: nothing is allocated.
void Simulation::RefreshRowFields() {
  size_t at = first_row_field_;
#define SIMLAB_X(type, name, cols) \
  data_fields_[at++] = MakeFieldView(#name, "nefc", #cols, d_.name, d_.nefc, (cols));
  SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  data_fields_[at++] = MakeFieldView("efc_J", "nJ", "1", d_.efc_J, d_.nJ, 1);
  data_fields_[at++] = MakeFieldView("efc_J_colind", "nJ", "1", d_.efc_J_colind, d_.nJ, 1);
}

void Simulation::CheckIndex(const FieldView& f, int index) {
  if (index < 0 || index >= f.rows * f.cols) {
    throw Error(std::string(f.name) + "[" + std::to_string(index) + "]: index out of range (" +
                f.name + " has " + std::to_string(f.rows * f.cols) + " numbers)");
  }
}

void Simulation::WriteAll(const FieldView& f, const std::vector<double>& values) {
  const int n = f.rows * f.cols;
  if (static_cast<int>(values.size()) != n) {
    throw Error(std::string(f.name) + " needs " + std::to_string(n) + " numbers, got " +
                std::to_string(values.size()));
  }
  for (int i = 0; i < n; i++) {
    if (f.is_int) {
      f.ints[i] = static_cast<int>(values[i]);
    } else {
      f.doubles[i] = values[i];
    }
  }
}

val Simulation::Option() const {
  const simlab::Option& o = m_.opt;
  val opt = NumbersObject({{"timestep", o.timestep}, {"integrator", o.integrator},
                           {"cone", o.cone}, {"solver", o.solver},
                           {"iterations", o.iterations}, {"disableflags", o.disableflags},
                           {"enableflags", o.enableflags}});
  opt.set("gravity", VectorToJs(o.gravity.data(), 3));
  return opt;
}

val Simulation::Statistic() const {
  const simlab::Statistic& s = m_.stat;
  val stat = NumbersObject(
      {{"extent", s.extent}, {"meansize", s.meansize}, {"meanmass", s.meanmass}});
  stat.set("center", VectorToJs(s.center.data(), 3));
  return stat;
}

val Simulation::PerturbState() const {
  val state = NumbersObject({{"select", perturb_.select}, {"active", perturb_.active},
                             {"localmass", perturb_.localmass}});
  double selpos[3] = {0, 0, 0};
  if (perturb_.select > 0) PerturbSelectionPoint(d_, perturb_, selpos);
  state.set("selpos", VectorToJs(selpos, 3));
  state.set("refselpos", VectorToJs(perturb_.refselpos.data(), 3));
  state.set("refquat", VectorToJs(perturb_.refquat.data(), 4));
  return state;
}

val Simulation::Counts() const {
  val counts = NumbersObject({{"ncon", d_.ncon}, {"nefc", d_.nefc}, {"ne", d_.ne},
                              {"nf", d_.nf}, {"nl", d_.nl}, {"nisland", d_.nisland},
                              {"solver_niter", d_.solver_niter}, {"nreset", d_.nreset}});
  counts.set("energy", VectorToJs(d_.energy, 2));
  return counts;
}

val Simulation::Warnings() const {
  val list = val::array();
  for (int w = 0; w < kNumWarnings; w++) {
    if (d_.warning[w].number == 0) continue;
    val one = NumbersObject({{"kind", w}, {"number", d_.warning[w].number},
                             {"lastinfo", d_.warning[w].lastinfo}});
    one.set("name", std::string(WarningName(w)));
    one.set("message", w == kWarnEngineError ? d_.error : std::string());
    list.call<void>("push", one);
  }
  return list;
}

val Simulation::Contacts() const {
  val contacts = val::array();
  double row[kContactStride];
  for (int i = 0; i < d_.ncon; i++) {
    WriteContactRow(m_, d_, i, row);
    val one = val::object();
    one.set("geom1", d_.contact[i].geom[0]);
    one.set("geom2", d_.contact[i].geom[1]);
    one.set("dist", row[kContactDist]);
    one.set("pos", VectorToJs(row + kContactPos, 3));
    one.set("frame", VectorToJs(row + kContactFrame, 9));
    one.set("dim", d_.contact[i].dim);
    one.set("efc_address", d_.contact[i].efc_address);
    one.set("force", VectorToJs(row + kContactForce, 6));
    contacts.call<void>("push", one);
  }
  return contacts;
}

val Simulation::ContactData() {
  const size_t n = static_cast<size_t>(d_.ncon) * kContactStride;
  if (contact_rows_.size() < n) contact_rows_.resize(n);
  for (int i = 0; i < d_.ncon; i++) {
    WriteContactRow(m_, d_, i, contact_rows_.data() + static_cast<size_t>(i) * kContactStride);
  }
  return val(emscripten::typed_memory_view(n, contact_rows_.data()));
}

}  // namespace

// ---------------------------------------------------------------- the JS names

EMSCRIPTEN_BINDINGS(simlab) {
  using emscripten::class_;
  emscripten::function("referenceVersion",
                       emscripten::optional_override([] { return std::string(ReferenceVersion()); }));
  class_<Simulation>("Simulation")
      .constructor(&Simulation::Create, emscripten::allow_raw_pointers())
      .constructor(&Simulation::CreateWithoutFiles, emscripten::allow_raw_pointers())
      .function("reset", &Simulation::Reset)
      .function("resetKeyframe", &Simulation::ResetKeyframe)
      .function("forward", &Simulation::Forward)
      .function("step", &Simulation::Step)
      .function("step", &Simulation::StepOnce)
      .function("history", &Simulation::History)
      .function("lint", &Simulation::Lint)
      .function("scrub", &Simulation::Scrub)
      .function("perturbSelect", &Simulation::PerturbSelect)
      .function("perturbStart", &Simulation::PerturbStart)
      .function("perturbMoveTo", &Simulation::PerturbMoveTo)
      .function("perturbTurnTo", &Simulation::PerturbTurnTo)
      .function("perturbStop", &Simulation::PerturbStop)
      .function("perturbState", &Simulation::PerturbState)
      .function("visual", &Simulation::Visual)
      .property("time", &Simulation::Time, &Simulation::SetTime)
      .function("data", &Simulation::Data)
      .function("dataView", &Simulation::DataView)
      .function("model", &Simulation::ModelArray)
      .function("modelView", &Simulation::ModelView)
      .function("dataShape", &Simulation::DataShape)
      .function("modelShape", &Simulation::ModelShape)
      .function("dataNames", &Simulation::DataNames)
      .function("modelNames", &Simulation::ModelNames)
      .function("setData", &Simulation::SetData)
      .function("setDataAt", &Simulation::SetDataAt)
      .function("sizes", &Simulation::Sizes)
      .function("option", &Simulation::Option)
      .function("statistic", &Simulation::Statistic)
      .function("counts", &Simulation::Counts)
      .function("warnings", &Simulation::Warnings)
      .function("warningTotal", &Simulation::WarningTotal)
      .function("nameToId", &Simulation::NameToId)
      .function("idToName", &Simulation::IdToName)
      .function("contacts", &Simulation::Contacts)
      .function("contactData", &Simulation::ContactData)
      .function("dataId", &Simulation::DataId)
      .function("dataViewAt", &Simulation::DataViewAt);
  // contactData()'s row layout: its length and where each part starts.
  emscripten::constant("contactStride", kContactStride);
  emscripten::constant("contactPos", kContactPos);
  emscripten::constant("contactFrame", kContactFrame);
  emscripten::constant("contactForce", kContactForce);
  emscripten::constant("contactGeom1", kContactGeom1);
  emscripten::constant("contactGeom2", kContactGeom2);
  emscripten::constant("contactDist", kContactDist);
  emscripten::constant("contactDim", kContactDim);
}

}  // namespace simlab::web
