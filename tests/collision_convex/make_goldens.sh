#!/bin/sh
# Goldens of tests/collision_convex_test.cc (MuJoCo's poses and contacts per keyframe).
#
#   python3 tests/collision_convex/make_models.py     (only to change the models)
#   sh tests/collision_convex/make_goldens.sh         (from the repository root)
set -e
here=$(dirname "$0")
for model in "$here"/models/*.xml; do
  name=$(basename "$model" .xml)
  node "$here/dump_keys.mjs" "$model" "$here/goldens/$name.json"
  echo "$name"
done
