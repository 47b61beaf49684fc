// `simlab bench MODEL.xml`: steps per second with MuJoCo's testspeed semantics, so that
// any model can be timed the same way in both engines: the start keyframe "test" when
// the model has one, testspeed's control noise (a Halton sequence around the middle of
// each control range), contacts and constraint rows per step, and the time of each
// pipeline stage as MuJoCo's profiler reports it (Data::timer). Times are thread CPU
// time; with --threads N, N independent rollouts (one Data each) run at once and the
// total steps per second is over wall time.
#ifndef SIMLAB_APPS_BENCH_H_
#define SIMLAB_APPS_BENCH_H_

#include <ostream>
#include <string>
#include <vector>

#include "cli.h"
#include "simlab/simlab.h"

namespace CLI {
class App;
}

namespace simlab::apps {

struct BenchOptions {
  std::string model;
  int steps = 10000;
  int key = -1;             // -1: keyframe "test" if the model has one
  double ctrlnoise = 0.01;  // clamped to [0, 1], as testspeed does
  int threads = 1;
};

// Registers the subcommand; its callback prints the report to io.out.
void AddBenchCommand(CLI::App& app, CommandIo& io);

// Runs the benchmark and writes its report to `out`; returns the exit status. Throws
// simlab::Error on a bad model or keyframe.
int RunBench(const BenchOptions& options, std::ostream& out);

// Element `index` of the Halton sequence in `base` (MuJoCo's mju_Halton): the digits of
// index in that base mirrored after the point.
double Halton(int index, int base);

// testspeed's controls, `steps` rows of nu: control i at step s is the middle of its
// range (0 when not ctrllimited) plus ctrlnoise times its half-range (1 when not
// limited) times 2 Halton(s, i + 2) - 1.
std::vector<double> ControlNoise(const Model& m, int steps, double ctrlnoise);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_BENCH_H_
