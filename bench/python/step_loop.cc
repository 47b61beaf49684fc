// The C++ side of bench/python/python_overhead.py: the humanoid stepped in a plain loop of
// simlab::Step, timed in thread CPU time, round by round.
//
//   simlab_step_loop MODEL.xml STEPS ROUNDS    prints one line per round: CPU seconds
//
// Each round starts from keyframe 0 with zero controls, as the Python side does.
#include <time.h>

#include <cstdio>
#include <cstdlib>

#include "simlab/simlab.h"

namespace {

double ThreadSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: simlab_step_loop MODEL.xml STEPS ROUNDS\n");
    return 2;
  }
  try {
    simlab::Model m = simlab::LoadXml(argv[1]);
    simlab::Data d = simlab::MakeData(m);
    const int steps = std::atoi(argv[2]), rounds = std::atoi(argv[3]);
    for (int r = 0; r < rounds; r++) {
      simlab::ResetDataKeyframe(m, d, 0);
      double begin = ThreadSeconds();
      for (int i = 0; i < steps; i++) simlab::Step(m, d);
      std::printf("%.9f %.17g\n", ThreadSeconds() - begin, d.qpos[2]);
    }
  } catch (const simlab::Error& e) {
    std::fprintf(stderr, "simlab_step_loop: %s\n", e.what());
    return 1;
  }
  return 0;
}
