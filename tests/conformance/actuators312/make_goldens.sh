#!/usr/bin/env bash
# make_goldens.sh — actuators newer than the npm oracle (MuJoCo 3.5.1): pid, dcmotor,
# orientation, with several controls per actuator (nactuator, nu and nout differ). The
# reference is native MuJoCo built from source by ../shared/oracle/native/build.sh
# ($MUJOCO_NATIVE, default /work/mujoco-native; its `rollout` has rollout.mjs's
# arguments and format, with nactuator and nout in the header).
#
# Usage:  tests/conformance/actuators312/make_goldens.sh      (from any working directory)
#
#   1. base/<name>.xml in each integrator I of (Euler RK4 implicit implicitfast), or of
#      those a comment "integrators: LIST -->" in the base names:
#      models/<name>__I.xml is the base with integrator="I" added to its <option> tag;
#      ctrl/<name>__I.csv = tools/ctrl_sines.py (a smooth sine on every control entry;
#      ctrlgen.mjs cannot load these models; a comment "ctrl_sines: ARGS -->" in the
#      base adds ARGS, e.g. a ramp), goldens/<model>.jsonl = rollout MODEL --steps 500
#      --every 10 --ctrl CTRL.
#   2. Each base from its keyframe 0 (the keyframe's ctrl held: no control file), when it
#      has one.
#   A comment "golden_tol: X -->" in a base checks its cases at tolerance X instead of
#   TOL (the reason beside it).
#   3. mujoco/<name>.xml, MuJoCo's own test models (unchanged but for a comment naming
#      their source), as they are, under the same smooth controls.
#   Writes tests/conformance/actuators312_cases.txt.
# Requirements: bash, GNU sed, python3, and the native build.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
NATIVE="${MUJOCO_NATIVE:-/work/mujoco-native}"
ROLLOUT="$NATIVE/rollout"
[ -x "$ROLLOUT" ] || { echo "no $ROLLOUT: build native MuJoCo with ../shared/oracle/native/build.sh" >&2; exit 1; }
cd "$ROOT"
OUT=tests/conformance/actuators312
CASES=tests/conformance/actuators312_cases.txt
STEPS=500
EVERY=10
TOL=1e-8
rm -rf "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
mkdir -p "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
: > "$CASES"

# A header number of the native rollout of MODEL (nu, timestep).
header() { "$ROLLOUT" "$1" --steps 0 | head -1 | python3 -c "import json,sys; print(json.load(sys.stdin)['$2'])"; }

# goldens/<name>.jsonl for MODEL from STATE (- or key:K) under CTRL (- or a CSV).
native_case() {
  local model="$1" state="$2" ctrl="$3" golden args
  golden="$OUT/goldens/$(basename "$model" .xml)${state#-}.jsonl"
  golden="${golden/key:/key}"
  args=(--steps "$STEPS" --every "$EVERY" --out "$golden")
  [ "$state" = - ] || args+=(--key "${state#key:}")
  [ "$ctrl" = - ] || args+=(--ctrl "$ctrl")
  echo "rollout $model ${state} ${ctrl}"
  "$ROLLOUT" "$model" "${args[@]}"
  ! grep -qiE 'null|nan|infinity' "$golden" || { echo "$golden: non-finite values" >&2; exit 1; }
  echo "$model $golden $STEPS $state $ctrl ${CASE_TOL:-$TOL}" >> "$CASES"
}

for base in "$OUT"/base/*.xml; do
  name="$(basename "$base" .xml)"
  read -r -a extra <<< "$(sed -n 's/.*ctrl_sines:\(.*\)-->.*/\1/p' "$base")"
  read -r -a integrators <<< "$(sed -n 's/.*integrators:\(.*\)-->.*/\1/p' "$base")"
  [ ${#integrators[@]} -gt 0 ] || integrators=(Euler RK4 implicit implicitfast)
  CASE_TOL="$(sed -n 's/.*golden_tol: *\([0-9.e+-]*\) .*-->.*/\1/p' "$base")"
  for integrator in "${integrators[@]}"; do
    model="$OUT/models/${name}__$integrator.xml"
    sed "s|<option timestep=|<option integrator=\"$integrator\" timestep=|" "$base" > "$model"
    cmp -s "$model" "$base" && { echo "$base: no <option timestep=...>" >&2; exit 1; }
    ctrl="$OUT/ctrl/${name}__$integrator.csv"
    tools/ctrl_sines.py "$(header "$model" nu)" "$STEPS" "$(header "$model" timestep)" \
      ${extra[@]+"${extra[@]}"} > "$ctrl"
    native_case "$model" - "$ctrl"
  done
  if grep -q '<key ' "$base"; then native_case "$OUT/models/${name}__implicitfast.xml" key:0 -; fi
done
CASE_TOL=
for model in "$OUT"/mujoco/*.xml; do
  ctrl="$OUT/ctrl/$(basename "$model" .xml).csv"
  tools/ctrl_sines.py "$(header "$model" nu)" "$STEPS" "$(header "$model" timestep)" > "$ctrl"
  native_case "$model" - "$ctrl"
done
echo "wrote $(wc -l < "$CASES") cases to $CASES"
