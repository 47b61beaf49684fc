#!/usr/bin/env bash
# The sanitizer configuration (issue 15): builds everything native in build-sanitize with
# g++, AddressSanitizer and UndefinedBehaviorSanitizer (any undefined behaviour stops the
# program) and libstdc++'s assertions (-D_GLIBCXX_ASSERTIONS: operator[] in range, front()
# of a non-empty vector...), then runs the native ctest suite there: the C++ tests,
# install_find_package and the Python tests (python_test_*). The browser and WebAssembly
# tests (wasm_*, lab_*, lesson_*) run on the normal build (tools/test.sh), not here.
#
#   bash tools/sanitize.sh [--build-dir DIR] [--jobs N] [--budget MINUTES] [--no-build]
#
#   --build-dir DIR   build folder (default build-sanitize)
#   --jobs N          parallel compile and test jobs (default 2)
#   --budget MINUTES  stop (and fail) when building and testing take longer than this;
#                     tools/test.sh gives CI's run a budget
#   --no-build        run the tests of the existing build only
#
# -O1 -g1: with the sanitizers, -O2 -g compiles 2 to 4 times slower here (the Python
# module's data.cc: 225 s against 56 s) while the suite, many short tests, takes minutes
# at either level; -g1 keeps file:line in the reports.
#
# Prints the time spent building and testing; exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."

# ---------------------------------------------------------------- options
build=build-sanitize
jobs=2
budget=0
do_build=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --budget) budget=$2; shift 2 ;;
    --no-build) do_build=0; shift ;;
    *) echo "sanitize: unknown option '$1' (see the top of $0)" >&2; exit 2 ;;
  esac
done
start=$(date +%s)
deadline=$((start + budget * 60))

# Runs a command within what is left of the budget (all the time there is without one);
# a command stopped by the budget fails with status 124.
within_budget() {
  if [[ $budget -le 0 ]]; then
    "$@"
    return
  fi
  local left=$((deadline - $(date +%s)))
  if [[ $left -le 0 ]]; then
    echo "sanitize: the budget of $budget minutes is spent before: $*" >&2
    return 124
  fi
  local status=0
  timeout -k 30 "$left" "$@" || status=$?
  [[ $status -eq 124 ]] && echo "sanitize: the budget of $budget minutes ran out in: $*" >&2
  return $status
}

# ---------------------------------------------------------------- flags
sanitize_flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
sanitize_flags+=" -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS"
# install_find_package builds a project against the installed (instrumented) library;
# CMake takes that project's flags from CXXFLAGS.
export CXXFLAGS="$sanitize_flags"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
asan_options="check_initialization_order=1:strict_init_order=1"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# ---------------------------------------------------------------- build
if [[ $do_build -eq 1 ]]; then
  cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=g++ "${launcher[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS="$sanitize_flags" >/dev/null
  # (gtest_discover_tests runs the test program while building: no leak check there)
  ASAN_OPTIONS="$asan_options:detect_leaks=0" within_budget cmake --build "$build" -j"$jobs"
fi
built=$(date +%s)

# ---------------------------------------------------------------- tests
# Leaks are errors in the C++ tests, when LeakSanitizer can run here (it stops the
# process's threads with ptrace, which some containers forbid).
leaks=1
if ASAN_OPTIONS="detect_leaks=1" "$build/simlab" explain models/actuator_bench.xml 2>&1 \
   >/dev/null | grep -q "LeakSanitizer has encountered a fatal error"; then
  echo "sanitize: LeakSanitizer cannot run on this machine; leaks are not checked"
  leaks=0
fi
# Not run here: the browser and WebAssembly tests (normal build), and one test that
# uses up every file descriptor while the server prints, where UBSan's own check of
# the std::cerr call needs a descriptor (for a pipe) and so reports a false "invalid
# vptr".
not_here='^(wasm_|lab_|lesson_|python_|LabServerTest\.KeepsAcceptingAfterRunningOutOfDescriptors$)'
status=0
(cd "$build" && ASAN_OPTIONS="$asan_options:detect_leaks=$leaks" \
   within_budget ctest --output-on-failure -j"$jobs" --timeout 600 -E "$not_here") || status=$?
# The Python tests: python3 is not instrumented, so the sanitizer runtimes are preloaded;
# CPython keeps memory until exit by design, so leaks are not checked there.
preload="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libubsan.so)"
if [[ $status -ne 124 ]]; then
  (cd "$build" && LD_PRELOAD="$preload" ASAN_OPTIONS="$asan_options:detect_leaks=0" \
     within_budget ctest --output-on-failure -j"$jobs" --timeout 900 -R '^python_') || status=$?
fi
tested=$(date +%s)

# ---------------------------------------------------------------- summary
echo "sanitize: build $((built - start)) s, tests $((tested - built)) s," \
     "total $((tested - start)) s"
if [[ $status -eq 0 ]]; then
  echo "sanitize: all passed"
else
  echo "sanitize: FAILED (see above)"
fi
exit $status
