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

source "$(dirname "$0")/../../../tools/oracle_case.sh"
CORPUS="$(cd "$ROOT/../shared/corpus/mujoco/test/engine/testdata/actuation" && pwd)"
STEPS=500
TOL=1e-9

case_suite fluid

# --- 1. our models in every integrator (one control file per base) -----------------------
for base in "$OUT"/base/*.xml; do
  name="$(basename "$base" .xml)"
  ctrl="$OUT/ctrl/$name.csv"
  node "$ORACLE/ctrlgen.mjs" "$base" --steps "$STEPS" --out "$ctrl"
  models="$(integrator_models "$base")"
  for model in $models; do
    oracle_rollout "$model" "$STEPS" "$OUT/base/$name.state.json" "$ctrl" "$TOL" "$CASES"
  done
done

# --- 2. MuJoCo's actuation models with fluid forces ---------------------------------------
cp "$CORPUS/sites.xml" "$OUT/models/sites.xml"
derive "$CORPUS" refsite nogravcomp "gravity compensation removed and gravity off (they come later); viscosity kept" \
  -e 's|<flag contact="disable"/>|<flag contact="disable" gravity="disable"/>|' \
  -e 's| actuatorgravcomp="true"||' -e 's| gravcomp="1"||g'
derive "$CORPUS" actearly nocontact "contacts disabled (the spheres rest on the floor; they come later); density kept" \
  -e 's|<option density="1000" timestep="0.05" integrator="implicitfast" />|<option density="1000" timestep="0.05" integrator="implicitfast"><flag contact="disable"/></option>|'
for model in "$OUT/models/sites.xml" "$OUT/models/refsite__nogravcomp.xml" \
             "$OUT/models/actearly__nocontact.xml"; do
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES"
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
