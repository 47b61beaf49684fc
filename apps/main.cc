// The `simlab` command line: one subcommand per job.
#include <CLI/CLI.hpp>
#include <iostream>

#include "explain.h"
#include "lab.h"
#include "rollout.h"
#include "simlab/simlab.h"

int main(int argc, char** argv) {
  CLI::App app{"simlab: MJCF models simulated with MuJoCo's semantics"};
  app.require_subcommand(1);
  simlab::apps::AddRolloutCommand(app);
  simlab::apps::AddExplainCommand(app);
  simlab::apps::AddLabCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const simlab::Error& e) {
    std::cerr << "simlab: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
