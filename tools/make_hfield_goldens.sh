#!/usr/bin/env bash
# make_hfield_goldens.sh — the height-field collision cases: convex geoms falling onto a
# bumpy, tilted hfield and sliding or rolling on it (tests/hfield/*.xml), rolled out by
# MuJoCo 3.5.1 (the oracle), and MuJoCo's contacts at states of its own trajectory.
#
# Usage:  tools/make_hfield_goldens.sh          (from any working directory)
#
# What it does (idempotent: tests/conformance/hfield is emptied and rebuilt):
#   1. Rollouts (ctrlgen.mjs controls for the pushed capsule, --every 10) of each
#      one-shape scene tests/hfield/hfield_SHAPE.xml, with pyramidal and elliptic cones;
#      box and mesh also with a geom margin of .005 (MuJoCo's margin handling, and smooth
#      GJK/EPA); the all-shapes scene hfield_convex.xml (an explicit <pair> with margin and
#      gap) with a margin of .005 on every geom, both cones.
#      Steps: 400, except where a box or mesh without margin rests on several prisms and
#      the two engines' last-bit differences in the constraint solver (their contacts are
#      bit-identical from the same state) flip which prism face EPA reports: those cases
#      stop before that (box 120 pyramidal / 280 elliptic, mesh 270 elliptic).
#      Tolerance 1e-8 relative; 1e-6 for the elliptic all-shapes scene (measured worst
#      1.5e-8 in qacc, as elliptic cones amplify last-bit differences).
#   2. Contacts along MuJoCo's own trajectory: hfield_convex.xml (no margins) rolled out
#      400 steps; its states at steps 105, 130, 200, 300 and 400 become keyframes of
#      tests/collision_pairs/models/hfield_convex_sNNN.xml, whose contact goldens
#      tests/collision_pairs/make_goldens.sh writes (tests/collision_pair_test.cc).
#   Writes tests/conformance/hfield_cases.txt (model, golden, steps, state, ctrl, tol).
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/oracle_case.sh"
TOL=1e-8
CONTACTS=yes

case_suite hfield
SRC=tests/hfield

# --- 1. rollouts -----------------------------------------------------------------------------
ELLIPTIC=(-e 's|<option timestep="0.002"/>|<option timestep="0.002" cone="elliptic"/>|')
MARGIN=(-e 's|<option timestep="0.002"/>|&\n  <default><geom margin=".005"/></default>|')
# (the steps of each variant: name:pyramidal:elliptic)
for entry in sphere:400:400 capsule:400:400 ellipsoid:400:400 cylinder:400:400 \
             box:120:280 mesh:400:270; do
  IFS=: read -r shape steps steps_elliptic <<< "$entry"
  cp "$SRC/hfield_$shape.xml" "$OUT/models/"
  oracle_case "$OUT/models/hfield_$shape.xml" "$steps" - "$TOL" "$CASES"
  derive "$SRC" "hfield_$shape" elliptic "elliptic friction cones" "${ELLIPTIC[@]}"
  oracle_case "$OUT/models/hfield_${shape}__elliptic.xml" "$steps_elliptic" - "$TOL" "$CASES"
done
for shape in box mesh convex; do
  derive "$SRC" "hfield_$shape" margin "a margin of .005 on every geom" "${MARGIN[@]}"
  oracle_case "$OUT/models/hfield_${shape}__margin.xml" 400 - "$TOL" "$CASES"
  derive "$SRC" "hfield_$shape" margin_elliptic "a margin of .005 on every geom, elliptic cones" \
    "${MARGIN[@]}" "${ELLIPTIC[@]}"
  tol=$TOL
  [ "$shape" != convex ] || tol=1e-6
  oracle_case "$OUT/models/hfield_${shape}__margin_elliptic.xml" 400 - "$tol" "$CASES"
done

# --- 2. contacts along MuJoCo's trajectory ---------------------------------------------------
PAIRS=tests/collision_pairs
trajectory="$(mktemp)"
trap 'rm -f "$trajectory"' EXIT
node "$ORACLE/ctrlgen.mjs" "$SRC/hfield_convex.xml" --steps 400 --out "$trajectory.csv"
node "$ORACLE/rollout.mjs" "$SRC/hfield_convex.xml" --steps 400 --ctrl "$trajectory.csv" \
  --out "$trajectory"
rm -f "$trajectory.csv"
names=()
for step in 105 130 200 300 400; do
  name="hfield_convex_s$step"
  key="$(node -e '
    const fs = require("fs");
    const [file, step] = process.argv.slice(1);
    for (const line of fs.readFileSync(file, "utf8").split("\n")) {
      if (!line.includes("\"step\"")) continue;
      const r = JSON.parse(line);
      if (r.step === Number(step)) {
        console.log(`<key qpos="${r.qpos.join(" ")}" qvel="${r.qvel.join(" ")}"/>`);
      }
    }' "$trajectory" "$step")"
  [ -n "$key" ] || { echo "no step $step in the trajectory" >&2; exit 1; }
  {
    echo "<!-- hfield : every convex type, key=0 (MuJoCo's state after $step steps of $SRC/hfield_convex.xml) -->"
    sed -e "s|</mujoco>|  <keyframe>\n    $key\n  </keyframe>\n</mujoco>|" "$SRC/hfield_convex.xml"
  } > "$PAIRS/models/$name.xml"
  names+=("$name")
done
"$PAIRS/make_goldens.sh" "${names[@]}"
echo "wrote $CASES ($(wc -l < "$CASES") cases)"
