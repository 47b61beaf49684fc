// The `simlab` command line as a function, so tests run exactly what the command runs:
// it parses the arguments, runs one subcommand and turns every failure into one line
// `simlab: ...` on the error stream and a non-zero exit status.
#ifndef SIMLAB_APPS_CLI_H_
#define SIMLAB_APPS_CLI_H_

#include <ostream>
#include <string>

namespace simlab::apps {

// Where a subcommand writes and the exit status its callback leaves (a callback never
// calls std::exit, so the caller's streams are flushed and checked).
struct CommandIo {
  std::ostream* out = nullptr;
  std::ostream* err = nullptr;  // warnings
  int status = 0;
};

// Exit statuses of the command line.
constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // bad input, a file that cannot be read or written
constexpr int kExitUsage = 2;  // arguments the command line does not take

// Runs `simlab ARGS...` (argv[0] is the program name) writing results to `out` and
// messages to `err`; returns the exit status. Never throws.
int RunSimlab(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

// `text` on one line: control characters (newlines included) become spaces and trailing
// blanks go, so an error message is always one line.
std::string OneLine(const std::string& text);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_CLI_H_
