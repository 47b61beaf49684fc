#!/usr/bin/env bash
# make_contact_goldens.sh — the contact conformance cases (issue 5): MuJoCo's contact
# scenes from the corpus and the gantry gripper's lab scenario, rolled out by MuJoCo
# 3.5.1 (the oracle).
#
# Usage:  tools/make_contact_goldens.sh          (from any working directory)
#
# What it does (idempotent: tests/conformance/contact is deleted and rebuilt):
#   1. Copies unchanged: actuation/activation.xml, actuation/actearly.xml (its spheres
#      touch side by side: MuJoCo's sweep and prune decides), core_constraint/dofless_contact.xml,
#      core_constraint/dofless_weld.xml, model/humanoid/humanoid.xml.
#   2. Derives sensor/contact*.xml without their <sensor> section (sensors: issue 6);
#      contact_subtree*.xml attach humanoid.xml, which is copied beside them.
#   3. Each model: ctrlgen.mjs controls, rollout.mjs --steps 200 --every 10; the humanoid
#      also from each of its four keyframes.
#   4. The lab scenario on models/gantry_gripper.xml (with the gripper.xml it attaches)
#      from keyframe 0 with the lab's
#      control files (tests/models/compose/gantry_lab_{slow,jump,hold}.csv, made by
#      make_lab_ctrl.py): lower, close, raise slowly (the cube is lifted) or in one jump
#      (the cube slips), over the whole file.
#   5. tests/models/contact_params.xml (priority, solmix, condim 1/4/6, margin/gap, an
#      explicit pair with solreffriction, an exclude) as written, with the global overrides
#      enabled, and with elliptic cones: 200 steps (elliptic: tolerance 1e-6, measured
#      worst 7e-7 in qacc as free bodies amplify last-bit differences).
#   Writes tests/conformance/contact_cases.txt (model, golden, steps, state, ctrl, tol);
#   tolerance 1e-8 relative.
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/oracle_case.sh"
STEPS=200
TOL=1e-8
CONTACTS=yes

case_suite contact

# --- 1. corpus models, unchanged ------------------------------------------------------------
for rel in test/engine/testdata/actuation/activation.xml \
           test/engine/testdata/actuation/actearly.xml \
           test/engine/testdata/core_constraint/dofless_contact.xml \
           test/engine/testdata/core_constraint/dofless_weld.xml \
           model/humanoid/humanoid.xml; do
  cp "$SHARED_CORPUS/$rel" "$OUT/models/"
done

# --- 2. sensor scenes without their sensors --------------------------------------------------
SENSOR="$SHARED_CORPUS/test/engine/testdata/sensor"
for name in contact contact_net contact_sorted contact_subtree contact_subtree_partial; do
  derive "$SENSOR" "$name" nosensor "its <sensor> section removed" \
    -e '/<sensor>/,/<\/sensor>/d'
done

# --- 3. rollouts ----------------------------------------------------------------------------
for model in "$OUT"/models/*.xml; do
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES"
done
for key in 0 1 2 3; do
  cp "$OUT/models/humanoid.xml" "$OUT/models/humanoid__key$key.xml"
  oracle_case "$OUT/models/humanoid__key$key.xml" "$STEPS" "key:$key" "$TOL" "$CASES"
done

# --- 4. the gantry gripper lab scenario --------------------------------------------------------
for run in slow jump hold; do
  ctrl="tests/models/compose/gantry_lab_$run.csv"
  steps=$(grep -vc '^#' "$ctrl")
  cp models/gantry_gripper.xml "$OUT/models/gantry_lab_$run.xml"
  cp models/gripper.xml "$OUT/models/gripper.xml"
  # The 16 s hold is recorded every 50 steps (the golden stays small).
  every_before=$EVERY
  [ "$run" = hold ] && EVERY=50
  oracle_rollout "$OUT/models/gantry_lab_$run.xml" "$steps" key:0 "$ctrl" "$TOL" "$CASES"
  EVERY=$every_before
done

# --- 5. contact parameters --------------------------------------------------------------------
cp tests/models/contact_params.xml "$OUT/models/contact_params.xml"
derive tests/models contact_params override "the global contact overrides enabled" \
  -e 's|<option |<option><flag override="enable"/></option>\n  <option |'
derive tests/models contact_params elliptic "elliptic friction cones" \
  -e 's|<option |<option cone="elliptic" |'
oracle_case "$OUT/models/contact_params.xml" "$STEPS" - "$TOL" "$CASES"
oracle_case "$OUT/models/contact_params__override.xml" "$STEPS" - "$TOL" "$CASES"
oracle_case "$OUT/models/contact_params__elliptic.xml" "$STEPS" - 1e-6 "$CASES"
