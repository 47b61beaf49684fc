#!/usr/bin/env bash
# make_goldens.sh — flex features newer than the npm oracle (MuJoCo 3.5.1): MuJoCo 3.12's
# models rolled out by native MuJoCo 3.12 built from source ($MUJOCO_NATIVE, default
# /work/mujoco-native; its `rollout` has rollout.mjs's arguments and format), with
# musl's sines and cosines preloaded ($MUSL_TRIG, default
# /work/mujoco-oracle-era3/musl_trig.so, when it exists), as simlab computes them.
#
# Usage:  tests/conformance/flex_native/make_goldens.sh      (from any working directory)
#
#   Each line of MODELS: a model path (from the repository's root), the steps, how often
#   to record, the tolerance, and optionally a control file (CSV, from the root; none:
#   zero controls). Writes goldens/<name>.jsonl and tests/conformance/flex_native_cases.txt.
#   These models follow MuJoCo 3.12 (Model::release): flex contacts thinned per collision
#   pair, the primal solvers' iteration and the convex collider (GJK, EPA) as 3.12 has
#   them; models/<name>_nocontact.xml are the same models without contacts.
# Requirements: bash, python3, and the native build.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
NATIVE="${MUJOCO_NATIVE:-/work/mujoco-native}"
ROLLOUT="$NATIVE/rollout"
MUSL_TRIG="${MUSL_TRIG:-/work/mujoco-oracle-era3/musl_trig.so}"
[ -x "$ROLLOUT" ] || { echo "no $ROLLOUT: build native MuJoCo with ../shared/oracle/native/build.sh" >&2; exit 1; }
PRELOAD=""
[ -f "$MUSL_TRIG" ] && PRELOAD="$MUSL_TRIG"
cd "$ROOT"
OUT=tests/conformance/flex_native
CASES=tests/conformance/flex_native_cases.txt
FLEX=../shared/corpus/mujoco/model/flex
MODELS=(
  # cellcount: trilinear bunnies on a 3 x 3 x 3 lattice of cells (nodes only in empty
  # cells pinned), a volume with elasticity and a shell (interior nodes pinned, bending
  # between faces, strain equality), falling on the floor from step 42 (92 contacts
  # thinned to 50; the volume bunny goes unstable at t = 0.248, in MuJoCo too), and
  # without contacts
  "$FLEX/bunny_multicell.xml 200 10 1e-9"
  "$FLEX/bunny_shell.xml 200 10 1e-9"
  "$OUT/models/bunny_multicell_nocontact.xml 120 10 1e-9"
  "$OUT/models/bunny_shell_nocontact.xml 200 20 1e-9"
  # a solid and a hollow (shell) 6 x 1 x 6-cell grid kept by strain equality, falling on
  # the floor from step 55 (CG, elliptic cones), and without contacts
  "$FLEX/hollow_vs_solid.xml 200 40 1e-9"
  "$OUT/models/hollow_vs_solid_nocontact.xml 200 50 1e-9"
  # dof="2d": a fin-ray gripper's fingers of vertex bodies with two slide joints each
  # (edge equality and damping) under smooth controls (ctrl/gripper_2d.csv, by hand): the
  # free cylinder lands at step 81 (3.12's implicitfast solves a free body on its own), the
  # fingers grasp it from step 94 (elliptic cones, sparse Newton), the two fingers'
  # triangles touch from step 177 (3.12's GJK and EPA: stops at the tolerance, faces turned
  # outward), and without contacts
  "$FLEX/gripper_2d.xml 300 15 1e-9 $OUT/ctrl/gripper_2d.csv"
  "$OUT/models/gripper_2d_nocontact.xml 200 10 1e-9 $OUT/ctrl/gripper_2d.csv"
  # strain equality: trilinear boxes pinned at one end (a flexstrain per cell, a row per
  # stiff mode) and a free box landing on them from step 155 (4 pairs thinned to 50
  # contacts each), without contacts, the same with quadratic boxes (75 modes a cell, a
  # sparse Jacobian), explicit <flexstrain> elements before a connect read by a force
  # sensor (MuJoCo's cfrc_ext pass skips the connect; free-falling boxes whose strain
  # forces are the solver's noise: 1e-7), and on pinned boxes of both orders (rank-deficient
  # cells: 3.12's Cholesky clears a deficient pivot's column)
  "$FLEX/strain.xml 200 10 1e-9"
  "$OUT/models/strain_nocontact.xml 400 20 1e-9"
  "$OUT/models/strain_quadratic_nocontact.xml 300 20 1e-9"
  "$OUT/models/strain_sensor.xml 100 10 1e-7"
  "$OUT/models/strain_explicit_pinned.xml 300 30 1e-9"
  "$OUT/models/strain_explicit_pinned_quadratic.xml 300 30 1e-9"
  # bending with static pins (3.12 only), forces in the vertex bodies' tilted frames
  "$OUT/models/pinned_bend.xml 300 30 1e-9"
  # sleeping flexes (MuJoCo 3.12's sleep tests): a three-vertex cable held by its edge
  # equality falls asleep with its trees as one island, and wakes by a contact with an
  # awake body (a ball falling on it); an unconstrained one never sleeps; a sleeping
  # flex meets neither the floor nor a static or mocap body (3.12's thinning of flex
  # contacts removes none of these cables' contacts)
  "$OUT/models/sleep_flex_nocnstr.xml 300 5 1e-9"
  "$OUT/models/sleep_flex_state.xml 300 5 1e-9"
  "$OUT/models/sleep_flex_edge.xml 300 5 1e-9"
  "$OUT/models/sleep_flex_mocap.xml 300 5 1e-9"
  "$OUT/models/sleep_flex_static.xml 300 5 1e-9"
  "$OUT/models/sleep_flex_contact.xml 300 5 1e-9"
  # flexes that never sleep, with sleeping bodies: a box asleep on a flex pinned whole
  # (no contacts once it sleeps), and a box asleep on the floor woken by a cable falling
  # on it (MuJoCo 3.5.1 refuses to step both; 3.12's thinning removes none of their flex
  # contacts either)
  "$OUT/models/sleep_box_on_pinned_flex.xml 300 5 1e-9"
  "$OUT/models/sleep_cable_on_box.xml 400 5 1e-9"
)

rm -rf "$OUT/goldens"
mkdir -p "$OUT/goldens"
: > "$CASES"
for line in "${MODELS[@]}"; do
  read -r model steps every tol ctrl <<< "$line"
  name=$(basename "$model" .xml)
  golden="$OUT/goldens/$name.jsonl"
  args=(--steps "$steps" --every "$every" --out "$golden")
  [ -z "${ctrl:-}" ] || args+=(--ctrl "$ctrl")
  LD_PRELOAD="$PRELOAD" "$ROLLOUT" "$model" "${args[@]}"
  ! grep -qiE 'null|nan|infinity' "$golden" || { echo "$golden: non-finite values" >&2; exit 1; }
  echo "$model $golden $steps - ${ctrl:--} $tol" >> "$CASES"
  echo "$name: $(wc -c < "$golden") bytes"
done
