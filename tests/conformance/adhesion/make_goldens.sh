#!/usr/bin/env bash
# make_goldens.sh — the adhesion actuator conformance cases (body transmission through
# the contacts of the actuated body), rolled out by MuJoCo 3.5.1 (the oracle) under
# ctrlgen.mjs controls. These cases have contacts.
#
# Usage:  tests/conformance/adhesion/make_goldens.sh      (from any working directory)
#
#   1. base/<name>.xml (plane: a box held on a tilted plane; ceiling: a box hanging under
#      a ceiling, contacts in the gap included; stack: a box stuck on a sliding box,
#      condim 4) in each integrator I of (Euler RK4 implicit implicitfast):
#      models/<name>__I.xml is the base with integrator="I" added to its <option> tag.
#   2. Cone and condim variants: each base with elliptic cones; plane and ceiling with
#      frictionless contacts (condim 1 on the moving box, which has priority).
#   For each: ctrl/<name>.csv = node ctrlgen.mjs MODEL --steps 500, and
#   goldens/<model>.jsonl = rollout.mjs MODEL --steps 500 --every 10 --ctrl ...
#   3. stack with islands disabled.
#   Writes tests/conformance/adhesion_cases.txt (model, golden, steps, state or -, ctrl,
#   tolerance).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/../../../tools/oracle_case.sh"
STEPS=500
TOL=1e-8
CONTACTS=yes

case_suite adhesion

# --- 1. our models in every integrator ----------------------------------------------------
base_cases "$STEPS" "$TOL" "$CASES"

# --- 2. cone and condim variants ----------------------------------------------------------
for name in plane ceiling stack; do
  derive "$OUT/base" "$name" elliptic "elliptic friction cones" \
    -e 's|<option timestep="0.002"|<option cone="elliptic" timestep="0.002"|'
  oracle_case "$OUT/models/${name}__elliptic.xml" "$STEPS" - "$TOL" "$CASES"
done
for name in plane ceiling; do
  derive "$OUT/base" "$name" frictionless "frictionless contacts (condim 1, priority 1)" \
    -e 's|<geom name="box" type="box"|<geom name="box" type="box" condim="1" priority="1"|'
  oracle_case "$OUT/models/${name}__frictionless.xml" "$STEPS" - "$TOL" "$CASES"
done

# --- 3. box on box with islands off (the same answer, without the island split) ------------
derive "$OUT/base" stack noisland "islands disabled" \
  -e 's|<option timestep="0.002"/>|<option timestep="0.002"><flag island="disable"/></option>|'
oracle_case "$OUT/models/stack__noisland.xml" "$STEPS" - "$TOL" "$CASES"
echo "wrote $(wc -l < "$CASES") cases to $CASES"
