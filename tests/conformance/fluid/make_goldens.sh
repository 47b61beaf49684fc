#!/usr/bin/env bash
# make_goldens.sh — the fluid-force conformance cases, rolled out by MuJoCo 3.5.1 (the
# oracle) under ctrlgen.mjs controls.
#
# Usage:  tests/conformance/fluid/make_goldens.sh      (from any working directory)
#
#   1. base/<name>.xml (inertia-box drag with wind, viscosity only, density only, the
#      ellipsoid model with default and custom fluidcoef) in each integrator I of
#      (Euler RK4 implicit implicitfast): models/<name>__I.xml is the base with
#      integrator="I" added to its <option> tag, started from base/<name>.state.json.
#   2. MuJoCo's actuation test models that use fluid forces
#      (../shared/corpus/mujoco/test/engine/testdata/actuation): sites.xml unchanged;
#      refsite.xml without gravity compensation and actearly.xml without contacts
#      (features that come later), their fluid options kept.
#   For each: ctrl/<name>.csv = node ctrlgen.mjs MODEL --steps 500, and
#   goldens/<model>.jsonl = rollout.mjs MODEL --steps 500 --every 10 [--state ...] --ctrl ...
#   Writes tests/conformance/fluid_cases.txt (model, golden, steps, state or -, ctrl,
#   tolerance).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
ORACLE="$(cd "$ROOT/../shared/oracle" && pwd)"
CORPUS="$(cd "$ROOT/../shared/corpus/mujoco/test/engine/testdata/actuation" && pwd)"
STEPS=500
EVERY=10
TOL=1e-9
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }

cd "$ROOT"
OUT=tests/conformance/fluid
rm -rf "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
mkdir -p "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
CASES=tests/conformance/fluid_cases.txt
: > "$CASES"

# Rolls out one model (state or -, ctrl) and adds its case.
roll() {
  local model="$1" state="$2" ctrl="$3"
  local golden="$OUT/goldens/$(basename "$model" .xml).jsonl"
  local args=(--steps "$STEPS" --every "$EVERY" --ctrl "$ctrl" --out "$golden")
  [ "$state" = - ] || args+=(--state "$state")
  node "$ORACLE/rollout.mjs" "$model" "${args[@]}"
  if grep -q -i 'nan\|null' "$golden"; then echo "$golden: NaN or null" >&2; exit 1; fi
  echo "$model $golden $STEPS $state $ctrl $TOL" >> "$CASES"
}

# --- 1. our models in every integrator ----------------------------------------------------
for base in "$OUT"/base/*.xml; do
  name="$(basename "$base" .xml)"
  ctrl="$OUT/ctrl/$name.csv"
  node "$ORACLE/ctrlgen.mjs" "$base" --steps "$STEPS" --out "$ctrl"
  grep -q '<option timestep=' "$base" || { echo "$base: no <option timestep=...>" >&2; exit 1; }
  for integrator in Euler RK4 implicit implicitfast; do
    model="$OUT/models/${name}__$integrator.xml"
    sed "s|<option timestep=|<option integrator=\"$integrator\" timestep=|" "$base" > "$model"
    roll "$model" "$OUT/base/$name.state.json" "$ctrl"
  done
done

# --- 2. MuJoCo's actuation models with fluid forces ---------------------------------------
# Adds a simlab comment after the <mujoco> tag; checks that sed changed something.
derive() {
  local src="$1" variant="$2" what="$3"; shift 3
  local dst="$OUT/models/${src}__${variant}.xml"
  sed "$@" "$CORPUS/$src.xml" |
    sed -e "0,/<mujoco/s|\(<mujoco[^>]*>\)|\1\n  <!-- simlab: derived from the MuJoCo test model actuation/$src.xml: $what -->|" > "$dst"
  if cmp -s <(sed "$@" "$CORPUS/$src.xml") "$CORPUS/$src.xml"; then
    echo "derive $dst: no change" >&2; exit 1
  fi
}
cp "$CORPUS/sites.xml" "$OUT/models/sites.xml"
derive refsite nogravcomp "gravity compensation removed and gravity off (they come later); viscosity kept" \
  -e 's|<flag contact="disable"/>|<flag contact="disable" gravity="disable"/>|' \
  -e 's| actuatorgravcomp="true"||' -e 's| gravcomp="1"||g'
derive actearly nocontact "contacts disabled (the spheres rest on the floor; they come later); density kept" \
  -e 's|<option density="1000" timestep="0.05" integrator="implicitfast" />|<option density="1000" timestep="0.05" integrator="implicitfast"><flag contact="disable"/></option>|'
for model in "$OUT/models/sites.xml" "$OUT/models/refsite__nogravcomp.xml" \
             "$OUT/models/actearly__nocontact.xml"; do
  ctrl="$OUT/ctrl/$(basename "$model" .xml).csv"
  node "$ORACLE/ctrlgen.mjs" "$model" --steps "$STEPS" --out "$ctrl"
  roll "$model" - "$ctrl"
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
