#!/usr/bin/env bash
# Installs what is missing, builds (Release, build/), and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
# Everything is installed here, so the browser tests must run, not skip.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSIMLAB_REQUIRE_BROWSER_TESTS=ON >/dev/null
# The engine and the command line profile-guided (as tools/run.sh builds them; the suite
# below checks that build), then everything else.
bash tools/build_pgo.sh build
cmake --build build -j2
# The engine in WebAssembly (web/dist), which ctest compares with the native build.
bash tools/build_wasm.sh
(cd build && ctest --output-on-failure -j2)
# The native suite again under AddressSanitizer, UndefinedBehaviorSanitizer and
# libstdc++'s assertions (build-sanitize). On a fresh 2-core machine it takes about as
# long as everything above; the budget stops it (as a failure) before CI's 90 minutes.
bash tools/sanitize.sh --budget 40
# The loader and the engine under libFuzzer (clang, ASan, UBSan; build-fuzz) for 60 s,
# from the seed corpus of the project's models.
bash tools/fuzz.sh 60
