// Batched open-loop rollouts on a thread pool (MuJoCo's rollout module): nbatch initial
// states, each stepped nstep times under its own controls, one Data per thread, the GIL
// released while they run. A rollout's result depends only on its own inputs, never on
// which thread ran it or what ran there before.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "simlab/simlab.h"
#include "simlab/support.h"
#include "wrappers.h"

namespace simlab::python {

namespace {

// ---------------------------------------------------------------- the pool

// Threads that wait for work; Run hands them a loop over tasks and waits for it to end.
class ThreadPool {
 public:
  explicit ThreadPool(int nthread) {
    for (int w = 0; w < nthread; w++) workers_.emplace_back([this, w] { Work(w); });
  }
  ~ThreadPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }
  int size() const { return static_cast<int>(workers_.size()); }

  // Calls task(worker, k) for every k in [0, ntask), each worker taking the next k
  // until none is left; returns when all are done.
  void Run(int ntask, const std::function<void(int, int)>& task) {
    std::lock_guard<std::mutex> one_run(run_mutex_);  // callers on several threads queue
    std::unique_lock<std::mutex> lock(mutex_);
    task_ = &task;
    ntask_ = ntask;
    next_ = 0;
    busy_ = size();
    generation_++;
    wake_.notify_all();
    done_.wait(lock, [this] { return busy_ == 0; });
    task_ = nullptr;
    // A task that threw: the first error, on the calling thread.
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  void Work(int worker) {
    long seen = 0;
    while (true) {
      // Wait for a new generation of work (or the end).
      const std::function<void(int, int)>* task;
      int ntask;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        task = task_;
        ntask = ntask_;
      }
      // Take tasks until none is left (or one fails: the rest are skipped), then report.
      std::exception_ptr error;
      for (int k = next_++; k < ntask; k = next_++) {
        try {
          (*task)(worker, k);
        } catch (...) {
          error = std::current_exception();
          next_ = ntask;
        }
      }
      std::lock_guard<std::mutex> lock(mutex_);
      if (error && !error_) error_ = error;
      if (--busy_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex run_mutex_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int)>* task_ = nullptr;
  int ntask_ = 0;
  std::atomic<int> next_{0};
  int busy_ = 0;
  long generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;  // the first error of the current run
};

// ---------------------------------------------------------------- one rollout

// The arrays of a batch (row-major, nbatch leading): inputs may be null where optional.
struct Batch {
  int nstep = 0;
  int control_spec = 0;
  const double* state0 = nullptr;     // nbatch x nstate
  const double* warmstart0 = nullptr; // nbatch x nv, or null: zero
  const double* control = nullptr;    // nbatch x nstep x ncontrol, or null: none
  double* state = nullptr;            // nbatch x nstep x nstate, or null
  double* sensordata = nullptr;       // nbatch x nstep x nsensordata, or null
  // The first engine error of any rollout (they run on several threads).
  std::mutex* error_mutex = nullptr;
  std::string* error = nullptr;
};

// Whether a warning ends the rollout: MuJoCo's kinds, and an engine error.
bool AnyWarning(const Data& d) {
  return d.warning[kWarnEngineError].number > 0 ||
         std::any_of(d.warning, d.warning + kNumMujocoWarnings,
                     [](const WarningStat& w) { return w.number > 0; });
}

// Writes step t's outputs of rollout r.
void Record(const Model& m, const Data& d, const Batch& b, size_t r, size_t t) {
  const size_t nstate = StateSize(m, kStateFullPhysics);
  const size_t step = r * b.nstep + t;
  if (b.state) GetState(m, d, b.state + step * nstate, kStateFullPhysics);
  if (b.sensordata) {
    std::copy(d.sensordata.begin(), d.sensordata.end(), b.sensordata + step * m.nsensordata);
  }
}

// Inputs the controls do not set take their defaults: no ctrl or applied forces, mocap
// bodies at their model poses, equality constraints as the model activates them.
void ClearInputs(const Model& m, Data& d) {
  std::fill(d.ctrl.begin(), d.ctrl.end(), 0.0);
  std::fill(d.qfrc_applied.begin(), d.qfrc_applied.end(), 0.0);
  std::fill(d.xfrc_applied.begin(), d.xfrc_applied.end(), 0.0);
  for (int i = 0; i < m.nbody; i++) {
    int id = m.body_mocapid[i];
    if (id < 0) continue;
    std::copy_n(&m.body_pos[3 * i], 3, &d.mocap_pos[3 * id]);
    std::copy_n(&m.body_quat[4 * i], 4, &d.mocap_quat[4 * id]);
  }
  std::copy(m.eq_active0.begin(), m.eq_active0.end(), d.eq_active.begin());
}

// Rollout r on data d: set its initial state, then step under its controls. After a
// warning (a divergence reset), the remaining steps repeat the state reached.
void RollOut(const Model& m, Data& d, const Batch& b, size_t r) {
  const size_t nstate = StateSize(m, kStateFullPhysics);
  const size_t ncontrol = StateSize(m, b.control_spec);
  ClearInputs(m, d);
  SetState(m, d, b.state0 + r * nstate, kStateFullPhysics);
  if (b.warmstart0) std::copy_n(b.warmstart0 + r * m.nv, m.nv, d.qacc_warmstart.begin());
  else std::fill(d.qacc_warmstart.begin(), d.qacc_warmstart.end(), 0.0);
  for (WarningStat& w : d.warning) w.number = 0;
  for (size_t t = 0; t < static_cast<size_t>(b.nstep); t++) {
    if (!AnyWarning(d)) {
      if (b.control) SetState(m, d, b.control + (r * b.nstep + t) * ncontrol, b.control_spec);
      Step(m, d);
    }
    Record(m, d, b, r, t);
  }
  // An engine error (now a warning) is reported to the caller.
  if (d.warning[kWarnEngineError].number > 0) {
    std::lock_guard<std::mutex> lock(*b.error_mutex);
    if (b.error->empty()) *b.error = d.error;
  }
}

// ---------------------------------------------------------------- Python

// An optional float64 array of `size` numbers: its data if given (the Python layer made
// it contiguous; the sizes are checked again here, as this class can be called directly).
template <typename T>
T* DataOf(const py::object& a, size_t size, const char* name) {
  if (a.is_none()) return nullptr;
  py::array arr = py::reinterpret_borrow<py::array>(a);
  if (!py::isinstance<py::array>(a) || !arr.dtype().is(py::dtype::of<double>()) ||
      !(arr.flags() & py::array::c_style)) {
    throw py::type_error(std::string(name) + " must be a C-contiguous float64 array");
  }
  if (static_cast<size_t>(arr.size()) != size) {
    throw py::value_error(std::string(name) + " has " + std::to_string(arr.size()) +
                          " numbers, expected " + std::to_string(size));
  }
  if constexpr (std::is_const_v<T>) return static_cast<T*>(arr.data());
  else return static_cast<T*>(arr.mutable_data());
}

class PyRollout {
 public:
  explicit PyRollout(int nthread) : pool_(std::max(nthread, 0)) {}

  // models: nbatch MjModel; datas: at least max(1, nthread) MjData (one per thread).
  void Rollout(const py::list& models, const py::list& datas, int nstep, int control_spec,
               const py::object& state0, const py::object& warmstart0, const py::object& control,
               const py::object& state, const py::object& sensordata, int chunk_size) {
    // Engine pointers, taken while the GIL is held; every model fits every data.
    if (models.empty() || datas.size() < static_cast<size_t>(std::max(pool_.size(), 1))) {
      throw py::value_error("rollout needs a model per rollout and an MjData per thread");
    }
    std::vector<const Model*> m;
    std::vector<Data*> d;
    for (py::handle h : datas) d.push_back(&h.cast<PyData&>().data);
    for (py::handle h : models) {
      const PyModel& model = h.cast<const PyModel&>();
      for (py::handle data : datas) CheckCompatible(model, data.cast<const PyData&>());
      m.push_back(model.model.get());
    }
    // The arrays, of the sizes the first model gives.
    const size_t nbatch = m.size(), steps = std::max(nstep, 0);
    const size_t nstate = OrFatal("rollout", [&] { return StateSize(*m[0], kStateFullPhysics); });
    const size_t ncontrol = OrFatal("rollout", [&] { return StateSize(*m[0], control_spec); });
    Batch b{static_cast<int>(steps), control_spec,
            DataOf<const double>(state0, nbatch * nstate, "initial_state"),
            DataOf<const double>(warmstart0, nbatch * m[0]->nv, "initial_warmstart"),
            DataOf<const double>(control, nbatch * steps * ncontrol, "control"),
            DataOf<double>(state, nbatch * steps * nstate, "state"),
            DataOf<double>(sensordata, nbatch * steps * m[0]->nsensordata, "sensordata")};
    if (!b.state0) throw py::value_error("initial_state is required");
    std::mutex error_mutex;
    std::string error;
    b.error_mutex = &error_mutex;
    b.error = &error;
    {
      py::gil_scoped_release release;
      OrFatal("rollout", [&] { Run(m, d, b, chunk_size); });
    }
    if (!error.empty()) throw FatalError("rollout: " + error);
  }

 private:
  // On the calling thread, or in chunks of rollouts on the pool.
  void Run(const std::vector<const Model*>& m, const std::vector<Data*>& d, const Batch& b,
           int chunk_size) {
    const int nbatch = static_cast<int>(m.size());
    if (pool_.size() == 0) {
      for (int r = 0; r < nbatch; r++) RollOut(*m[r], *d[0], b, r);
      return;
    }
    if (chunk_size <= 0) chunk_size = std::max(1, nbatch / (pool_.size() * 10));
    const int nchunk = (nbatch + chunk_size - 1) / chunk_size;
    pool_.Run(nchunk, [&](int worker, int chunk) {
      const int end = std::min(nbatch, (chunk + 1) * chunk_size);
      for (int r = chunk * chunk_size; r < end; r++) RollOut(*m[r], *d[worker], b, r);
    });
  }

  ThreadPool pool_;
};

}  // namespace

void DefineRollout(py::module_& m) {
  py::class_<PyRollout>(m, "_Rollout")
      .def(py::init<int>(), py::arg("nthread"))
      .def("rollout", &PyRollout::Rollout, py::arg("models"), py::arg("datas"), py::arg("nstep"),
           py::arg("control_spec"), py::arg("state0"), py::arg("warmstart0"), py::arg("control"),
           py::arg("state"), py::arg("sensordata"), py::arg("chunk_size"));
}

}  // namespace simlab::python
