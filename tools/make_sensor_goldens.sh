#!/usr/bin/env bash
# make_sensor_goldens.sh — the sensor conformance cases (issue 6): MuJoCo's sensor test
# models from the corpus and our own sensor models, rolled out by MuJoCo 3.5.1 (the
# oracle); `sensordata` is compared with every other field.
#
# Usage:  tools/make_sensor_goldens.sh          (from any working directory)
#
# What it does (idempotent: tests/conformance/sensor is emptied and rebuilt):
#   1. Copies the corpus sensor models (testdata/sensor/*.xml) that simlab runs, with the
#      humanoid.xml the contact_subtree*.xml models attach.
#   2. Copies our own sensor models, tests/sensors/*.xml.
#   3. Each model: ctrlgen.mjs controls, rollout.mjs --steps 200 --every 10; models with
#      keyframes also from keyframe 0 (as a copy named NAME__key0.xml).
#   Writes tests/conformance/sensor_cases.txt (model, golden, steps, state, ctrl, tol);
#   tolerance 1e-8 relative.
# Requirements: bash, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/oracle_case.sh"
STEPS=200
TOL=1e-8
CONTACTS=yes

case_suite sensor

# --- 1. corpus sensor models ---------------------------------------------------------------
SENSOR="$SHARED_CORPUS/test/engine/testdata/sensor"
CORPUS_MODELS=()
# geometric sensors (camprojection, insidesite, distance/normal/fromto)
CORPUS_MODELS+=(camprojection insidesite fromto_capsule_ellipsoid fromto_primitive fromto_convex)
# (fromto_body_body builds its bodies' geoms with <replicate>)
CORPUS_MODELS+=(fromto_body_body)
# contact sensors (site/geom/body/subtree criteria, reductions); the subtree scenes attach
# humanoid.xml, copied beside them (not a case of its own: it is model/humanoid/humanoid.xml,
# a contact case with all its keyframes, tools/make_contact_goldens.sh)
CORPUS_MODELS+=(contact contact_net contact_sorted contact_subtree contact_subtree_partial)
cp "$SENSOR/humanoid.xml" "$OUT/models/"
for name in "${CORPUS_MODELS[@]}"; do
  cp "$SENSOR/$name.xml" "$OUT/models/"
done

# --- 2. our own sensor models --------------------------------------------------------------
cp tests/sensors/*.xml "$OUT/models/"

# --- 3. rollouts ---------------------------------------------------------------------------
for model in "$OUT"/models/*.xml; do
  [ "$(basename "$model")" != humanoid.xml ] || continue
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES"
  if grep -q "<key" "$model"; then
    # (a copy under its own name: the test names each case by its model file)
    cp "$model" "${model%.xml}__key0.xml"
    oracle_case "${model%.xml}__key0.xml" "$STEPS" key:0 "$TOL" "$CASES"
  fi
done
echo "wrote $CASES ($(wc -l < "$CASES") cases)"
