# oracle_goldens.sh — sourced by the make_goldens.sh scripts whose reference is the
# oracle (npm MuJoCo, $ORACLE): rolls out each of MODELS ("path steps every tol
# [none]") under ctrlgen.mjs's controls (or none), into $OUT/goldens and $OUT/ctrl, and
# writes the list of cases to $CASES.
make_oracle_goldens() {
  rm -rf "$OUT/goldens" "$OUT/ctrl"
  mkdir -p "$OUT/goldens" "$OUT/ctrl"
  : > "$CASES"
  local line model steps every tol controls name ctrl
  for line in "${MODELS[@]}"; do
    read -r model steps every tol controls <<< "$line"
    name=$(basename "$model" .xml)
    ctrl=-
    if [ "${controls:-ctrlgen}" != none ]; then
      ctrl=$OUT/ctrl/$name.csv
      node "$ORACLE/ctrlgen.mjs" "$model" --steps "$steps" --out "$ctrl"
    fi
    node "$ORACLE/rollout.mjs" "$model" --steps "$steps" --every "$every" \
      $([ "$ctrl" = - ] || echo --ctrl "$ctrl") --out "$OUT/goldens/$name.jsonl"
    echo "$model $OUT/goldens/$name.jsonl $steps - $ctrl $tol" >> "$CASES"
    echo "$name: $(wc -c < "$OUT/goldens/$name.jsonl") bytes"
  done
}
