#!/usr/bin/env bash
# make_goldens.sh — regenerate the conformance test inputs and golden rollouts.
#
# Usage:  tools/make_goldens.sh          (from any working directory)
#
# What it does (idempotent: everything it writes is deleted and rebuilt):
#   1. tests/models/humanoid_nocontact.xml is derived with sed from the corpus file
#      ../shared/corpus/mujoco/model/humanoid/humanoid.xml (option line replaced by one with
#      contacts disabled). If the corpus is missing, the committed copy is kept.
#   2. For every base model in tests/models (list BASES below) and every integrator
#      (Euler, RK4, implicit, implicitfast) it writes the variant
#          tests/conformance/models/<name>__<integrator>.xml
#      = the base model with integrator="<integrator>" added to its single <option> tag.
#   3. It runs the MuJoCo reference (../shared/oracle/rollout.mjs, the official wasm build)
#      on each variant:
#          rollout.mjs VARIANT.xml --steps N --every 10 [--state tests/models/<name>.state.json]
#      writing tests/conformance/goldens/<name>__<integrator>.jsonl
#      (N = 500 for the small models, 200 for the humanoid; format: ../shared/oracle/FORMAT.md).
#   4. It writes tests/conformance/cases.txt, one line per case, paths relative to repo root:
#          <variant xml> <golden jsonl> <steps> <state json or ->
#      A C++ test runs `simlab rollout` with the same arguments (--every 10) and compares.
#   5. It checks every golden: no NaN/null, and the final qvel is not all zero.
#
# Requirements: bash, GNU sed, node, and `npm ci` done in ../shared/oracle.
set -euo pipefail

SCRIPT_DIR="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$SCRIPT_DIR/.." && pwd)"
ORACLE="$(cd "$SCRIPT_DIR/../../shared/oracle" && pwd)"
CORPUS_HUMANOID="$SCRIPT_DIR/../../shared/corpus/mujoco/model/humanoid/humanoid.xml"

BASES=(pendulum double_pendulum slide_hinge_chain ball_joint free_tumble free_fall humanoid_nocontact)
INTEGRATORS=(Euler RK4 implicit implicitfast)
EVERY=10

[ -f "$ORACLE/rollout.mjs" ] || { echo "missing $ORACLE/rollout.mjs" >&2; exit 1; }
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }

cd "$ROOT"
MODELS=tests/models
OUTDIR=tests/conformance

# --- 1. humanoid without contacts -------------------------------------------------------
HUM="$MODELS/humanoid_nocontact.xml"
if [ -f "$CORPUS_HUMANOID" ]; then
  grep -q '^  <option timestep="0.005"/>$' "$CORPUS_HUMANOID" \
    || { echo "corpus humanoid.xml: expected option line not found" >&2; exit 1; }
  sed -e 's|^  <option timestep="0.005"/>$|  <option timestep="0.005"><flag contact="disable"/></option>|' \
      -e '0,/-->/s|-->|-->\n<!-- simlab: derived from the MuJoCo corpus file model/humanoid/humanoid.xml with contacts\n     disabled (option line changed by tools/make_goldens.sh); everything else unchanged. -->|' \
      "$CORPUS_HUMANOID" > "$HUM.tmp"
  mv "$HUM.tmp" "$HUM"
else
  echo "warning: $CORPUS_HUMANOID not found, keeping committed $HUM" >&2
fi

# --- 2-4. variants, goldens, case list ---------------------------------------------------
rm -rf "$OUTDIR/models" "$OUTDIR/goldens"
mkdir -p "$OUTDIR/models" "$OUTDIR/goldens"
CASES="$OUTDIR/cases.txt"
: > "$CASES.tmp"

for name in "${BASES[@]}"; do
  base="$MODELS/$name.xml"
  [ -f "$base" ] || { echo "missing base model $base" >&2; exit 1; }
  # exactly one <option ...> start tag (</option> is not counted)
  n_opt=$(grep -o '<option[ />]' "$base" | wc -l)
  [ "$n_opt" -eq 1 ] || { echo "$base: expected exactly one <option tag, found $n_opt" >&2; exit 1; }
  grep -q 'integrator=' "$base" && { echo "$base: must not set integrator itself" >&2; exit 1; }

  if [ "$name" = humanoid_nocontact ]; then steps=200; else steps=500; fi
  state="$MODELS/$name.state.json"
  state_args=()
  if [ -f "$state" ]; then state_args=(--state "$state"); else state="-"; fi

  for integ in "${INTEGRATORS[@]}"; do
    variant="$OUTDIR/models/${name}__${integ}.xml"
    golden="$OUTDIR/goldens/${name}__${integ}.jsonl"
    sed -E "s/<option([ />])/<option integrator=\"$integ\"\1/" "$base" > "$variant"
    grep -q "<option integrator=\"$integ\"" "$variant" || { echo "sed failed on $variant" >&2; exit 1; }
    echo "rollout $variant (${steps} steps)"
    node "$ORACLE/rollout.mjs" "$variant" --steps "$steps" --every "$EVERY" \
      "${state_args[@]}" --out "$golden"
    echo "$variant $golden $steps $state" >> "$CASES.tmp"
  done
done
mv "$CASES.tmp" "$CASES"

# --- 5. sanity checks ----------------------------------------------------------------------
node - "$CASES" <<'EOF'
const fs = require('fs');
let bad = 0;
for (const line of fs.readFileSync(process.argv[2], 'utf8').split('\n').filter(Boolean)) {
  const golden = line.split(' ')[1];
  const text = fs.readFileSync(golden, 'utf8');
  const rows = text.split('\n').filter(Boolean).map((l) => JSON.parse(l));
  const last = rows[rows.length - 1];
  const problems = [];
  if (/null|NaN|Infinity/.test(text)) problems.push('non-finite values');
  if (!last.qvel.some((v) => v !== 0)) problems.push('final qvel is all zero');
  if (problems.length) { bad++; console.error(`${golden}: ${problems.join(', ')}`); }
}
if (bad) process.exit(1);
EOF
echo "done: $(wc -l < "$CASES") cases, goldens $(du -sh "$OUTDIR/goldens" | cut -f1)"
