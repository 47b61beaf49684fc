#!/usr/bin/env bash
# Builds the engine for the browser: web/dist/simlab.mjs and web/dist/simlab.wasm
# (emscripten from Debian, Release, ES module; see web/README.md for the JS API).
#
#   bash tools/build_wasm.sh            # build dir build-wasm (SIMLAB_WASM_BUILD=... to change)
#
# pugixml, qhull, libpng and zlib have no WebAssembly build in Debian: their Debian source
# packages (the same versions the native build links) are fetched once with apt-get
# source, through private package lists under the build folder, and compiled with
# emscripten: pugixml installed under build-wasm/_deps; qhull's reentrant C library
# (src/libqhull_r), libpng and zlib compiled by the engine's CMake (SIMLAB_QHULL_SOURCE,
# SIMLAB_PNG_SOURCE, SIMLAB_ZLIB_SOURCE). libpng is unpacked with Debian's patches
# applied (dpkg-source), since it reads the model's image files.
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

# ---------------------------------------------------------------- Debian sources
# Downloads the source package $1 into _deps/src and unpacks it into _deps/src/$1-src:
# with Debian's patches (dpkg-source) when $2 is "patched", else its upstream tarball.
fetch_debian_source() {
  local apt="$deps/apt"
  mkdir -p "$apt/lists/partial" "$deps/src"
  echo "deb-src http://deb.debian.org/debian bookworm main" > "$apt/sources.list"
  local opts=(-o Dir::Etc::SourceList="$apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
              -o Dir::State::Lists="$apt/lists" -o APT::Sandbox::User=root)
  apt-get "${opts[@]}" -qq update
  (cd "$deps/src" && apt-get "${opts[@]}" -qq source --download-only "$1")
  if [ "${2:-}" = patched ]; then
    (cd "$deps/src" && dpkg-source --no-check -x "$1"_*.dsc "$1-src" >/dev/null)
  else
    mkdir -p "$deps/src/$1-src"
    tar -xf "$deps/src/$1"_*.orig.tar.* -C "$deps/src/$1-src" --strip-components=1
  fi
}

# The unpacked source folder of package $1, fetched first if missing ($2 as above).
debian_source_dir() {
  [ -d "$deps/src/$1-src" ] || fetch_debian_source "$1" "${2:-}" >&2
  echo "$deps/src/$1-src/"
}

# ---------------------------------------------------------------- pugixml for wasm
pugixml_config="$deps/pugixml/lib/cmake/pugixml/pugixml-config.cmake"
if [ ! -f "$pugixml_config" ]; then
  pugixml_src=$(debian_source_dir pugixml)
  emcmake cmake -S "$pugixml_src" -B "$deps/pugixml-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$deps/pugixml" -DBUILD_SHARED_LIBS=OFF -DPUGIXML_BUILD_TESTS=OFF \
    -DCMAKE_CXX_FLAGS=-fwasm-exceptions >/dev/null
  cmake --build "$deps/pugixml-build" -j2 --target install >/dev/null
fi

# ---------------------------------------------------------------- qhull for wasm
qhull_src=$(debian_source_dir qhull)

# ---------------------------------------------------------------- libpng and zlib for wasm
png_src=$(debian_source_dir libpng1.6 patched)
zlib_src=$(debian_source_dir zlib)

# ---------------------------------------------------------------- the engine and binding
emcmake cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSIMLAB_TESTS=OFF -DSIMLAB_BENCH=OFF \
  -DEigen3_DIR=/usr/share/eigen3/cmake -Dpugixml_DIR="$(dirname "$pugixml_config")" \
  -DSIMLAB_QHULL_SOURCE="${qhull_src%/}" -DSIMLAB_PNG_SOURCE="${png_src%/}" \
  -DSIMLAB_ZLIB_SOURCE="${zlib_src%/}" >/dev/null
cmake --build "$build" -j2 --target simlab_wasm
ls -l web/dist/simlab.mjs web/dist/simlab.wasm
