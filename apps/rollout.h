// `simlab rollout`: the rollout format of ../shared/oracle/FORMAT.md.
#ifndef SIMLAB_APPS_ROLLOUT_H_
#define SIMLAB_APPS_ROLLOUT_H_

#include <ostream>
#include <string>

namespace CLI {
class App;
}

namespace simlab::apps {

struct RolloutOptions {
  std::string model;
  int key = -1;
  std::string state;
  std::string ctrl;
  int steps = 0;
  int every = 1;
  std::string out;
  bool table = false;  // a short human-readable table instead of JSON Lines
};

// Registers the subcommand; its callback runs the rollout.
void AddRolloutCommand(CLI::App& app);

// Runs a rollout, writing to options.out (or `out` when that is empty). Returns the
// process exit code; throws simlab::Error on bad input.
int RunRollout(const RolloutOptions& options, std::ostream& out);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_ROLLOUT_H_
