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
# Requirements: bash, node, and `npm ci` done in ../shared/oracle (or an oracle folder
# with its node_modules in $SIMLAB_ORACLE).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
ORACLE="$(cd "${SIMLAB_ORACLE:-$ROOT/../shared/oracle}" && pwd)"
[ -d "$ORACLE/node_modules/mujoco" ] || { echo "run 'npm ci' in $ORACLE first" >&2; exit 1; }
cd "$ROOT"
OUT=tests/conformance/corpus
CASES=tests/conformance/corpus_cases.txt
MODELS=(
  # 22 humanoids attached in a <replicate>, each with the child's excludes; poses
  # composed through replicate, frame and attach. Equal to MuJoCo to the bit (falling
  # humanoids amplify any rounding difference: this pile parted at step 65 while sine
  # and cosine were glibc's).
  "../shared/corpus/mujoco/model/humanoid/22_humanoids.xml 200 25 1e-9"
  # MuJoCo's humanoid100.xml (copied into mujoco/, with the humanoid it attaches): 100
  # humanoids in a <replicate>, each with the child's excludes.
  # (no controls: 2100 actuators' schedule would be megabytes)
  "tests/conformance/corpus/mujoco/humanoid100.xml 200 50 1e-9 none"
  # The piles of issue 19, each equal to MuJoCo to the bit over 200 steps (copied into
  # mujoco/benchmark, mujoco/perf and mujoco/replicate from MuJoCo's test/benchmark/testdata,
  # test/engine/testdata/{forward,solver}/perf and model/replicate): 27 cubelets in
  # frictional contact (Newton); 200 humanoid bodies on cylinders; two humanoids among 100
  # objects with islands (CG), without them (Newton, sparse factor) and with PGS; 100
  # humanoids (Newton; no controls, as humanoid100); boxes, capsules and cylinders (PGS);
  # replicated stones resting on each other.
  "../shared/corpus/mujoco/model/cube/cube_3x3x3.xml 200 20 1e-9"
  "tests/conformance/corpus/mujoco/benchmark/humanoid200.xml 200 50 1e-9"
  "tests/conformance/corpus/mujoco/benchmark/2humanoid100.xml 200 50 1e-9"
  "tests/conformance/corpus/mujoco/benchmark/2humanoid100_chol.xml 200 50 1e-9"
  "tests/conformance/corpus/mujoco/perf/2humanoid100_PGS.xml 200 50 1e-9"
  "tests/conformance/corpus/mujoco/benchmark/100_humanoids_chol.xml 200 100 1e-9 none"
  "tests/conformance/corpus/mujoco/perf/mixed.xml 200 20 1e-9 none"
  "tests/conformance/corpus/mujoco/replicate/stonehenge.xml 200 20 1e-9 none"
  # Sleeping (copied into mujoco/sleep/ from MuJoCo's test/engine/testdata/sleep and
  # model/sleep): trees falling asleep in islands, waking on contact (also explicit
  # pairs), tendon limits, equalities and mocap motion, sleep="init", sleeping sensors,
  # static and world bodies (no actuators: no controls). (The domino row parted from
  # MuJoCo at step 205 while sine and cosine were glibc's; it is now equal to the bit.)
  "tests/conformance/corpus/mujoco/sleep/sleep_contact.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_contactpair.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_equality.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_init.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_init_island.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_mocap.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_sensor.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_static.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_scene.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_smooth.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_tendon.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_tendon2.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_perf_static.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_perf_world.xml 400 10 1e-9 none"
  "tests/conformance/corpus/mujoco/sleep/sleep_dominos.xml 400 10 1e-9 none"
  # multiccd (copied into mujoco/multiccd/ from MuJoCo's test/engine/testdata/
  # collision_convex): the polygon contacts of boxes and box meshes, face to face and edge
  # to face. Equal to MuJoCo to the bit (the stacks parted at steps 104-173 while the
  # polygons were listed in another order: the first of two equal edges wins).
  "tests/conformance/corpus/mujoco/multiccd/multiccd_box_boxmesh.xml 300 10 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_dice.xml 300 50 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_dice_boxmesh.xml 300 50 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_edge_edge.xml 300 10 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_long_box.xml 300 10 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_multiple_objects.xml 300 10 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_perf_box.xml 300 50 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_perf_boxmesh.xml 300 50 1e-9 none"
  "tests/conformance/corpus/mujoco/multiccd/multiccd_stacked_boxes.xml 300 10 1e-9 none"
  # sdf geoms on meshes (signed distance octrees; mjc_SDF): MuJoCo's two test models with
  # one (copied into mujoco/sdf/), and simlab's own scenes in sdf/: primitives, sdf
  # geoms and a mesh geom dropped on sdf geoms and the floor. Equal to MuJoCo to the bit.
  "tests/conformance/corpus/mujoco/sdf/sdf_testdata_model.xml 200 20 1e-9"
  "tests/conformance/corpus/mujoco/sdf/sdf_solver_model.xml 200 20 1e-9"
  "tests/conformance/corpus/sdf/sdf_drops.xml 400 20 1e-9 none"
  "tests/conformance/corpus/sdf/sdf_pile.xml 600 30 1e-9 none"
  "tests/conformance/corpus/sdf/sdf_meshsdf.xml 300 30 1e-9 none"
)
source tests/conformance/oracle_goldens.sh
make_oracle_goldens
