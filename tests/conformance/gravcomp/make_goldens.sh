#!/usr/bin/env bash
# make_goldens.sh — the gravity compensation conformance cases, rolled out by MuJoCo 3.5.1
# (the oracle) under ctrlgen.mjs controls.
#
# Usage:  tests/conformance/gravcomp/make_goldens.sh      (from any working directory)
#
#   1. base/<name>.xml (arm: partial, full and over-compensation, actuatorgravcomp on
#      ball, slide and free joints with a joint force clamp; noactuator: nu = 0, negative
#      gravcomp, tilted gravity) in each integrator I of (Euler RK4 implicit implicitfast):
#      models/<name>__I.xml is the base with integrator="I" added to its <option> tag.
#   2. Flag variants: arm with gravity disabled (no compensation either), noactuator with
#      only the negative gravcomp left (MuJoCo then skips compensation altogether), arm
#      with springs and dampers disabled (MuJoCo's passive stage, gravcomp included, is
#      skipped).
#   (MuJoCo's refsite.xml, gravcomp on every body and actuatorgravcomp on every joint, is
#   an actuation case, unchanged: tools/make_actuation_goldens.sh.)
#   For each: ctrl/<name>.csv = node ctrlgen.mjs MODEL --steps 500, and
#   goldens/<model>.jsonl = rollout.mjs MODEL --steps 500 --every 10 --ctrl ...
#   Writes tests/conformance/gravcomp_cases.txt (model, golden, steps, state or -, ctrl,
#   tolerance).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/../../../tools/oracle_case.sh"
STEPS=500
TOL=1e-8

case_suite gravcomp

# --- 1. our models in every integrator ----------------------------------------------------
base_cases "$STEPS" "$TOL" "$CASES"

# --- 2. flag variants ---------------------------------------------------------------------
derive "$OUT/base" arm nogravity "gravity disabled, which disables compensation too" \
  -e 's|<flag contact="disable"/>|<flag contact="disable" gravity="disable"/>|'
derive "$OUT/base" noactuator negativeonly "only the negative gravcomp kept" \
  -e 's| gravcomp="0.8"||' -e 's| gravcomp="1"||'
derive "$OUT/base" arm nopassive "springs and dampers disabled, which skips compensation too" \
  -e 's|<flag contact="disable"/>|<flag contact="disable" spring="disable" damper="disable"/>|'
for model in "$OUT/models/arm__nogravity.xml" "$OUT/models/noactuator__negativeonly.xml" \
             "$OUT/models/arm__nopassive.xml"; do
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES"
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
