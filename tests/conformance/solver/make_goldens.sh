#!/usr/bin/env bash
# make_goldens.sh — the contact solver conformance cases (friction cones and noslip),
# rolled out by MuJoCo 3.5.1 (the oracle) under ctrlgen.mjs controls.
#
# Usage:  tests/conformance/solver/make_goldens.sh      (from any working directory)
#
#   1. base/contact_cones.xml (spheres with condim 3, 4, 6 rolling, sliding and spinning,
#      stacked boxes, a frictionless puck, a hinged paddle with a limit hitting a sphere;
#      from its keyframe "moving") with <option cone="C" solver="S"/> for C in pyramidal,
#      elliptic and S in Newton, CG, PGS: models/contact_cones__C_S.xml.
#   2. Variants of the elliptic Newton model: noslip (noslip_iterations 10, also with
#      pyramidal cones and with PGS), impratio 10, islands disabled (one whole problem),
#      and the implicitfast integrator.
#   3. base/ball_chains.xml (spheres on slide/hinge chains: no free bodies, so our smooth
#      dynamics match MuJoCo's nearly bit for bit and Newton and PGS are checked to 1e-9
#      over 400 steps, CG to 1e-3): both cones x the three solvers, and noslip with
#      Newton, CG and PGS.
#   4. MuJoCo's actuation test model actuation/activation.xml (boxes on a plane, limits, a
#      muscle) with elliptic cones, and with elliptic cones and noslip.
#   For each: ctrl/<name>.csv = node ctrlgen.mjs MODEL --steps N, and
#   goldens/<name>.jsonl = rollout.mjs MODEL --steps N --every 10 --ctrl ... (N = 100 for
#   the bench, tolerances by bench_tol below; 400 steps for the others).
#   CG and PGS cases run to a tight solver tolerance (TIGHT below).
#   Writes tests/conformance/solver_cases.txt (model, golden, steps, state, ctrl, tolerance).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/../../../tools/oracle_case.sh"
CORPUS="$(cd "$ROOT/../shared/corpus/mujoco/test/engine/testdata" && pwd)"
STEPS=400      # the activation model
BENCH_STEPS=100
TOL=1e-8
export CONTACTS=yes
# CG and PGS stop at opt.tolerance, so a last-bit difference in their input (our smooth
# dynamics and collisions are not yet bit-identical to MuJoCo's) can change the iteration
# count and the answer by the tolerance; their cases run to a tight tolerance instead.
TIGHT='tolerance="1e-13" iterations="300" noslip_tolerance="1e-13"'

case_suite solver
BASE="$OUT/base/contact_cones.xml"

# The bench's tolerance: free bodies bounce and spin on each other, which amplifies
# last-bit differences. Since "simple" bodies keep MuJoCo's diagonal mass matrix
# (dof_M0), the measured worst errors over 100 steps are 1e-10 (elliptic Newton), 1e-12
# (elliptic PGS), 1e-9..1e-6 (pyramidal Newton, noslip, impratio, islands off) and up to
# 1e-5 (CG); they grow with the horizon.
bench_tol() {
  case "$1" in
    elliptic_Newton|elliptic_implicitfast) echo 1e-8 ;;
    elliptic_impratio) echo 1e-6 ;;
    *CG*|*PGS*) echo 1e-4 ;;
    *) echo 1e-5 ;;
  esac
}

# Writes models/contact_cones__NAME.xml: the bench with the given <option> attributes.
bench_variant() {
  local name="$1" attrs="$2" model="$OUT/models/contact_cones__$1.xml"
  sed "s|<option timestep=|<option $attrs timestep=|" "$BASE" > "$model"
  echo "$model"
}

# --- 1. cones x solvers --------------------------------------------------------------------
for cone in pyramidal elliptic; do
  for solver in Newton CG PGS; do
    attrs="cone=\"$cone\" solver=\"$solver\""
    [ $solver = Newton ] || attrs="$attrs $TIGHT"
    model=$(bench_variant "${cone}_$solver" "$attrs")
    oracle_case "$model" "$BENCH_STEPS" key:0 "$(bench_tol "${cone}_$solver")" "$CASES"
  done
done

# --- 2. noslip, impratio, islands, integrator ----------------------------------------------
VARIANTS=(
  "elliptic_noslip|cone=\"elliptic\" noslip_iterations=\"10\""
  "pyramidal_noslip|noslip_iterations=\"10\""
  "elliptic_PGS_noslip|cone=\"elliptic\" solver=\"PGS\" noslip_iterations=\"10\" $TIGHT"
  "elliptic_CG_noslip|cone=\"elliptic\" solver=\"CG\" noslip_iterations=\"5\" $TIGHT"
  "elliptic_impratio|cone=\"elliptic\" impratio=\"10\""
  "pyramidal_impratio|impratio=\"5\""
  "elliptic_implicitfast|cone=\"elliptic\" integrator=\"implicitfast\""
)
for variant in "${VARIANTS[@]}"; do
  model=$(bench_variant "${variant%%|*}" "${variant#*|}")
  oracle_case "$model" "$BENCH_STEPS" key:0 "$(bench_tol "${variant%%|*}")" "$CASES"
done
model=$(bench_variant elliptic_noisland 'cone="elliptic"')
sed -i 's|<option \([^/]*\)/>|<option \1><flag island="disable"/></option>|' "$model"
oracle_case "$model" "$BENCH_STEPS" key:0 "$(bench_tol elliptic_noisland)" "$CASES"

# --- 3. the free-body-less bench, tightly ------------------------------------------------------
CHAINS="$OUT/base/ball_chains.xml"
CHAIN_VARIANTS=(
  "pyramidal_Newton|"
  "pyramidal_CG|solver=\"CG\""
  "pyramidal_PGS|solver=\"PGS\""
  "elliptic_Newton|cone=\"elliptic\""
  "elliptic_CG|cone=\"elliptic\" solver=\"CG\""
  "elliptic_PGS|cone=\"elliptic\" solver=\"PGS\""
  "elliptic_noslip|cone=\"elliptic\" noslip_iterations=\"10\""
  "elliptic_CG_noslip|cone=\"elliptic\" solver=\"CG\" noslip_iterations=\"10\""
  "pyramidal_PGS_noslip|solver=\"PGS\" noslip_iterations=\"10\""
)
for variant in "${CHAIN_VARIANTS[@]}"; do
  model="$OUT/models/ball_chains__${variant%%|*}.xml"
  sed "s|<option timestep=|<option ${variant#*|} timestep=|" "$CHAINS" > "$model"
  # CG stops at opt.tolerance: the last-bit differences left drift its answers apart by
  # about the tolerance after 100-150 steps (worst 6e-4 measured over 400).
  tol=1e-9
  case "$variant" in *CG*) tol=1e-3 ;; esac
  oracle_case "$model" "$STEPS" key:0 "$tol" "$CASES"
done

# --- 4. MuJoCo's activation model ----------------------------------------------------------
derive "$CORPUS/actuation" activation elliptic "elliptic cones" \
  -e 's|<option density="1000"/>|<option density="1000" cone="elliptic"/>|'
derive "$CORPUS/actuation" activation elliptic_noslip "elliptic cones and noslip" \
  -e 's|<option density="1000"/>|<option density="1000" cone="elliptic" noslip_iterations="4"/>|'
for model in "$OUT/models/activation__elliptic.xml" "$OUT/models/activation__elliptic_noslip.xml"; do
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES"
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
