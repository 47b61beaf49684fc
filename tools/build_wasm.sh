#!/usr/bin/env bash
# Builds the engine for the browser: web/dist/simlab.mjs and web/dist/simlab.wasm
# (emscripten from Debian, Release, ES module; see web/README.md for the JS API).
#
#   bash tools/build_wasm.sh            # build dir build-wasm (SIMLAB_WASM_BUILD=... to change)
#
# pugixml has no WebAssembly build in Debian: its Debian source package (the same 1.13
# the native build links) is fetched once with apt-get source, through private package
# lists under the build folder, and compiled with emscripten beside the engine.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${SIMLAB_WASM_BUILD:-build-wasm}
case "$build" in /*) ;; *) build="$root/$build" ;; esac
deps="$build/_deps"

# emscripten 3.1.6 needs Debian's node modules (acorn) and its own frozen cache.
export NODE_PATH=/usr/share/nodejs
unset EM_CACHE
command -v emcmake >/dev/null || { echo "build_wasm: emscripten is missing (bash tools/install_deps.sh)"; exit 1; }

# ---------------------------------------------------------------- pugixml for wasm
fetch_pugixml_source() {
  local apt="$deps/apt"
  mkdir -p "$apt/lists/partial" "$deps/src"
  echo "deb-src http://deb.debian.org/debian bookworm main" > "$apt/sources.list"
  local opts=(-o Dir::Etc::SourceList="$apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
              -o Dir::State::Lists="$apt/lists" -o APT::Sandbox::User=root)
  apt-get "${opts[@]}" -qq update
  (cd "$deps/src" && apt-get "${opts[@]}" -qq source --download-only pugixml)
  tar -xzf "$deps"/src/pugixml_*.orig.tar.gz -C "$deps/src"
}

pugixml_config="$deps/pugixml/lib/cmake/pugixml/pugixml-config.cmake"
if [ ! -f "$pugixml_config" ]; then
  [ -d "$deps/src" ] && ls -d "$deps"/src/pugixml-*/ >/dev/null 2>&1 || fetch_pugixml_source
  pugixml_src=$(ls -d "$deps"/src/pugixml-*/ | head -1)
  emcmake cmake -S "$pugixml_src" -B "$deps/pugixml-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$deps/pugixml" -DBUILD_SHARED_LIBS=OFF -DPUGIXML_BUILD_TESTS=OFF \
    -DCMAKE_CXX_FLAGS=-fwasm-exceptions >/dev/null
  cmake --build "$deps/pugixml-build" -j2 --target install >/dev/null
fi

# ---------------------------------------------------------------- the engine and binding
emcmake cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSIMLAB_TESTS=OFF -DSIMLAB_BENCH=OFF \
  -DEigen3_DIR=/usr/share/eigen3/cmake -Dpugixml_DIR="$(dirname "$pugixml_config")" >/dev/null
cmake --build "$build" -j2 --target simlab_wasm
ls -l web/dist/simlab.mjs web/dist/simlab.wasm
