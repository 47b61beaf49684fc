// The `simlab` command line: one subcommand per job (apps/cli.cc runs them and turns
// every failure into one line `simlab: ...` and a non-zero status).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "cli.h"

namespace {

// Last line of defence: should anything still call std::terminate (an exception thrown
// where none may pass), say so on one line and exit with the error status instead of
// aborting.
[[noreturn]] void OnTerminate() {
  try {
    if (const std::exception_ptr current = std::current_exception()) {
      std::rethrow_exception(current);
    }
    std::fputs("simlab: internal error: terminate called\n", stderr);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "simlab: internal error: %s\n",
                 simlab::apps::OneLine(e.what()).c_str());
  } catch (...) {
    std::fputs("simlab: internal error: an unknown exception\n", stderr);
  }
  std::fflush(stderr);
  std::_Exit(simlab::apps::kExitError);
}

}  // namespace

int main(int argc, char** argv) {
  std::set_terminate(OnTerminate);
  return simlab::apps::RunSimlab(argc, argv, std::cout, std::cerr);
}
