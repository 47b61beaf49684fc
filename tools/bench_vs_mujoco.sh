#!/usr/bin/env bash
# Steps per second of simlab beside MuJoCo on the same model, in one run, same machine.
#
#   tools/bench_vs_mujoco.sh [BUILD_DIR]
#
# MuJoCo's number comes from Debian's MuJoCo 2.2.2 (`mujoco-testspeed` from the package
# libmujoco-samples: one thread, control noise 0.01); ours from build/simlab_bench
# (Google Benchmark, the same control noise). Prints both and the ratio ours / MuJoCo.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
model=$here/tests/models/humanoid_nocontact.xml
steps=20000

if ! command -v mujoco-testspeed >/dev/null; then
  echo "installing Debian's MuJoCo 2.2.2 (libmujoco-samples) for the comparison"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get install -y -qq libmujoco-dev libmujoco-samples >/dev/null
fi

# MuJoCo: median of three runs of `mujoco-testspeed MODEL NSTEP NTHREAD CTRLNOISE`.
mj_runs=()
for _ in 1 2 3; do
  sps=$(mujoco-testspeed "$model" "$steps" 1 0.01 | awk '/Steps per second/ {print $5}')
  mj_runs+=("$sps")
done
mj=$(printf '%s\n' "${mj_runs[@]}" | sort -n | sed -n 2p)

# simlab: median of three repetitions of the benchmark.
ours=$("$build/simlab_bench" --benchmark_filter=HumanoidNoContact --benchmark_repetitions=3 \
        --benchmark_report_aggregates_only=true --benchmark_format=json 2>/dev/null |
       python3 -c 'import json,sys; b=json.load(sys.stdin)["benchmarks"]; print([x for x in b if x["aggregate_name"]=="median"][0]["steps_per_second"])')

python3 - "$mj" "$ours" <<'PY'
import sys
mj, ours = float(sys.argv[1]), float(sys.argv[2])
print(f"humanoid (contacts off)  MuJoCo 2.2.2: {mj:10.0f} steps/s   simlab: {ours:10.0f} steps/s   ratio simlab/MuJoCo: {ours/mj:.2f}")
PY
