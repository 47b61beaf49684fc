// `simlab rollout`: the rollout format of ../shared/oracle/FORMAT.md.
#ifndef SIMLAB_APPS_ROLLOUT_H_
#define SIMLAB_APPS_ROLLOUT_H_

#include <ostream>
#include <string>

#include "cli.h"
#include "simlab/data.h"

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

// Registers the subcommand; its callback runs the rollout, writing to io.out when no
// --out is given, and leaves its exit status in io.status.
void AddRolloutCommand(CLI::App& app, CommandIo& io);

// Runs a rollout, writing to options.out (or `out` when that is empty). Returns the
// process exit code; throws simlab::Error on bad input (naming the file, and the line
// or field where it applies: a --state value that is not a number, a --ctrl cell that
// is neither a decimal number nor NaN/Infinity/-Infinity, a folder given as a file) and
// when the output cannot be written (checked after every record and after the last
// flush). The engine's warnings go to `warnings`, if given: each kind the first time it
// is raised, then a count of each kind at the end (RolloutWarnings).
int RunRollout(const RolloutOptions& options, std::ostream& out,
               std::ostream* warnings = nullptr);

// Prints, as the first of its kind is raised, each warning of `d` to `out`
// ("simlab: warning: bad qvel (NaN or too large): simulation reset (info 3, time
// 0.0100)"); Summary prints each kind raised with its count.
class RolloutWarnings {
 public:
  RolloutWarnings(Data& d, std::ostream& out);
  void Summary(const Data& d) const;

 private:
  std::ostream& out_;
};

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_ROLLOUT_H_
