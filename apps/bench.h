// `simlab bench MODEL.xml`: steps per second with MuJoCo's testspeed semantics, so that
// any model can be timed the same way in both engines: the start keyframe "test" when
// the model has one, testspeed's control noise (an Ornstein-Uhlenbeck process driven by a
// Halton sequence around the middle of each control range or the keyframe's controls),
// contacts and constraint rows per step, and the time of each pipeline stage as MuJoCo's
// profiler reports it (Data::timer). Times are thread CPU
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

// testspeed's control noise: its deviation in half-ranges and its time constant.
struct NoiseOptions {
  double std = 0.01;
  double rate = 0.1;
};

struct BenchOptions {
  std::string model;
  int steps = 10000;
  int key = -1;             // -1: keyframe "test" if the model has one
  NoiseOptions noise;
  int threads = 1;
  bool profiler = true;     // time the pipeline's stages (a clock read per stage edge)
};

// Registers the subcommand; its callback prints the report to io.out.
void AddBenchCommand(CLI::App& app, CommandIo& io);

// Runs the benchmark and writes its report to `out`; returns the exit status. Throws
// simlab::Error on a bad model or keyframe.
int RunBench(const BenchOptions& options, std::ostream& out);

// Element `index` of the Halton sequence in `base` (MuJoCo's mju_Halton): the digits of
// index in that base mirrored after the point.
double Halton(int index, int base);

// MuJoCo 3.12 testspeed's controls, `steps` rows of nu. The centre of control i is the
// middle of its range (0 when not ctrllimited), or keyframe `key`'s control when key >= 0.
// Step 0 is the centre; step s keeps r = exp(-timestep / noise.rate) of step s-1 and
// takes 1 - r of the centre, plus noise.std sqrt(1 - r^2) half-ranges (1 when not
// limited) times 2 Halton(s, i + 2) - 1; limited controls are clamped to their range.
std::vector<double> ControlNoise(const Model& m, int steps, const NoiseOptions& noise,
                                 int key);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_BENCH_H_
