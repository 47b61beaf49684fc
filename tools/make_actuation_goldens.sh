#!/usr/bin/env bash
# make_actuation_goldens.sh — the actuator conformance cases (issue 3): MuJoCo's own
# actuation test models, and our muscle and slider-crank benches, rolled out by MuJoCo
# under ctrlgen.mjs controls.
#
# Usage:  tools/make_actuation_goldens.sh          (from any working directory)
#
# What it does (idempotent: tests/conformance/actuation is deleted and rebuilt):
#   1. Copies the models of ../shared/corpus/mujoco/test/engine/testdata/actuation that
#      need nothing beyond actuators (no contacts, equality, spatial tendons, sensors,
#      fluid forces, limit constraints) into
#      tests/conformance/actuation/models, unchanged (their Apache-2.0 headers kept).
#      Models that need one of those features only incidentally are derived with sed into
#      <name>__<variant>.xml, with a comment saying what was removed (the derive calls below).
#      Left out: activation (spatial tendon, muscle lengthrange by simulation, contacts),
#      tendon_dampratio (equality constraints), orientation (<orientation>
#      actuators: newer than MuJoCo 3.5.1, the oracle cannot load it).
#   2. Adds tests/models/{muscle_bench,slider_crank_bench}.xml in each integrator.
#   3. For each model: node ctrlgen.mjs MODEL --steps 500 > ctrl/<name>.csv, then
#          rollout.mjs MODEL --ctrl ctrl/<name>.csv --steps 500 --every 10
#      writing goldens/<name>.jsonl.
#      Flag cases (FLAGS below): muscle_bench with <flag actuation="disable">, and with a
#      ctrlrange and clampctrl on/off, under a wild schedule (ctrl/wild.csv: beyond every
#      range, one NaN row, ten rows of 1e20) that MuJoCo answers with "bad ctrl" warnings
#      and zeroed controls; 300 steps.
#   4. Writes tests/conformance/actuation_cases.txt, one line per case:
#          <model xml> <golden jsonl> <steps> <state json or -> <ctrl csv> <tolerance>
#
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

source "$(dirname "$0")/oracle_case.sh"
CORPUS="$(cd "$ROOT/../shared/corpus/mujoco/test/engine/testdata/actuation" && pwd)"
STEPS=500
TOL=1e-8

cd "$ROOT"
OUT=tests/conformance/actuation
rm -rf "$OUT"
mkdir -p "$OUT/models" "$OUT/goldens" "$OUT/ctrl"

# --- 1. corpus models ----------------------------------------------------------------------
for name in damper dampratio refsite; do cp "$CORPUS/$name.xml" "$OUT/models/$name.xml"; done
derive "$CORPUS" sites nofluid "option density removed (fluid forces come later)" \
  -e 's|<option density="1000">|<option>|'
derive "$CORPUS" refsite_free smooth "frictionloss and sensors removed (they come later)" \
  -e 's| frictionloss="0.1334"||g' -e '/<sensor>/,/<\/sensor>/d'
derive "$CORPUS" refsite smooth "viscosity and gravity compensation removed, gravity off (they come later)" \
  -e 's|<option viscosity="10" integrator="implicit">|<option integrator="implicit">|' \
  -e 's|<flag contact="disable"/>|<flag contact="disable" gravity="disable"/>|' \
  -e 's| actuatorgravcomp="true"||' -e 's| gravcomp="1"||g'
derive "$CORPUS" joint_force_clamp nosensor "sensors removed (they come later)" \
  -e '/<sensor>/,/<\/sensor>/d'
derive "$CORPUS" tendon_force_clamp fixed "spatial tendons, their motors and the sensors removed (they come later)" \
  -e '/<spatial/,/<\/spatial>/d' -e '/<motor tendon="spatial/d' -e '/<sensor>/,/<\/sensor>/d'
derive "$CORPUS" actearly smooth "contacts disabled (the spheres rest on the floor) and density removed (fluid forces); they come later" \
  -e 's|<option density="1000" timestep="0.05" integrator="implicitfast" />|<option timestep="0.05" integrator="implicitfast"><flag contact="disable"/></option>|'
derive "$CORPUS" actuator_group_disable nocontact "contacts disabled and joint ranges removed (contacts and limits come later)" \
  -e 's|<option actuatorgroupdisable="1 2" cone="elliptic"/>|<option actuatorgroupdisable="1 2" cone="elliptic"><flag contact="disable"/></option>|' \
  -e 's| range="[^"]*"||'

# --- 2. our benches in every integrator ----------------------------------------------------
for name in muscle_bench slider_crank_bench; do
  for integ in Euler RK4 implicit implicitfast; do
    sed -E "s/<option([ />])/<option integrator=\"$integ\"\1/" "tests/models/$name.xml" \
      > "$OUT/models/${name}__${integ}.xml"
  done
done

# --- 3-4. controls, goldens, case list -------------------------------------------------------
CASES=tests/conformance/actuation_cases.txt
: > "$CASES.tmp"
for model in "$OUT"/models/*.xml; do
  oracle_case "$model" "$STEPS" - "$TOL" "$CASES.tmp"
done

# --- flags: actuation off, clampctrl off/on, bad controls -----------------------------------
node -e '
  const rows = [];
  for (let k = 0; k < 300; k++) {
    const r = [0, 1, 2, 3, 4].map((i) => 1.5 * Math.sin(0.05 * k + i));
    if (k === 100) r[2] = NaN;
    if (k >= 150 && k < 160) r[0] = 1e20;
    rows.push(r.map((x) => (Number.isNaN(x) ? "NaN" : String(x))).join(","));
  }
  require("fs").writeFileSync(process.argv[1], "# simlab: beyond every range, a NaN row (100), 1e20 rows (150-159)\n" + rows.join("\n") + "\n");
' "$OUT/ctrl/wild.csv"
BENCH=tests/models/muscle_bench.xml
FLAGS_DIR="$OUT/flags"
mkdir -p "$FLAGS_DIR"
sed 's|<flag contact="disable"/>|<flag contact="disable" actuation="disable"/>|' "$BENCH" > "$FLAGS_DIR/muscle_bench__actuation_off.xml"
sed 's|<muscle name="m1" joint="h1"|<muscle name="m1" joint="h1" ctrlrange="0 0.5"|' "$BENCH" > "$FLAGS_DIR/muscle_bench__clampctrl_on.xml"
sed -e 's|<flag contact="disable"/>|<flag contact="disable" clampctrl="disable"/>|' \
    -e 's|<muscle name="m1" joint="h1"|<muscle name="m1" joint="h1" ctrlrange="0 0.5"|' "$BENCH" \
    > "$FLAGS_DIR/muscle_bench__clampctrl_off.xml"
for model in "$FLAGS_DIR"/*.xml; do
  ! cmp -s "$model" "$BENCH" || { echo "$model: sed changed nothing" >&2; exit 1; }
  oracle_rollout "$model" 300 - "$OUT/ctrl/wild.csv" "$TOL" "$CASES.tmp"
done

mv "$CASES.tmp" "$CASES"
echo "done: $(wc -l < "$CASES") cases"
