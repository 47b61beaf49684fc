#include "cli.h"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "bench.h"
#include "explain.h"
#include "lab.h"
#include "lint.h"
#include "rollout.h"

namespace simlab::apps {
namespace {

// Writes `simlab: MESSAGE` on one line and returns the error status. Never throws, so
// it is safe inside a catch block.
int Fail(std::ostream& err, const char* message) noexcept {
  try {
    err << "simlab: " << OneLine(message) << std::endl;
  } catch (...) {
    // Nothing more can be said; the status still tells.
  }
  return kExitError;
}

// Parses the arguments and runs the subcommand they name; may throw anything a
// subcommand throws.
int ParseAndRun(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  // One subcommand per job, each writing to `out` and leaving its status in `io`.
  CLI::App app{"simlab: MJCF models simulated with MuJoCo's semantics"};
  app.require_subcommand(1);
  CommandIo io{&out, &err};
  AddRolloutCommand(app, io);
  AddBenchCommand(app, io);
  AddExplainCommand(app, io);
  AddLintCommand(app, io);
  AddLabCommand(app, io);
  AddViewCommand(app, io);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints the usage; a usage error is one line like every other failure.
    if (e.get_exit_code() == 0) return app.exit(e, out, err);
    Fail(err, (std::string(e.what()) + " (simlab --help lists the options)").c_str());
    return kExitUsage;
  }
  // What went to `out` must have arrived (a full disk or a closed pipe is an error).
  errno = 0;
  if (!out.flush()) {
    const std::string cause = errno != 0 ? std::strerror(errno) : "write error";
    return Fail(err, ("standard output: cannot write: " + cause).c_str());
  }
  return io.status;
}

}  // namespace

std::string OneLine(const std::string& text) {
  std::string line = text;
  for (char& c : line) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  }
  line.erase(line.find_last_not_of(' ') + 1);
  return line;
}

int RunSimlab(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  // Every failure, whatever its type, becomes one line and a non-zero status.
  try {
    return ParseAndRun(argc, argv, out, err);
  } catch (const std::bad_alloc&) {
    return Fail(err, "out of memory");
  } catch (const std::exception& e) {
    return Fail(err, e.what());
  } catch (...) {
    return Fail(err, "internal error: an unknown exception");
  }
}

}  // namespace simlab::apps
