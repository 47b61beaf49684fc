// Steps per second of simlab::Step on models the issues name. Compare with MuJoCo via
// tools/bench_vs_mujoco.sh, which runs this beside MuJoCo's own timing program.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "simlab/simlab.h"

namespace {

std::string Path(const char* relative) { return std::string(SIMLAB_SOURCE_DIR) + "/" + relative; }

// Steps a model with small pseudo-random controls (as mujoco-testspeed's ctrlnoise).
void StepModel(benchmark::State& state, const char* model_path) {
  simlab::Model m = simlab::LoadXml(Path(model_path));
  simlab::Data d = simlab::MakeData(m);
  unsigned seed = 12345;
  for (auto _ : state) {
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

}  // namespace

BENCHMARK_MAIN();
