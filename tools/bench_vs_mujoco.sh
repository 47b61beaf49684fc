#!/usr/bin/env bash
# Steps per second of simlab beside MuJoCo 3.12 (and Debian's 2.2.2) on the same models,
# interleaved in one run on one machine, and the ratio simlab / MuJoCo.
#
#   tools/bench_vs_mujoco.sh [--rounds R] [--only NAME] [--cpu C] [BUILD_DIR]
#
# Both engines run the same workload: MuJoCo's own `testspeed` (built from source by
# ../shared/oracle/native/build.sh into $MUJOCO_NATIVE, default /work/mujoco-native) and
# `simlab bench`, which follows testspeed 3.12 exactly (start keyframe "test", the same
# Ornstein-Uhlenbeck control noise; contacts and rows per step agree). Time is the CPU
# time of each process (user + system, from the kernel), not wall time: the machine is
# shared. Loading a model is taken out by running every command twice, with N steps and
# with N0 = N/10 steps: steps/s = (N - N0) / (cpu(N) - cpu(N0)), each cpu the least of
# the rounds (other work on a shared machine only adds time: a virtual machine's runs of
# one binary vary by up to 40%). The commands of one round run one after the other, both
# engines in turn; --cpu C pins every run to CPU C. (The two virtual CPUs of the machine
# this was written on swap between a fast and a 30% slower state every minute or so:
# the least time of many rounds is each engine's time in the fast state.)
#
# The step counts make each run about a second. Workloads agree step for step (the same
# contacts and rows per step) except where MuJoCo 3.12 changed its colliders: box-box is a
# new SAT collider (the gantry's cube: 8 contacts per step against 3.5.1's 7) and
# mesh-mesh pairs differ slightly (the cubes: 32.6 against 32.0).
#
# Debian's MuJoCo 2.2.2 (`mujoco-testspeed`, package libmujoco-samples) is the third
# column when installed; its control noise is the older process (no relaxation to the
# centre), so its workload differs slightly, and it cannot load 3.x-only models (-).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=9 only="" cpu="" build=$here/build
while [ $# -gt 0 ]; do
  case $1 in
    --rounds) rounds=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --cpu) cpu=$2; shift 2 ;;
    *) build=$1; shift ;;
  esac
done
native=${MUJOCO_NATIVE:-/work/mujoco-native}
testspeed=$native/build/bin/testspeed
if [ ! -x "$testspeed" ]; then
  cat >&2 <<EOF
MuJoCo 3.12's testspeed is missing ($testspeed). Build it from source:
  fetch github:google-deepmind/mujoco and its pinned dependencies (the header of
  $here/../shared/oracle/native/build.sh lists them), then
  bash ../shared/oracle/native/build.sh MIRROR/google-deepmind+mujoco/repo MIRROR $native
EOF
  exit 2
fi
[ -x "$build/simlab" ] || { echo "no $build/simlab: build the project first" >&2; exit 2; }

# Models from MuJoCo's source tree (exported by build.sh into $native/src); the cube with
# multiccd off, as MuJoCo 3.5.1 and simlab default to (3.8 turned it on).
src=$native/src
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$src/model/cube" "$work/cube"
sed -i 's|<option \([^/]*\)/>|<option \1><flag multiccd="disable"/></option>|' "$work/cube/cube_3x3x3.xml"
grep -q 'multiccd="disable"' "$work/cube/cube_3x3x3.xml" || { echo "cube: could not set multiccd" >&2; exit 1; }

# name|model|steps
models="humanoid|$here/tests/conformance/contact/models/humanoid.xml|40000
humanoid-nocontact|$here/tests/models/humanoid_nocontact.xml|100000
gantry-holding|$here/tests/models/bench_gantry_holding.xml|20000
actuator-bench|$here/models/actuator_bench.xml|200000
shadow-hand|$src/mjx/mujoco/mjx/test_data/shadow_hand/scene_right.xml|20000
cube-3x3x3|$work/cube/cube_3x3x3.xml|4000
22-humanoids|$src/model/humanoid/22_humanoids.xml|1000"

old=$(command -v mujoco-testspeed || true)
echo "simlab: $build/simlab ($(git -C "$here" rev-parse --short HEAD))"
echo "MuJoCo: $testspeed ($(basename "$(readlink -f "$native/build/lib/libmujoco.so")"))"
echo "Debian MuJoCo 2.2.2: ${old:-not installed (apt-get install libmujoco-samples)}"
echo "rounds: $rounds, CPU time per process${cpu:+, all runs on CPU $cpu}"
echo

python3 - "$build/simlab" "$testspeed" "$old" "$rounds" "$only" "$cpu" <<PY
import os, resource, statistics, subprocess, sys
simlab, testspeed, old, rounds, only = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
pin = ["taskset", "-c", sys.argv[6]] if sys.argv[6] else []
models = [line.split("|") for line in """$models""".splitlines()]

def cpu(cmd, cwd):
    """CPU seconds of one command (None when it fails)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(pin + cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0 or "rror" in done.stdout:
        return None
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

engines = {
    "simlab": lambda f, n: [simlab, "bench", f, "--steps", str(n)],
    "mujoco": lambda f, n: [testspeed, f, f"--nstep={n}"],
}
if old:
    engines["2.2.2"] = lambda f, n: [old, f, str(n), "1", "0.01"]

print(f"{'model':20s} {'simlab':>10s} {'MuJoCo 3.12':>12s} {'ratio':>6s}   {'2.2.2':>9s} {'ratio':>6s}")
for name, path, steps in models:
    if only and name != only:
        continue
    n = int(steps); n0 = n // 10
    times = {e: {n: [], n0: []} for e in engines}
    for r in range(rounds):
        order = list(engines) if r % 2 == 0 else list(reversed(engines))
        for count in (n, n0):
            for e in order:
                times[e][count].append(cpu(engines[e](path, count), os.path.dirname(path)))
    # steps/s per engine from the least CPU time of the rounds (on a shared machine other
    # work only ever adds time), and the ratio of those.
    def rate(e):
        tn, t0 = times[e][n], times[e][n0]
        if any(t is None for t in tn + t0):
            return None
        dt = min(tn) - min(t0)
        return (n - n0) / dt if dt > 0 else None
    sps = {e: rate(e) for e in engines}
    def ratio_of(e):
        return sps["simlab"] / sps[e] if sps["simlab"] and sps[e] else None
    def fmt(x, w):
        return f"{x:{w}.0f}" if x else f"{'-':>{w}s}"
    ratio = ratio_of("mujoco")
    line = f"{name:20s} {fmt(sps['simlab'], 10)} {fmt(sps['mujoco'], 12)} "
    line += f"{ratio:6.2f}" if ratio else f"{'-':>6s}"
    if old:
        r2 = ratio_of("2.2.2")
        line += f"   {fmt(sps['2.2.2'], 9)} " + (f"{r2:6.2f}" if r2 else f"{'-':>6s}")
    print(line, flush=True)
PY
