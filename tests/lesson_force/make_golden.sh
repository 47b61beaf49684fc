#!/usr/bin/env bash
# Golden of tests/lesson_force_sensor_test.cc: MuJoCo 3.5.1's rollout of the gantry
# gripper with lesson 2.3's force and torque sensors at a site on the carriage (the same
# two insertions the test makes in models/gantry_gripper.xml), from keyframe 0 with the
# lab's slow raise (tests/models/compose/gantry_lab_slow.csv), every 50 steps.
#
# Usage: tests/lesson_force/make_golden.sh   (SIMLAB_ORACLE: the oracle folder with
#        node_modules/mujoco; default ../shared/oracle beside the repository)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
ORACLE="${SIMLAB_ORACLE:-$ROOT/../shared/oracle}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$ROOT"
cp models/gripper.xml "$WORK/"
# The site after the carriage's geom, the sensors before the keyframes.
sed -e 's|^\( *\)<attach model="gripper"|\1<site name="carriage_ft" pos="0 0 0.01"/>\n&|' \
    -e 's|^  <keyframe>|  <sensor>\n    <force name="carriage_force" site="carriage_ft"/>\n    <torque name="carriage_torque" site="carriage_ft"/>\n  </sensor>\n&|' \
    models/gantry_gripper.xml > "$WORK/gantry_force.xml"
grep -q carriage_ft "$WORK/gantry_force.xml"
grep -q '<force name' "$WORK/gantry_force.xml"
node "$ORACLE/rollout.mjs" "$WORK/gantry_force.xml" --key 0 \
  --ctrl tests/models/compose/gantry_lab_slow.csv --steps 3500 --every 50 \
  --out tests/lesson_force/gantry_force_slow.jsonl
