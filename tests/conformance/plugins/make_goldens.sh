#!/usr/bin/env bash
# make_goldens.sh — MuJoCo's models with its first-party plugins: signed distance fields
# (mujoco.sdf.torus, .bolt, .nut, .gear, .bowl) and the touch grid sensor
# (mujoco.sensor.touch_grid); copied into mujoco/ from MuJoCo's model/plugin/sdf,
# model/plugin/sensor, model/tactile, test/engine/testdata/ray and test/plugin/sensor,
# each naming its source in its first line.
# The npm oracle has no plugins, so the reference is native MuJoCo at the oracle's commit
# with its plugins, built by tools/native/build_oracle_era.sh ($MUJOCO_ORACLE_ERA,
# default /work/mujoco-oracle-era), its trigonometry musl's as the oracle's (LD_PRELOAD
# musl_trig.so). Its rollouts equal the npm oracle's to the bit on the models both load
# (the sdf corpus cases, checked below).
#
# Usage:  tests/conformance/plugins/make_goldens.sh      (from any working directory)
#
#   Each line of MODELS: a model in mujoco/, the steps, how often to record, the
#   tolerance, and a control file in ctrl/ (written by hand: ctrlgen.mjs cannot load
#   these models) or "none". goldens/<name>.jsonl = rollout MODEL --steps N --every E.
#   Writes tests/conformance/plugins_cases.txt.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
ERA="${MUJOCO_ORACLE_ERA:-/work/mujoco-oracle-era}"
[ -x "$ERA/rollout" ] && [ -f "$ERA/musl_trig.so" ] ||
  { echo "no $ERA/rollout: run tools/native/build_oracle_era.sh $ERA" >&2; exit 1; }
rollout() { LD_PRELOAD="$ERA/musl_trig.so" "$ERA/rollout" "$@"; }
cd "$ROOT"
OUT=tests/conformance/plugins
CASES=tests/conformance/plugins_cases.txt
MODELS=(
  # three tori falling on a tilted cylinder and each other; a bowl holding three balls;
  # a nut on a bolt; two gears, one driven (ctrl 0.5: they mesh from step ~100)
  "sdf_torus.xml 600 20 1e-9 none"
  "sdf_bowl.xml 600 20 1e-9 none"
  "sdf_nutbolt.xml 600 20 1e-9 none"
  "sdf_gear.xml 600 20 1e-9 gear_half.csv"
  # primitives dropped on a torus; a torus on a mesh die (the mesh's side of the field is
  # the reference's ray estimate), on a mesh cow, and as a mug's handle
  "sdf_primitives.xml 600 20 1e-9 none"
  "sdf_mesh.xml 600 20 1e-9 none"
  "sdf_cow.xml 600 20 1e-9 none"
  "sdf_mug.xml 600 20 1e-9 none"
  # rangefinders swinging over a torus (rays marching on the field); tactile sensors
  # touching a gear
  "sdf_ray.xml 300 10 1e-9 none"
  "sdf_tactile.xml 300 50 1e-9 none"
  # touch grids: 7 x 7 cells of 3 channels under an ellipsoid rolling on a height field
  # among boxes; a box resting on a floor seen by a 3 x 3 grid of 4 channels
  "touch_grid.xml 300 10 1e-9 none"
  "touch_grid_test.xml 300 10 1e-9 none"
)

# The reference agrees with the npm oracle's goldens of the corpus's sdf scenes.
for name in sdf_drops sdf_meshsdf; do
  golden=tests/conformance/corpus/goldens/$name.jsonl
  steps=$(tail -1 "$golden" | python3 -c "import json,sys; print(json.load(sys.stdin)['step'])")
  every=$(sed -n 3p "$golden" | python3 -c "import json,sys; print(json.load(sys.stdin)['step'])")
  rollout "tests/conformance/corpus/sdf/$name.xml" --steps "$steps" --every "$every" --out /tmp/era_check.jsonl
  python3 - "$golden" /tmp/era_check.jsonl <<'PY'
import json, sys
a = [json.loads(l) for l in open(sys.argv[1])][1:]
b = [json.loads(l) for l in open(sys.argv[2])][1:]
assert len(a) == len(b) and all(x[k] == y[k] for x, y in zip(a, b) for k in ('qpos', 'qvel', 'qacc')), \
    sys.argv[1] + ": the native reference differs from the npm oracle"
PY
done

rm -rf "$OUT/goldens"
mkdir -p "$OUT/goldens"
: > "$CASES"
for line in "${MODELS[@]}"; do
  read -r model steps every tol ctrl <<< "$line"
  name=$(basename "$model" .xml)
  args=(--steps "$steps" --every "$every" --out "$OUT/goldens/$name.jsonl")
  [ "$ctrl" = none ] || args+=(--ctrl "$OUT/ctrl/$ctrl")
  rollout "$OUT/mujoco/$model" "${args[@]}"
  ! grep -qiE 'null|nan|infinity' "$OUT/goldens/$name.jsonl" || { echo "$name: non-finite values" >&2; exit 1; }
  echo "$OUT/mujoco/$model $OUT/goldens/$name.jsonl $steps - $([ "$ctrl" = none ] && echo - || echo "$OUT/ctrl/$ctrl") $tol" >> "$CASES"
  echo "$name: $(wc -c < "$OUT/goldens/$name.jsonl") bytes"
done
