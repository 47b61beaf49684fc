#!/usr/bin/env bash
# Installs what simlab needs to build and test, from Debian's packages only.
# Safe to run again: packages already present are skipped.
set -euo pipefail

packages=(
  g++ cmake make
  libeigen3-dev libpugixml-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libqhull-dev libpng-dev
  # the Python package (pybind11 module for Debian's python3, numpy) and its tests
  pybind11-dev python3-dev python3-numpy python3-pytest
  # the browser lab: the engine in WebAssembly, and a headless browser for its tests
  emscripten chromium
  # (dpkg-source: the WebAssembly build unpacks Debian's patched libpng source)
  dpkg-dev
  # the fuzzer (tools/fuzz.sh: clang's libFuzzer and sanitizer runtimes) and a compiler
  # cache for the extra sanitizer and fuzzer builds
  clang-14 libclang-rt-14-dev ccache

)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# The web lab's npm packages (web/package.json: three, uPlot, KaTeX, playwright-core):
# installed when missing, and again when package-lock.json names packages that
# node_modules lacks (npm's own record, node_modules/.package-lock.json, is older).
web="$(dirname "$0")/../web"
if [ -f "$web/package-lock.json" ] &&
   { [ ! -d "$web/node_modules" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; }; then
  echo "installing web/node_modules (npm ci)"
  (cd "$web" && npm ci --no-audit --no-fund >/dev/null)
fi
