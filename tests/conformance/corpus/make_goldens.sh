#!/usr/bin/env bash
# make_goldens.sh — MuJoCo's own models from ../shared/corpus, rolled out as they are by
# the oracle (MuJoCo 3.5.1, ../shared/oracle) under ctrlgen.mjs's controls: the standing
# conformance of the models issue 19 names that the corpus holds (composition to the
# bit, attached contact sections...). The models stay in ../shared/corpus (CI has it
# beside the repository), or, for models the corpus lacks, in mujoco/ (copies from
# MuJoCo's repository, named in their first comment); controls and goldens are written
# here.
#
# Usage:  tests/conformance/corpus/make_goldens.sh      (from any working directory)
#
#   Each line of MODELS below: a model path, the steps, how often to record, the
#   tolerance, and "none" for no controls (else ctrlgen's). ctrl/<name>.csv = ctrlgen.mjs MODEL --steps N; goldens/<name>.jsonl =
#   rollout.mjs MODEL --steps N --every E --ctrl CTRL. Writes
#   tests/conformance/corpus_cases.txt.
# Requirements: bash, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
ORACLE="$(cd "$ROOT/../shared/oracle" && pwd)"
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }
cd "$ROOT"
OUT=tests/conformance/corpus
CASES=tests/conformance/corpus_cases.txt
MODELS=(
  # 22 humanoids attached in a <replicate>, each with the child's excludes; poses
  # composed through replicate, frame and attach. (Under these controls the falling
  # humanoids amplify rounding: 1e-12 apart at step 65, 3e-3 at step 200.)
  "../shared/corpus/mujoco/model/humanoid/22_humanoids.xml 100 25 1e-6"
  # MuJoCo's humanoid100.xml (copied into mujoco/, with the humanoid it attaches): 100
  # humanoids in a <replicate>, each with the child's excludes.
  # (no controls: 2100 actuators' schedule would be megabytes)
  "tests/conformance/corpus/mujoco/humanoid100.xml 100 50 1e-6 none"
)
rm -rf "$OUT/goldens" "$OUT/ctrl"
mkdir -p "$OUT/goldens" "$OUT/ctrl"
: > "$CASES"
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
