// `simlab bench`: see bench.h.
#include "bench.h"

#include <CLI/CLI.hpp>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace simlab::apps {
namespace {

// ---------------------------------------------------------------- clocks

// CPU time of the calling thread, in seconds (what the rollouts are measured in: the
// machine may be shared).
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The profiler's clock, in microseconds: steady and cheap (a thread CPU clock is a
// system call, too slow to read thirty times a step), as testspeed's.
double SteadyMicroseconds() {
  using Micro = std::chrono::duration<double, std::micro>;
  return Micro(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// ---------------------------------------------------------------- rollouts

// One rollout's Data and what it measured.
struct Rollout {
  Data d;
  double cpu_seconds = 0;
  double contacts = 0;  // summed over the steps
  double rows = 0;
  double iterations = 0;  // solver iterations, averaged over a step's islands, summed
};

// Steps one rollout through the control rows, timing it in thread CPU time (and its
// stages with the profiler's clock when `profiler`).
void Simulate(const Model& m, const std::vector<double>& ctrl, int steps, bool profiler,
              Rollout* r) {
  r->d.timer_clock = profiler ? SteadyMicroseconds : nullptr;
  double start = ThreadCpuSeconds();
  for (int s = 0; s < steps; s++) {
    std::copy_n(ctrl.begin() + static_cast<size_t>(s) * m.nu, m.nu, r->d.ctrl.begin());
    Step(m, r->d);
    r->contacts += r->d.ncon;
    r->rows += r->d.nefc;
    // (as testspeed: a step's iterations over its islands, averaged; Data sums them)
    r->iterations += static_cast<double>(r->d.solver_niter) / std::max(1, r->d.nisland);
  }
  r->cpu_seconds = ThreadCpuSeconds() - start;
}

// The keyframe to start from: the one asked for, else "test" when there is one.
int StartKey(const Model& m, int key) {
  if (key >= m.nkey) {
    throw Error("bench: keyframe " + std::to_string(key) + " does not exist (the model has " +
                std::to_string(m.nkey) + ")");
  }
  return key >= 0 ? key : m.NameToId(kObjKey, "test");
}

// ---------------------------------------------------------------- report

constexpr const char* kTimerNames[kNumTimers] = {
    "step",           "forward",     "inverse",        "position",    "velocity",
    "actuation",      "constraint",  "advance",        "kinematics",  "inertia",
    "collision",      "make",        "project",        "broadphase",  "narrowphase"};

// Microseconds per call of a timer (0 if it never ran).
double PerCall(const Data& d, int timer) {
  const TimerStat& t = d.timer[timer];
  return t.number > 0 ? t.duration / t.number : 0;
}

void Line(std::ostream& out, const char* format, double value) {
  char text[96];
  std::snprintf(text, sizeof(text), format, value);
  out << text << "\n";
}

// One profiler line: name (indented under what it is part of), microseconds per call
// and share of the step.
void ProfileLine(std::ostream& out, int indent, const char* name, double us, double step_us) {
  char text[96];
  std::snprintf(text, sizeof(text), "%*s%-*s: %7.2f  (%6.2f %%)", indent, "", 20 - indent, name,
                us, step_us > 0 ? 100 * us / step_us : 0.0);
  out << text << "\n";
}

// The profiler's table (testspeed's layout): the step and its stages with what they
// leave out as "other", then the position stage's parts and collision's.
void PrintProfile(std::ostream& out, const Data& d) {
  double step = PerCall(d, kTimerStep), parts = 0;
  out << " Internal profiler (wall clock), us per step\n";
  for (int t = kTimerStep; t <= kTimerAdvance; t++) {
    if (d.timer[t].number == 0) continue;
    ProfileLine(out, 1, kTimerNames[t], PerCall(d, t), step);
    if (t >= kTimerPosition) parts += PerCall(d, t);
  }
  ProfileLine(out, 1, "other", step - parts, step);
  out << "\n";
  struct Part {
    int timer, indent;
    const char* name;
  };
  const Part parts_of_position[] = {
      {kTimerPosition, 1, "position total"}, {kTimerPosKinematics, 3, "kinematics"},
      {kTimerPosInertia, 3, "inertia"},       {kTimerPosCollision, 3, "collision"},
      {kTimerColBroad, 5, "broadphase"},      {kTimerColNarrow, 5, "narrowphase"},
      {kTimerPosMake, 3, "make"},             {kTimerPosProject, 3, "project"}};
  for (const Part& part : parts_of_position) {
    ProfileLine(out, part.indent, part.name, PerCall(d, part.timer), step);
  }
}

void PrintReport(std::ostream& out, const Model& m, const BenchOptions& o,
                 const std::vector<std::unique_ptr<Rollout>>& rollouts, double wall) {
  const Rollout& first = *rollouts[0];
  double steps = o.steps;
  if (o.threads > 1) {
    out << "All " << o.threads << " threads (wall clock)\n";
    Line(out, " Total steps per second : %.0f", o.threads * steps / wall);
    Line(out, " Total realtime factor  : %.2f x", o.threads * steps * m.opt.timestep / wall);
    out << "\nThread 0 (its CPU time)\n";
  }
  Line(out, " Simulation time      : %.3f s", first.cpu_seconds);
  Line(out, " Steps per second     : %.0f", steps / first.cpu_seconds);
  Line(out, " Realtime factor      : %.2f x", steps * m.opt.timestep / first.cpu_seconds);
  Line(out, " Time per step        : %.2f us", 1e6 * first.cpu_seconds / steps);
  out << "\n";
  const char* iters_line = m.opt.solver == kSolverPGS  ? " PGS iters / step     : %.2f"
                           : m.opt.solver == kSolverCG ? " CG iters / step      : %.2f"
                                                       : " Newton iters / step  : %.2f";
  Line(out, iters_line, first.iterations / steps);
  Line(out, " Contacts per step    : %.2f", first.contacts / steps);
  Line(out, " Constraints per step : %.2f", first.rows / steps);
  Line(out, " Degrees of freedom   : %.0f", m.nv);
  out << "\n";
  if (o.profiler) PrintProfile(out, first.d);
}

}  // namespace

double Halton(int index, int base) {
  const double b = base;
  double f = 1 / b, h = 0;
  for (int n = index; n > 0; n /= base) {
    h += f * (n % base);
    f /= b;
  }
  return h;
}

std::vector<double> ControlNoise(const Model& m, int steps, const NoiseOptions& noise,
                                 int key) {
  // The discrete-time Ornstein-Uhlenbeck process: each step keeps `rate` of the last
  // control and moves the rest towards the centre; the noise is scaled to keep its
  // stationary deviation at noise.std half-ranges.
  const double rate = std::exp(-m.opt.timestep / noise.rate);
  const double scale = noise.std * std::sqrt(1 - rate * rate);
  std::vector<double> ctrl;
  ctrl.reserve(static_cast<size_t>(steps) * m.nu);
  for (int s = 0; s < steps; s++) {
    for (int i = 0; i < m.nu; i++) {
      double centre = 0, halfrange = 1;
      const double* range = &m.actuator_ctrlrange[2 * i];
      if (m.actuator_ctrllimited[i]) {
        centre = (range[1] + range[0]) / 2;
        halfrange = (range[1] - range[0]) / 2;
      }
      if (key >= 0) centre = m.key_ctrl[static_cast<size_t>(key) * m.nu + i];
      double u = s > 0 ? rate * ctrl[static_cast<size_t>(s - 1) * m.nu + i] + (1 - rate) * centre
                       : centre;
      u += scale * halfrange * (2 * Halton(s, i + 2) - 1);
      if (m.actuator_ctrllimited[i]) u = std::clamp(u, range[0], range[1]);
      ctrl.push_back(u);
    }
  }
  return ctrl;
}

int RunBench(const BenchOptions& o, std::ostream& out) {
  Model m = LoadXml(o.model);
  int key = StartKey(m, o.key);
  std::vector<double> ctrl = ControlNoise(m, o.steps, o.noise, key);

  // One Data per thread, each at the start state.
  std::vector<std::unique_ptr<Rollout>> rollouts;
  for (int t = 0; t < o.threads; t++) {
    rollouts.push_back(std::make_unique<Rollout>(Rollout{MakeData(m)}));
    if (key >= 0) ResetDataKeyframe(m, rollouts.back()->d, key);
  }
  out << "Rolling out " << o.steps << " steps" << (o.threads > 1 ? " per thread" : "")
      << " at dt = " << m.opt.timestep
      << (key >= 0 ? ", from keyframe " + std::to_string(key) : "") << ", control noise "
      << o.noise.std << " (rate " << o.noise.rate << " s)\n\n";

  // The rollouts, on threads of their own when there are several.
  auto start = std::chrono::steady_clock::now();
  if (o.threads == 1) {
    Simulate(m, ctrl, o.steps, o.profiler, rollouts[0].get());
  } else {
    std::vector<std::thread> threads;
    for (auto& r : rollouts) {
      Rollout* rollout = r.get();
      threads.emplace_back([&m, &ctrl, &o, rollout] { Simulate(m, ctrl, o.steps, o.profiler, rollout); });
    }
    for (auto& thread : threads) thread.join();
  }
  std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  PrintReport(out, m, o, rollouts, wall.count());
  return kExitOk;
}

void AddBenchCommand(CLI::App& app, CommandIo& io) {
  const CLI::Range kCount(1, std::numeric_limits<int>::max());
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "steps per second as MuJoCo's testspeed measures them, with a profile");
  cmd->add_option("model", options->model, "MJCF file")->required();
  cmd->add_option("--steps", options->steps, "steps per rollout (default 10000)")->check(kCount);
  cmd->add_option("--key", options->key, "start from this keyframe (default: \"test\" if any)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--noisestd,--ctrlnoise", options->noise.std,
                  "control noise, a share of each control's half-range (default 0.01)");
  cmd->add_option("--noiserate", options->noise.rate,
                  "time constant of the noise's return to the centre, s (default 0.1)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", options->threads, "independent rollouts at once (default 1)")
      ->check(CLI::Range(1, 512));
  cmd->add_flag("!--no-profiler", options->profiler,
                "no stage timers (their clock reads cost ~1 us a step; testspeed has them)");
  cmd->callback([options, &io] { io.status = RunBench(*options, *io.out); });
}

}  // namespace simlab::apps
