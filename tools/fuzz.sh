#!/usr/bin/env bash
# Fuzzes the loader and the engine: builds tests/fuzz/load_step_fuzzer with clang-14
# (libFuzzer, ASan, UBSan) in build-fuzz/, makes the seed corpus from the project's
# models, and runs the fuzzer for SECONDS (default 60).
#
#   bash tools/fuzz.sh [SECONDS]
#
# Exits non-zero on any finding (crash, sanitizer report, exception other than the
# loader's simlab::Error, timeout, out-of-memory, leak); the input is saved in
# build-fuzz/findings/ and replays with build-fuzz/load_step_fuzzer FILE.
# The inputs libFuzzer found interesting are kept in build-fuzz/corpus/ for the next run;
# its log is build-fuzz/fuzz.log. Environment: FUZZ_BUILD_DIR (default build-fuzz),
# FUZZ_NICE (default 10), FUZZ_FLAGS: more libFuzzer flags (a long run that goes on
# after findings: FUZZ_FLAGS="-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1").
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
build=${FUZZ_BUILD_DIR:-build-fuzz}
# Inputs longer than this are not tried (each input's cost stays bounded); models in the
# seed corpus longer than it are left out.
max_len=16384
nice_level=${FUZZ_NICE:-10}

# ---------------------------------------------------------------- packages
# (clang-14 and its libFuzzer and sanitizer runtimes among them)
bash tools/install_deps.sh

# ---------------------------------------------------------------- build
# Only the engine and the fuzzer: no tests, benchmarks or Python module in this tree.
# Optimized, with line tables only (enough for symbolized stack traces, faster to build).
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DSIMLAB_FUZZ=ON -DSIMLAB_TESTS=OFF \
  -DSIMLAB_BENCH=OFF -DSIMLAB_PYTHON=OFF >/dev/null
nice -n "$nice_level" cmake --build "$build" -j2 --target load_step_fuzzer

# ---------------------------------------------------------------- corpus
seeds="$build/seeds"
corpus="$build/corpus"
findings="$build/findings"
/usr/bin/python3 tests/fuzz/make_seed_corpus.py "$seeds" --max-bytes "$max_len"
mkdir -p "$corpus" "$findings"
stamp="$build/fuzz.start"
touch "$stamp"

# ---------------------------------------------------------------- fuzz
# The first directory is where new inputs go; the seeds are read only. -timeout: one
# input (load, 40 steps, resets) over 10 s is a finding; -rss_limit_mb: the process over
# 2 GB (a single allocation over it too) is one. Leaks are findings (ASan's default).
log="$build/fuzz.log"
echo "fuzzing for ${seconds}s (log: $log)"
status=0
# UBSan's reports with their stack (undefined behaviour aborts: -fno-sanitize-recover).
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# shellcheck disable=SC2086
nice -n "$nice_level" "$build/load_step_fuzzer" "$corpus" "$seeds" \
  -dict=tests/fuzz/mjcf.dict -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
  -max_total_time="$seconds" -artifact_prefix="$findings/" -print_final_stats=1 \
  ${FUZZ_FLAGS:-} >"$log" 2>&1 || status=$?

# ---------------------------------------------------------------- report
grep -E '^(stat::|Done|#[0-9]+ +DONE)' "$log" | tail -n 12 || true
new=$(find "$findings" -type f -newer "$stamp" | sort)
if [ "$status" -ne 0 ] || [ -n "$new" ]; then
  echo "FUZZING FOUND SOMETHING (libFuzzer exit $status); the inputs:"
  echo "$new" | head -n 20
  echo "--- the report (from $log):"
  awk '/Assertion .* failed|runtime error:|ERROR: |simlab-fuzz== FINDING|terminate called|ALARM|out-of-memory/ \
       { on = 1 } on && shown < 45 && !/ in fuzzer::/ { print; shown++ }' "$log"
  echo "replay: $build/load_step_fuzzer FILE"
  exit 1
fi
echo "no findings"
