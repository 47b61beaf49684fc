// Steps per second of simlab::Step on models the issues name. Compare with MuJoCo via
// tools/bench_vs_mujoco.sh, which runs this beside MuJoCo's own timing program.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "simlab/simlab.h"

namespace {

std::string Path(const char* relative) { return std::string(SIMLAB_SOURCE_DIR) + "/" + relative; }

// Steps a model with small pseudo-random controls (as mujoco-testspeed's ctrlnoise),
// from keyframe "test" when the model has one (as mujoco-testspeed starts), going back
// to it every `restart` steps when restart > 0 (outside the timing).
void StepModel(benchmark::State& state, const char* model_path, int restart = 0) {
  simlab::Model m = simlab::LoadXml(Path(model_path));
  simlab::Data d = simlab::MakeData(m);
  int key = m.NameToId(simlab::kObjKey, "test");
  if (key >= 0) simlab::ResetDataKeyframe(m, d, key);
  unsigned seed = 12345;
  int steps = 0;
  for (auto _ : state) {
    if (restart > 0 && ++steps % restart == 0) {
      state.PauseTiming();
      simlab::ResetDataKeyframe(m, d, key);
      state.ResumeTiming();
    }
    for (int i = 0; i < m.nu; i++) {
      seed = seed * 1103515245u + 12345u;
      d.ctrl[i] = 0.01 * (static_cast<double>(seed >> 8) / (1u << 24) * 2 - 1);
    }
    simlab::Step(m, d);
  }
  state.counters["steps_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_StepHumanoidNoContact(benchmark::State& state) {
  StepModel(state, "tests/models/humanoid_nocontact.xml");
}
BENCHMARK(BM_StepHumanoidNoContact)->MinTime(2.0);

// MuJoCo's humanoid with its contacts: it falls and lies on the floor (about 12 contacts).
void BM_StepHumanoid(benchmark::State& state) {
  StepModel(state, "tests/conformance/contact/models/humanoid.xml");
}
BENCHMARK(BM_StepHumanoid)->MinTime(2.0);

// The gantry gripper holding the cube up (7 contacts); the grip creeps, so every 1000
// steps (before the cube could slip out) it starts again from the held state.
void BM_StepGantryHolding(benchmark::State& state) {
  StepModel(state, "tests/models/bench_gantry_holding.xml", 1000);
}
BENCHMARK(BM_StepGantryHolding)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
