#!/usr/bin/env bash
# A profile-guided build (g++ -fprofile-use) of the engine and the command line, as
# tools/run.sh and tools/test.sh build them:
#   1. an instrumented simlab (-fprofile-generate) in BUILD_DIR/pgo-instrumented;
#   2. training: 300 steps of `simlab bench` on every model of models/, tests/models/ and
#      tests/conformance/*/models/ (contacts, flexes, tendons, sensors, every integrator
#      and solver the suite covers), counts in BUILD_DIR/pgo-profile;
#   3. BUILD_DIR configured to compile with that profile, and TARGETs built.
# Results are bit-identical to a build without the profile (it changes code layout,
# inlining and branch order, never the arithmetic); the conformance suite runs on it.
#
#   tools/build_pgo.sh [BUILD_DIR [TARGET...]]   (default: build simlab; about 12 minutes
#                                                 on 2 cores from nothing, 6 when rerun)
#
# The profile stays BUILD_DIR's compile flag: later builds of BUILD_DIR (cmake --build)
# keep using it, and g++ ignores it for a function whose source has changed since.
# Each object finds its counts by its path inside its build folder (-fprofile-prefix-path),
# so the two builds need not share a folder.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mkdir -p "${1:-$here/build}" && cd "${1:-$here/build}" && pwd)
[ $# -gt 0 ] && shift
targets=("${@:-simlab}")
cd "$here"
generate=$dir/pgo-instrumented
profile=$dir/pgo-profile
jobs=${JOBS:-2}

# 1. Instrumented build.
cmake -S . -B "$generate" -DCMAKE_BUILD_TYPE=Release -DSIMLAB_TESTS=OFF \
  -DCMAKE_CXX_FLAGS="-fprofile-generate -fprofile-update=single -fprofile-dir=$profile -fprofile-prefix-path=$generate" \
  >/dev/null
cmake --build "$generate" -j"$jobs" --target simlab

# 2. Training, on fresh counts: every model the repository simulates (a model that fails
#    to load or runs past its time is skipped; its counts are simply not in the profile).
rm -rf "$profile"
trained=0
for model in models/*.xml tests/models/*.xml tests/conformance/*/models/*.xml; do
  if (cd "$(dirname "$model")" && timeout 20 "$generate/simlab" bench "$(basename "$model")" \
        --steps 300 >/dev/null 2>&1); then
    trained=$((trained + 1))
  fi
done
echo "profile-guided build: trained on $trained models"

# 3. BUILD_DIR with the profile.
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS="-fprofile-use -fprofile-partial-training -fprofile-dir=$profile -fprofile-prefix-path=$dir -Wno-missing-profile -Wno-error=coverage-mismatch" \
  >/dev/null
cmake --build "$dir" -j"$jobs" --target "${targets[@]}"
