#!/usr/bin/env bash
# Installs a built simlab into a fresh prefix and uses it from a project outside the tree,
# as a user would (ctest's install_find_package, tests/install/install_test.cmake):
#
#   run_install_test.sh SOURCE_DIR BUILD_DIR CMAKE GENERATOR CXX_COMPILER CONFIG
#
# 1. cmake --install BUILD_DIR --prefix BUILD_DIR/install_test/prefix (removed first);
# 2. the installed package names neither the source nor the build tree;
# 3. tests/install/consumer is configured with CMAKE_PREFIX_PATH=prefix and built; it
#    found simlab in the prefix and compiled against the installed headers only;
# 4. it runs on models/actuator_bench.xml and prints the expected force and time; the
#    installed `simlab` command runs too.
# Any failing step stops the test with a message naming it.
set -euo pipefail

if [[ $# -lt 5 || $# -gt 6 ]]; then
  echo "usage: $0 SOURCE_DIR BUILD_DIR CMAKE GENERATOR CXX_COMPILER CONFIG" >&2
  exit 2
fi
source_dir=$(realpath "$1")
build_dir=$(realpath "$2")
cmake=$3
generator=$4
cxx=$5
config=${6:-Release}

work="$build_dir/install_test"
prefix="$work/prefix"
consumer_build="$work/consumer-build"
model="$source_dir/models/actuator_bench.xml"

step=""
fail() {
  echo "install_find_package FAILED at '$step': $*" >&2
  exit 1
}
trap 'echo "install_find_package FAILED at step \"$step\" (exit $?, line $LINENO)" >&2' ERR
begin() {
  step=$1
  echo "== $step"
}

begin "fresh prefix"
rm -rf "${work:?}"
mkdir -p "$work"

begin "install"
# A DESTDIR from the environment would put the files elsewhere.
env -u DESTDIR "$cmake" --install "$build_dir" --prefix "$prefix" --config "$config" \
  > "$work/install.log" || { cat "$work/install.log" >&2; fail "cmake --install failed"; }

begin "installed files"
package_dir=$(dirname "$(find "$prefix" -path '*/cmake/simlab/simlabConfig.cmake' -print -quit)")
[[ "$package_dir" != "." ]] || fail "no simlabConfig.cmake under $prefix"
for f in "$package_dir"/simlabConfig.cmake "$package_dir"/simlabConfigVersion.cmake \
         "$package_dir"/simlabTargets.cmake "$prefix/bin/simlab" \
         "$prefix"/include/simlab/{simlab,model,data}.h; do
  [[ -f "$f" ]] || fail "missing $f"
done
[[ -n "$(find "$prefix" -name 'libsimlab_core.a' -print -quit)" ]] \
  || fail "no libsimlab_core.a under $prefix"

begin "package names no source or build path"
# The build tree lies inside the source tree here, but need not.
for tree in "$source_dir" "$build_dir"; do
  if grep -rn --fixed-strings "$tree" "$package_dir"; then
    fail "the installed package refers to $tree (lines above)"
  fi
done

begin "configure consumer"
"$cmake" -S "$source_dir/tests/install/consumer" -B "$consumer_build" -G "$generator" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE="$config" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$work/configure.log" \
  || { cat "$work/configure.log" >&2; fail "configuring the consumer failed"; }

begin "consumer found the installed package"
found=$(sed -n 's/^simlab_DIR:PATH=//p' "$consumer_build/CMakeCache.txt")
[[ "$(realpath "$found")" == "$(realpath "$package_dir")" ]] \
  || fail "simlab_DIR is '$found', not $package_dir"

begin "build consumer"
"$cmake" --build "$consumer_build" --config "$config" -j2 > "$work/build.log" \
  || { cat "$work/build.log" >&2; fail "building the consumer failed"; }

begin "consumer compiled against the installed headers"
# Its compile command names no include folder of the source tree...
if grep -n --fixed-strings "$source_dir/include" "$consumer_build/compile_commands.json"; then
  fail "the consumer's compile command uses $source_dir/include"
fi
grep -q --fixed-strings "$prefix/include" "$consumer_build/compile_commands.json" \
  || fail "the consumer's compile command does not use $prefix/include"
# ...and the headers it read (the compiler's dependency file, when the generator keeps it:
# Makefiles do, Ninja folds it into its own log) are the installed ones.
depfile=$(find "$consumer_build" -name 'main.cc.o.d' -print -quit)
if [[ -n "$depfile" ]]; then
  grep -q --fixed-strings "$prefix/include/simlab/simlab.h" "$depfile" \
    || fail "main.cc did not include $prefix/include/simlab/simlab.h ($depfile)"
  if grep -n --fixed-strings "$source_dir/include" "$depfile"; then
    fail "main.cc read headers from $source_dir/include ($depfile)"
  fi
fi

begin "run consumer"
consumer=$(find "$consumer_build" -type f -name consumer -perm -u+x -print -quit)
[[ -n "$consumer" ]] || fail "no consumer executable in $consumer_build"
output=$("$consumer" "$model") || fail "consumer exited with $?"
echo "$output"
expected=$'motor actuator_force 0.500000\ntime 0.200000'
[[ "$output" == "$expected" ]] || fail "consumer printed the above, expected:"$'\n'"$expected"

begin "run installed simlab"
explain=$("$prefix/bin/simlab" explain "$model") || fail "simlab explain exited with $?"
grep -q motor <<< "$explain" || fail "simlab explain printed no 'motor':"$'\n'"$explain"

echo "install_find_package: OK"
