#!/usr/bin/env bash
# make_goldens.sh — MuJoCo's flex examples (../shared/corpus/mujoco/model/flex), rolled
# out by the oracle (MuJoCo 3.5.1, ../shared/oracle) under ctrlgen.mjs's controls where
# they have actuators: the conformance of deformables (issue 20), case by case as each
# part of the flex pipeline lands.
#
# Usage:  tests/conformance/flex/make_goldens.sh      (from any working directory)
#
#   Each line of MODELS: a model path, the steps, how often to record, the tolerance,
#   and "none" for no controls (else ctrlgen's). Writes tests/conformance/flex_cases.txt.
# Requirements: bash, node, and `npm ci` done in ../shared/oracle (or an oracle folder
# with its node_modules in $SIMLAB_ORACLE).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
ORACLE="$(cd "${SIMLAB_ORACLE:-$ROOT/../shared/oracle}" && pwd)"
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }
cd "$ROOT"
OUT=tests/conformance/flex
CASES=tests/conformance/flex_cases.txt
FLEX=../shared/corpus/mujoco/model/flex
MODELS=(
  # a 9 x 19 cloth flapping in the wind from a pinned corner: edge equality, edge
  # damping, fluid forces on the vertex bodies, CG (no contacts)
  "$FLEX/flag.xml 200 50 1e-9 none"
  # flexes interpolated from 2^3 and 3^3 nodes (trilinear, quadratic), with the
  # stiffness of the nodes' box; a trilinear sphere landing on the floor
  "$FLEX/trilinear.xml 200 20 1e-9 none"
  "$FLEX/quadratic.xml 200 20 1e-9 none"
  "$FLEX/sphere_trilinear.xml 300 50 1e-9 none"
  # 3D soft bodies landing on the floor (first contacts at steps 212-339): elasticity of
  # the tetrahedra and its damping, a box of radial sliders, full and radial spheres
  "$FLEX/floppy.xml 400 100 1e-9 none"
  "$FLEX/jelly.xml 400 100 1e-9 none"
  "$FLEX/softbox.xml 400 100 1e-9 none"
  "$FLEX/sphere_full.xml 400 100 1e-9 none"
  "$FLEX/sphere_radial.xml 200 50 1e-9 none"
  # 2D sheets: bending (flex_bending), stretching (triangle flex_stiffness), draped
  # cloths colliding with themselves (passive contacts), a cloth pinched by a gripper
  "$FLEX/pancake.xml 400 100 1e-9 none"
  "$FLEX/plate.xml 300 100 1e-9 none"
  "$FLEX/trampoline.xml 600 200 1e-9 none"
  "$FLEX/drape.xml 200 100 1e-9 none"
  "$FLEX/pinch.xml 200 50 1e-9"
  # a cable on a pulley (contacts from step 3; the cable's points 1 ulp from MuJoCo's
  # before musl's sines: 1e-6) and a press squeezing two blocks
  "$FLEX/pulley.xml 200 50 1e-6"
  "$FLEX/press.xml 200 50 1e-9"
  # two trilinear fingers on a gripper under implicitfast: the interpolated flexes'
  # stiffness in the implicit step (a dense system on the nodes' dofs). simlab equals
  # native MuJoCo at the oracle's commit to the bit over the 200 steps; the WebAssembly
  # oracle differs from native by 1e-19 from step 1, grown to 3e-9 by its 294 contacts
  "$FLEX/gripper_trilinear.xml 200 20 1e-8"
  # the mesh flexcomp bunny (trilinear) landing on the floor
  "$FLEX/bunny.xml 300 100 1e-9 none"
  # a cable (1D flex) with edge springs swinging from a pin, its potential energy (edge
  # springs included) read by an e_potential sensor
  "tests/conformance/flex/models/cable_energy.xml 300 50 1e-9 none"
  # a cloth, a soft block and a cable dropped onto a bumpy height field (first contacts
  # at steps 77-88, up to 311 contacts): the field's prisms under each flex element
  # (mjc_HFieldElem)
  "tests/conformance/flex/models/hfield_cloth.xml 400 100 1e-9 none"
  "tests/conformance/flex/models/hfield_softbody.xml 400 100 1e-9 none"
  "tests/conformance/flex/models/hfield_cable.xml 400 50 1e-9 none"
  # MuJoCo's own engine test models with flexes and skins (test/engine/testdata at the
  # oracle's commit, copied under testdata/): a humanoid in a hammock of 178 equalities and
  # tendons, a skinned box grid, a ray test's swinging flex
  "tests/conformance/flex/testdata/hammock/hammock.xml 200 50 1e-9"
  "tests/conformance/flex/testdata/skingroup.xml 200 50 1e-9 none"
  "tests/conformance/flex/testdata/ray/flex.xml 200 50 1e-9 none"
  # a poncho on a mannequin kept by the vertex equality (flexvert) before MuJoCo's own
  # run goes unstable (step 10)
  "$FLEX/poncho.xml 9 3 1e-9 none"
)
source tests/conformance/oracle_goldens.sh
make_oracle_goldens
