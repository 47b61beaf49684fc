// A program outside the repository using the installed engine (find_package(simlab)):
// tests/install/run_install_test.sh builds it against an installed prefix and checks
// what it prints.
//
//   consumer models/actuator_bench.xml
//
// loads the actuator bench, sets the motor's control to 0.5, steps 100 times and prints
// the motor's actuator_force (p = u = 0.5: a motor's gain is 1, its bias 0) and the time
// (100 steps of 2 ms).
#include <cstdio>
#include <exception>

#include "simlab/simlab.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s MODEL.xml\n", argv[0]);
    return 2;
  }
  try {
    simlab::Model m = simlab::LoadXml(argv[1]);
    simlab::Data d = simlab::MakeData(m);
    int motor = simlab::NameToId(m, simlab::kObjActuator, "motor");
    if (motor < 0) {
      std::fprintf(stderr, "%s has no actuator named motor\n", argv[1]);
      return 1;
    }
    d.ctrl[motor] = 0.5;
    for (int i = 0; i < 100; i++) simlab::Step(m, d);
    std::printf("motor actuator_force %.6f\n", d.actuator_force[motor]);
    std::printf("time %.6f\n", d.time);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
