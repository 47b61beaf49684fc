#!/usr/bin/env bash
# A profile-guided build of the command line (g++ -fprofile-use), for the fastest native
# simlab: builds an instrumented simlab, runs it on a broad training set (every model of
# models/, tests/models/ and tests/conformance/*/models/, 300 steps of `simlab bench` each:
# contacts, flexes, tendons, sensors, every integrator and solver the suite covers), then
# rebuilds it with the profile. Results are bit-identical to the normal build (the profile
# changes code layout, inlining and branch order, never the arithmetic).
#
#   tools/build_pgo.sh [BUILD_DIR]     (default build-pgo; about 10 minutes on 2 cores)
#   then: BUILD_DIR/simlab ..., or tools/bench_vs_mujoco.sh BUILD_DIR
#
# The two builds share BUILD_DIR: g++ finds each object's profile by the object's path.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mkdir -p "${1:-$here/build-pgo}" && cd "${1:-$here/build-pgo}" && pwd)
cd "$here"
profile=$dir/pgo-profile
jobs=${JOBS:-2}

# A Release build of the command line in $dir with the given profile flags.
build_with() {
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="$1" >/dev/null
  cmake --build "$dir" -j"$jobs" --target simlab
}

# 1. Instrumented build.
rm -rf "$profile"
build_with "-fprofile-generate -fprofile-update=single -fprofile-dir=$profile"

# 2. Training: every model the repository simulates (a model that fails to load or runs
#    past its time is skipped; its counts are simply not in the profile).
trained=0
for model in models/*.xml tests/models/*.xml tests/conformance/*/models/*.xml; do
  if (cd "$(dirname "$model")" && timeout 20 "$dir/simlab" bench "$(basename "$model")" \
        --steps 300 >/dev/null 2>&1); then
    trained=$((trained + 1))
  fi
done
echo "trained on $trained models"

# 3. The build with the profile.
build_with "-fprofile-use -fprofile-partial-training -fprofile-dir=$profile -Wno-missing-profile"
echo "profile-guided simlab: $dir/simlab"
