# oracle_case.sh — sourced by the golden scripts (tools/make_*_goldens.sh).
#
#   oracle_case MODEL STEPS STATE TOL CASES
#
# Writes ctrl/<name>.csv (ctrlgen.mjs) and goldens/<name>.jsonl (rollout.mjs, every
# $EVERY steps) under $OUT for MODEL, checks that MuJoCo found no contacts and no
# non-finite values, and appends the case line to CASES. STATE is "-", or "key:K" to start
# from keyframe K. Needs $ORACLE, $OUT and $EVERY.
oracle_case() {
  local model="$1" steps="$2" state="$3" tol="$4" cases="$5"
  local name ctrl golden key=()
  name="$(basename "$model" .xml)"
  ctrl="$OUT/ctrl/$name.csv"
  golden="$OUT/goldens/$name.jsonl"
  [ "${state#key:}" != "$state" ] && key=(--key "${state#key:}")
  echo "rollout $model"
  node "$ORACLE/ctrlgen.mjs" "$model" --steps "$steps" --out "$ctrl"
  node "$ORACLE/rollout.mjs" "$model" "${key[@]}" --ctrl "$ctrl" --steps "$steps" \
    --every "$EVERY" --out "$golden"
  ! grep -q '"ncon":[1-9]' "$golden" || { echo "$golden: MuJoCo found contacts" >&2; exit 1; }
  ! grep -qE 'null|NaN|Infinity' "$golden" || { echo "$golden: non-finite values" >&2; exit 1; }
  echo "$model $golden $steps $state $ctrl $tol" >> "$cases"
}
