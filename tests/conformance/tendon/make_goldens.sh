#!/usr/bin/env bash
# make_goldens.sh — the spatial tendon conformance cases: the models in base/ (no limits,
# friction loss or contacts) in each integrator, rolled out by MuJoCo 3.5.1 (the oracle).
#
# Usage:  tests/conformance/tendon/make_goldens.sh      (from any working directory)
#
# For every base/<name>.xml and integrator I in (Euler RK4 implicit implicitfast):
#   models/<name>__I.xml   = the base with integrator="I" added to its <option> tag;
#   ctrl/<name>.csv        = node ctrlgen.mjs MODEL --steps 500 (models with actuators);
#   goldens/<name>__I.jsonl = rollout.mjs MODEL --steps 500 --every 10
#                             [--state base/<name>.state.json] [--ctrl ctrl/<name>.csv]
# and writes tests/conformance/tendon_cases.txt (format of tests/conformance/cases.txt:
# model, golden, steps, state or -, ctrl or -, tolerance).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/../../../tools/oracle_case.sh"
STEPS=500
TOL=1e-9

case_suite tendon
for base in "$OUT"/base/*.xml; do
  name="$(basename "$base" .xml)"
  state="$OUT/base/$name.state.json"
  [ -f "$state" ] || state=-
  ctrl=-
  if grep -q "<actuator>" "$base"; then
    ctrl="$OUT/ctrl/$name.csv"
    node "$ORACLE/ctrlgen.mjs" "$base" --steps "$STEPS" --out "$ctrl"
  fi
  models="$(integrator_models "$base")"
  for model in $models; do
    oracle_rollout "$model" "$STEPS" "$state" "$ctrl" "$TOL" "$CASES"
  done
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
