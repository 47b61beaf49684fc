#!/usr/bin/env bash
# Steps per second of simlab beside MuJoCo on the same models, in one run, same machine.
#
#   tools/bench_vs_mujoco.sh [BUILD_DIR]
#
# MuJoCo's numbers come from Debian's MuJoCo 2.2.2 (`mujoco-testspeed` from the package
# libmujoco-samples: one thread, control noise 0.01, starting from keyframe "test" when
# the model has one); ours from build/simlab_bench (Google Benchmark, the same control
# noise and start). Prints both and the ratio ours / MuJoCo for each model:
#   humanoid (contacts off)  tests/models/humanoid_nocontact.xml, 20000 steps
#   humanoid (contacts on)   MuJoCo's humanoid.xml, falling and lying down, 20000 steps
#   gantry holding the cube  tests/models/bench_gantry_holding.xml, runs of 1000 steps
#                            (the soft grip creeps: the cube would slip out after ~1300)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}

if ! command -v mujoco-testspeed >/dev/null; then
  echo "installing Debian's MuJoCo 2.2.2 (libmujoco-samples) for the comparison"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get install -y -qq libmujoco-dev libmujoco-samples >/dev/null
fi

# MuJoCo: median of RUNS runs of `mujoco-testspeed MODEL NSTEP NTHREAD CTRLNOISE`.
mujoco_sps() {
  local model="$1" steps="$2" runs="$3" i
  for ((i = 0; i < runs; i++)); do
    mujoco-testspeed "$model" "$steps" 1 0.01 | awk '/Steps per second/ {print $5}'
  done | sort -n | sed -n "$(((runs + 1) / 2))p"
}

# simlab: median of three repetitions of one benchmark.
simlab_sps() {
  "$build/simlab_bench" --benchmark_filter="^BM_Step$1/" --benchmark_repetitions=3 \
      --benchmark_report_aggregates_only=true --benchmark_format=json 2>/dev/null |
    python3 -c 'import json,sys; b=json.load(sys.stdin)["benchmarks"]; print([x for x in b if x["aggregate_name"]=="median"][0]["steps_per_second"])'
}

report() {
  python3 - "$1" "$2" "$3" <<'PY'
import sys
name, mj, ours = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
print(f"{name:26s} MuJoCo 2.2.2: {mj:9.0f} steps/s   simlab: {ours:9.0f} steps/s   ratio simlab/MuJoCo: {ours/mj:.2f}")
PY
}

report "humanoid (contacts off)" \
  "$(mujoco_sps "$here/tests/models/humanoid_nocontact.xml" 20000 3)" "$(simlab_sps HumanoidNoContact)"
report "humanoid (contacts on)" \
  "$(mujoco_sps "$here/tests/conformance/contact/models/humanoid.xml" 20000 3)" "$(simlab_sps Humanoid)"
report "gantry holding the cube" \
  "$(mujoco_sps "$here/tests/models/bench_gantry_holding.xml" 1000 15)" "$(simlab_sps GantryHolding)"
