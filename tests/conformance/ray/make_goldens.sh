#!/usr/bin/env bash
# make_goldens.sh — rangefinder conformance cases (issue 6), rolled out by MuJoCo 3.5.1.
#
# Usage:  tests/conformance/ray/make_goldens.sh   (any working directory; set
#         SIMLAB_ORACLE=/path/to/oracle if ../shared/oracle has no node_modules)
#
#   1. MuJoCo's rfcamera.xml (sensor testdata), unchanged: a height field, a builtin
#      supersphere and primitives seen by 4x4 perspective and orthographic camera
#      rangefinders (dist, point, normal): 200 steps.
#   2. base/rangefinder_sites.xml: site rangefinders on a turning, lifting arm aimed at
#      every geom type (all data fields, several masks), under ctrlgen controls: 600
#      steps.
#   Writes tests/conformance/ray_cases.txt; tolerance 1e-9 relative.
set -euo pipefail

source "$(dirname "$0")/../../../tools/oracle_case.sh"
CORPUS="$(cd "$ROOT/../shared/corpus/mujoco/test/engine/testdata/sensor" && pwd)"
TOL=1e-9

case_suite ray

cp "$CORPUS/rfcamera.xml" "$OUT/models/rfcamera.xml"
oracle_case "$OUT/models/rfcamera.xml" 200 - "$TOL" "$CASES"
cp "$OUT/base/rangefinder_sites.xml" "$OUT/models/rangefinder_sites.xml"
oracle_case "$OUT/models/rangefinder_sites.xml" 600 - "$TOL" "$CASES"
echo "wrote $(wc -l < "$CASES") cases to $CASES"
