# oracle_case.sh — sourced by the golden scripts (tools/make_*_goldens.sh,
# tests/conformance/*/make_goldens.sh): the oracle's location and the steps they share.
#
# Sourcing sets ROOT (the repository), ORACLE (../shared/oracle beside it) and
# SHARED_CORPUS (MuJoCo's models in ../shared/corpus/mujoco), checks that
# `npm ci` was run there, and sets EVERY=10 unless the script set it. The functions use
# $OUT (the case folder, with models/, goldens/, ctrl/).
#
#   oracle_rollout MODEL STEPS STATE CTRL TOL CASES
#       goldens/<name>.jsonl = rollout.mjs MODEL, recording every $EVERY steps; STATE is
#       "-", "key:K" (start from keyframe K) or a state file; CTRL is "-" or a CSV.
#       Checks that MuJoCo found no contacts (unless CONTACTS=yes) and no non-finite
#       values; appends the case line "MODEL GOLDEN STEPS STATE CTRL TOL" to CASES.
#   oracle_case MODEL STEPS STATE TOL CASES
#       ctrl/<name>.csv = ctrlgen.mjs MODEL, then oracle_rollout with it.
#   case_folder CASES
#       Empties $OUT/{models,goldens,ctrl} and the case list CASES.
#   case_suite NAME
#       Starts the suite tests/conformance/NAME from the repository: cd to ROOT, sets
#       OUT=tests/conformance/NAME and CASES=tests/conformance/NAME_cases.txt, case_folder.
#   integrator_models BASE
#       models/<name>__I.xml for I in (Euler RK4 implicit implicitfast): BASE with
#       integrator="I" added to its <option timestep=...> tag; prints their paths.
#   base_cases STEPS TOL CASES
#       oracle_case (no state) for every integrator model of every $OUT/base/*.xml.
#   derive CORPUS SRC VARIANT WHAT SED-ARGS...
#       models/SRC__VARIANT.xml = sed SED-ARGS on CORPUS/SRC.xml, with a comment saying
#       WHAT was changed; fails if sed changed nothing.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# (SIMLAB_ORACLE, as for tools/oracle_model.mjs, names another oracle folder.)
ORACLE="${SIMLAB_ORACLE:-$(cd "$ROOT/../shared/oracle" && pwd)}"
SHARED_CORPUS="$(cd "$ROOT/../shared/corpus/mujoco" && pwd)"
EVERY="${EVERY:-10}"
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }

oracle_rollout() {
  local model="$1" steps="$2" state="$3" ctrl="$4" tol="$5" cases="$6"
  local golden args
  golden="$OUT/goldens/$(basename "$model" .xml).jsonl"
  args=(--steps "$steps" --every "$EVERY" --out "$golden")
  case "$state" in
    -) ;;
    key:*) args+=(--key "${state#key:}") ;;
    *) args+=(--state "$state") ;;
  esac
  [ "$ctrl" = - ] || args+=(--ctrl "$ctrl")
  echo "rollout $model"
  node "$ORACLE/rollout.mjs" "$model" "${args[@]}"
  [ "${CONTACTS:-no}" = yes ] || ! grep -q '"ncon":[1-9]' "$golden" \
    || { echo "$golden: MuJoCo found contacts" >&2; exit 1; }
  ! grep -qiE 'null|nan|infinity' "$golden" || { echo "$golden: non-finite values" >&2; exit 1; }
  echo "$model $golden $steps $state $ctrl $tol" >> "$cases"
}

oracle_case() {
  local model="$1" steps="$2" state="$3" tol="$4" cases="$5"
  local ctrl
  ctrl="$OUT/ctrl/$(basename "$model" .xml).csv"
  node "$ORACLE/ctrlgen.mjs" "$model" --steps "$steps" --out "$ctrl"
  oracle_rollout "$model" "$steps" "$state" "$ctrl" "$tol" "$cases"
}

case_folder() {
  rm -rf "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
  mkdir -p "$OUT/models" "$OUT/goldens" "$OUT/ctrl"
  : > "$1"
}

case_suite() {
  cd "$ROOT"
  OUT="tests/conformance/$1"
  CASES="tests/conformance/$1_cases.txt"
  case_folder "$CASES"
}

integrator_models() {
  local base="$1" name integrator model
  name="$(basename "$base" .xml)"
  grep -q '<option timestep=' "$base" || { echo "$base: no <option timestep=...>" >&2; exit 1; }
  for integrator in Euler RK4 implicit implicitfast; do
    model="$OUT/models/${name}__$integrator.xml"
    sed "s|<option timestep=|<option integrator=\"$integrator\" timestep=|" "$base" > "$model"
    echo "$model"
  done
}

base_cases() {
  local base model models
  for base in "$OUT"/base/*.xml; do
    # (assigned first: a failure inside a for list's $(...) would not stop the script)
    models="$(integrator_models "$base")" || exit 1
    for model in $models; do
      oracle_case "$model" "$1" - "$2" "$3"
    done
  done
}

derive() {
  local corpus="$1" src="$2" variant="$3" what="$4"; shift 4
  local dst="$OUT/models/${src}__${variant}.xml"
  ! cmp -s <(sed "$@" "$corpus/$src.xml") "$corpus/$src.xml" \
    || { echo "derive $dst: sed changed nothing" >&2; exit 1; }
  sed "$@" "$corpus/$src.xml" |
    sed -e "0,/<mujoco/s|\(<mujoco[^>]*>\)|\1\n  <!-- simlab: derived from the MuJoCo test model $(basename "$corpus")/$src.xml: $what -->|" \
    > "$dst"
}
