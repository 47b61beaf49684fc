#!/usr/bin/env bash
# build_oracle_era.sh — native MuJoCo at the commit the npm oracle's WebAssembly was
# built from (as near as its behaviour tells: its signed-distance code is that of
# google-deepmind/mujoco d0fc1c2c8, the parent of cd8bfb90c, February 2026, "3.5.1"),
# with its first-party plugins, which the npm package lacks. It is the reference for
# models the oracle cannot load because they use plugins (the mujoco.sdf.* shapes).
#
#   tools/native/build_oracle_era.sh [OUT]      (default /work/mujoco-oracle-era)
#
# Needs bare clones under $MIRRORS (default /work/.mirror, as `fetch` leaves them):
# google-deepmind+mujoco/repo and, per dependency, OWNER+NAME/repo (tinyxml2,
# tinyobjloader, MarchingCubeCpp, libccd, qhull, miniz, lodepng, TriangleMeshDistance).
# ../shared/oracle/native/build.sh builds newer MuJoCo; this era also needs
# TriangleMeshDistance, and its mjModel has no nactuator/nout (the rollout program's
# header then reports nu for both). About 4 minutes on two cores. Leaves:
#   OUT/rollout       (rollout.mjs's arguments and output format)
#   OUT/plugin/       (the plugin libraries rollout loads)
#   OUT/musl_trig.so  (LD_PRELOAD it: sine, cosine and arc functions as musl's)
# Run with NOTHIN=1 to compare models with many flex contacts (see below).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
OUT=$(mkdir -p "${1:-/work/mujoco-oracle-era}" && cd "${1:-/work/mujoco-oracle-era}" && pwd)
MIRRORS=${MIRRORS:-/work/.mirror}
GIT="$MIRRORS/google-deepmind+mujoco/repo"
REF=$(git --git-dir="$GIT" rev-parse d0fc1c2c8)
SRC=$OUT/src
if [ ! -f "$SRC/CMakeLists.txt" ]; then
  mkdir -p "$SRC"
  # (a mirror may lack large blobs under doc/, which git reports although it skips them)
  git --git-dir="$GIT" archive "$REF" -- . ':(exclude)doc' | tar -x -C "$SRC" || true
fi
[ -f "$SRC/src/engine/engine_collision_sdf.c" ] || { echo "could not export $REF from $GIT" >&2; exit 1; }

# This commit already thins flex contacts to 50 per collision pair (filterFlexContacts,
# commit 8ba68cee3); the npm oracle's build does not. NOTHIN=1 in the environment of a
# run turns the thinning off, and the native build then equals the oracle on flex
# contacts (gripper.xml, gripper_trilinear.xml, cloth_sdf.xml).
DRIVER=$SRC/src/engine/engine_collision_driver.c
if ! grep -q NOTHIN "$DRIVER"; then
  sed -i 's|^static void filterFlexContacts(mjData\* d, int ncon_before) {$|&\n  if (getenv("NOTHIN")) return;  // (simlab: the npm oracle does not thin)|' "$DRIVER"
  sed -i '1i #include <stdlib.h>' "$DRIVER"
  grep -q NOTHIN "$DRIVER" || { echo "could not add NOTHIN to $DRIVER" >&2; exit 1; }
fi

# Each dependency at the commit this MuJoCo pins.
pin() {
  { grep -h -A1 "set(MUJOCO_DEP_VERSION_$1\$" "$SRC"/cmake/MujocoDependencies.cmake \
      "$SRC"/cmake/third_party_deps/*.cmake 2>/dev/null || true; } | sed -n 2p | awk '{print $1}'
}
FC=()
while IFS=: read -r name var gh; do
  commit=$(pin "$var")
  [ -n "$commit" ] || { echo "no pinned version for $var" >&2; exit 1; }
  dir=$OUT/deps/$name
  if [ ! -e "$dir/.exported-$commit" ]; then
    rm -rf "$dir" && mkdir -p "$dir"
    git --git-dir="$MIRRORS/$gh/repo" archive "$commit" | tar -x -C "$dir"
    case $name in
      ccd|qhull) patch -d "$dir" -p1 --forward -s < "$SRC/cmake/$name-support-emscripten.patch" ;;
    esac
    touch "$dir/.exported-$commit"
  fi
  FC+=("-DFETCHCONTENT_SOURCE_DIR_${name^^}=$dir")
done <<'DEPS'
tinyxml2:tinyxml2:leethomason+tinyxml2
tinyobjloader:tinyobjloader:tinyobjloader+tinyobjloader
marchingcubecpp:MarchingCubeCpp:aparis69+MarchingCubeCpp
ccd:ccd:danfis+libccd
qhull:qhull:qhull+qhull
miniz:miniz:richgel999+miniz
lodepng:lodepng:lvandeve+lodepng
trianglemeshdistance:TriangleMeshDistance:InteractiveComputerGraphics+TriangleMeshDistance
DEPS

# The library and the sdf plugins (samples off; testspeed wants a glfw target).
echo 'if(NOT TARGET glfw)
  add_library(glfw INTERFACE)
endif()' > "$OUT/glfw-stub.cmake"
cmake -S "$SRC" -B "$OUT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFETCHCONTENT_FULLY_DISCONNECTED=ON "${FC[@]}" \
  -DMUJOCO_BUILD_EXAMPLES=OFF -DMUJOCO_BUILD_SIMULATE=OFF -DMUJOCO_BUILD_TESTS=OFF \
  -DMUJOCO_TEST_PYTHON_UTIL=OFF -DMUJOCO_BUILD_STUDIO=OFF \
  -DCMAKE_PROJECT_mujoco_INCLUDE="$OUT/glfw-stub.cmake" > "$OUT/configure.log"
cmake --build "$OUT/build" --target mujoco sdf_plugin sensor actuator elasticity -j "${JOBS:-2}"
mkdir -p "$OUT/plugin"
cp "$OUT"/build/lib/lib{actuator,elasticity,sensor,sdf_plugin}.so "$OUT/plugin/"

# The rollout program of ../shared/oracle/native (this mjModel: nu for nactuator and nout).
sed -e 's/m->nactuator/m->nu/g; s/m->nout/m->nu/g' "$ROOT/../shared/oracle/native/rollout.cc" > "$OUT/rollout.cc"
clang++ -std=c++17 -O2 -I"$SRC/include" "$OUT/rollout.cc" -L"$OUT/build/lib" -lmujoco \
  -Wl,-rpath,"$OUT/build/lib" -o "$OUT/rollout"
g++ -std=c++20 -O2 -shared -fPIC -I"$ROOT/src" -I"$ROOT/include" "$ROOT/tools/native/musl_trig.cc" \
  "$ROOT/src/math/elementary.cc" -o "$OUT/musl_trig.so"
echo "reference: LD_PRELOAD=$OUT/musl_trig.so $OUT/rollout MODEL.xml [--ctrl C.csv] [--steps N] [--every M] [--out F]"
