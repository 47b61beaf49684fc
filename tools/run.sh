#!/usr/bin/env bash
# Installs what is missing, builds (Release, build/), and runs the main job: a short
# rollout of a model from models/, printed as a table, the lesson's actuator bench read
# by `simlab explain` as instances of p = a u + b0 + b1 l + b2 l', and the lesson's own
# Python program on the Python package (build/python).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
# The engine profile-guided: built once instrumented, trained on the repository's models,
# built again with the counts (tools/build_pgo.sh, which configures build/; 5-10% faster,
# bit-identical results).
bash tools/build_pgo.sh build simlab _simlab
model=${1:-models/double_pendulum.xml}
./build/simlab rollout "$model" --steps 500 --every 50 --table
echo
./build/simlab explain models/actuator_bench.xml
echo
PYTHONPATH="$PWD/build/python" /usr/bin/python3 examples/l2_3_actuators.py
