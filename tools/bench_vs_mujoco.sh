#!/usr/bin/env bash
# Steps per second of simlab beside MuJoCo 3.12 (and Debian's 2.2.2) on the same models,
# interleaved in one run on one machine, and the ratio simlab / MuJoCo.
#
#   tools/bench_vs_mujoco.sh [--rounds R] [--only NAME] [--cpu C] [--no-profiler] [BUILD_DIR]
#
# Both engines run the same workload: MuJoCo's own `testspeed` (built from source by
# ../shared/oracle/native/build.sh into $MUJOCO_NATIVE, default /work/mujoco-native) and
# `simlab bench`, which follows testspeed 3.12 exactly (start keyframe "test", the same
# Ornstein-Uhlenbeck control noise; contacts and rows per step agree). Time is the CPU
# time of each process (user + system, from the kernel): other work on the machine does
# not count. Loading the model is taken out by running every command twice, with N and
# with N0 = N/10 steps, one after the other: steps/s = (N - N0) / (cpu(N) - cpu(N0)).
#
# A round runs both engines so, one after the other, pinned to the same CPU; rounds
# alternate the CPU and the order. Each engine's speed is its best round (a shared
# machine only ever slows a run: the two virtual CPUs of the machine this was written on
# swap between a fast and a 30% slower state every minute or so), and the ratio is
# simlab's best over MuJoCo's best; the median of the rounds' own ratios is printed
# beside it.
#
# The step counts make each run about a second. Workloads agree step for step except
# where MuJoCo 3.12 changed what it simulates and simlab follows 3.5.1 (the oracle's):
# box-box is a new SAT collider (the gantry's cube: 8 contacts per step against 3.5.1's
# 7), multiccd is on by default and mesh-mesh pairs differ (replicate-bowl: 72.3 against
# 78.7), and flex contacts are thinned to 50 per collision pair (flex-flag: 30.2 against
# 57.6), and the primal solvers stop earlier: a warm start whose duality gap is already
# below the tolerance skips the Hessian and the iterations, and CG uses Hager-Zhang's
# direction (replicate-bowl: 1.07 Newton iterations per step against 0.28). So the table
# gives both engines' contacts, constraint rows and solver iterations per step (from the
# first round) and marks with * a row whose rows differ by more than 2% or whose
# iterations differ by more than 5% and 0.1 a step: its ratio compares different work.
#
# Both engines time their pipeline stages by default (testspeed installs its profiler
# clock, mjcb_time; `simlab bench` sets Data::timer_clock): some 28 clock reads a step,
# about a microsecond, the same work in both and half of a small model's step. With
# --no-profiler neither does: simlab bench --no-profiler, and testspeed rebuilt here from
# MuJoCo's own testspeed.cc with the one line that installs mjcb_time made conditional
# (clang++ and the native build's headers and library; the engine is the same library).
#
# Debian's MuJoCo 2.2.2 (`mujoco-testspeed`, package libmujoco-samples) is the third
# column when installed; its control noise is the older process (no relaxation to the
# centre), so its workload differs slightly, and it cannot load 3.x-only models (-).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=9 only="" cpu="" profiler=1 build=$here/build
while [ $# -gt 0 ]; do
  case $1 in
    --rounds) rounds=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --cpu) cpu=$2; shift 2 ;;
    --no-profiler) profiler=0; shift ;;
    *) build=$(cd "$1" && pwd); shift ;;  # (absolute: the runs start in each model's folder)
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
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ $profiler = 0 ]; then
  # MuJoCo's testspeed without its profiler clock (the only change), built as build.sh does.
  sed 's/^  mjcb_time = gettm;$/  if (!getenv("TESTSPEED_NO_PROFILER")) mjcb_time = gettm;/' \
    "$native/src/sample/testspeed.cc" > "$work/testspeed.cc"
  grep -q TESTSPEED_NO_PROFILER "$work/testspeed.cc" || { echo "testspeed.cc: mjcb_time line not found" >&2; exit 1; }
  clang++ -DmjUSEPLATFORMSIMD -I"$native/src/include" -O3 -DNDEBUG -mavx -std=c++20 \
    "$work/testspeed.cc" -o "$work/testspeed" -L"$native/build/lib" \
    -Wl,-rpath,"$native/build/lib" -lmujoco -lpthread
  testspeed=$work/testspeed
  export TESTSPEED_NO_PROFILER=1
fi
[ -x "$build/simlab" ] || { echo "no $build/simlab: build the project first" >&2; exit 2; }

# Models from MuJoCo's source tree (exported by build.sh into $native/src); the cube with
# multiccd off, as MuJoCo 3.5.1 and simlab default to (3.8 turned it on).
src=$native/src
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
22-humanoids|$src/model/humanoid/22_humanoids.xml|1000
cards|$src/model/cards/cards.xml|2000
replicate-bowl|$src/model/replicate/bowl.xml|10000
replicate-leaves|$src/model/replicate/leaves.xml|500
flex-flag|$src/model/flex/flag.xml|2000
flex-softbox|$src/model/flex/softbox.xml|2000
flex-trampoline|$src/model/flex/trampoline.xml|2000"

old=$(command -v mujoco-testspeed || true)
[ $profiler = 1 ] || old=""  # (2.2.2 keeps its profiler)
echo "simlab: $build/simlab ($(git -C "$here" rev-parse --short HEAD))"
echo "MuJoCo: $testspeed ($(basename "$(readlink -f "$native/build/lib/libmujoco.so")"))"
echo "Debian MuJoCo 2.2.2: ${old:-not installed (apt-get install libmujoco-samples)}"
echo "rounds: $rounds, CPU time per process, best round of each engine${cpu:+, all runs on CPU $cpu}"
[ $profiler = 1 ] || echo "profilers off in both engines (testspeed rebuilt without mjcb_time: $testspeed)"
echo

python3 - "$build/simlab" "$testspeed" "$old" "$rounds" "$only" "$cpu" "$profiler" <<PY
import os, resource, statistics, subprocess, sys
simlab, testspeed, old, rounds, only, cpu, profiler = sys.argv[1:8]
rounds = int(rounds)
ncpu = os.cpu_count() or 1
models = [line.split("|") for line in """$models""".splitlines()]

workload = {}  # (engine, model) -> (contacts, rows, iterations) per step, first long run

def per_step(output, *labels):
    """The number after the first of labels that starts a line of a bench or testspeed
    report (None if none does; a 0 stays 0)."""
    for label in labels:
        for line in output.splitlines():
            if line.strip().startswith(label):
                return float(line.split(":")[1].split()[0])
    return None

def cpu_seconds(cmd, cwd, pin, key=None):
    """CPU seconds of one command (None when it fails); records its workload under key."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(["taskset", "-c", str(pin)] + cmd, cwd=cwd, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0 or "Steps per second" not in done.stdout:
        return None
    if key and key not in workload:
        out = done.stdout
        workload[key] = (per_step(out, "Contacts per step", "Contacts / step"),
                         per_step(out, "Constraints per step", "Constraints / step"),
                         per_step(out, "Newton iters / step", "CG iters / step", "PGS iters / step"))
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

def speed(engine, path, n, pin):
    """Steps per second of N - N0 steps from two runs (None when either fails)."""
    n0 = n // 10
    long = cpu_seconds(engines[engine](path, n), os.path.dirname(path), pin, (engine, path))
    short = cpu_seconds(engines[engine](path, n0), os.path.dirname(path), pin)
    if long is None or short is None or long <= short:
        return None
    return (n - n0) / (long - short)

def workload_columns(path):
    """Contacts, rows and solver iterations per step of both engines, * when the rows
    differ by over 2% or the iterations by over 5% and 0.1 a step (a model with a few
    joint-limit rows may take 0.15 iterations a step against 0.09: no work to speak of)."""
    (c1, r1, i1), (c2, r2, i2) = (workload.get((e, path), (None,) * 3) for e in ("simlab", "mujoco"))
    if None in (c1, r1, c2, r2, i1, i2):
        return f"{'-':>13s} {'-':>13s} {'-':>11s}  "
    differs = abs(r1 - r2) > 0.02 * max(r1, r2, 1) or abs(i1 - i2) > max(0.05 * max(i1, i2), 0.1)
    return f"{c1:6.1f}/{c2:<6.1f} {r1:6.0f}/{r2:<6.0f} {i1:5.2f}/{i2:<5.2f} {'*' if differs else ' '}"

engines = {
    "simlab": lambda f, n: [simlab, "bench", f, "--steps", str(n)]
                           + ([] if profiler == "1" else ["--no-profiler"]),
    "mujoco": lambda f, n: [testspeed, f, f"--nstep={n}"],
}
if old:
    engines["2.2.2"] = lambda f, n: [old, f, str(n), "1", "0.01"]

def fmt(x, w, digits=0):
    return f"{x:{w}.{digits}f}" if x else f"{'-':>{w}s}"

print(f"{'model':20s} {'simlab':>9s} {'MuJoCo 3.12':>12s} {'ratio':>6s} {'(median)':>9s}"
      + f"  {'contacts':>13s} {'rows':>13s} {'iterations':>11s}  " + (f"   {'2.2.2':>9s} {'ratio':>6s}" if old else ""))
for name, path, steps in models:
    if only and name != only:
        continue
    n = int(steps)
    runs = {e: [] for e in engines}
    for r in range(rounds):
        pin = int(cpu) if cpu else r % ncpu
        order = list(engines) if (r // ncpu) % 2 == 0 else list(reversed(engines))
        for e in order:
            runs[e].append(speed(e, path, n, pin))
    best = {e: max([x for x in runs[e] if x] or [0]) for e in engines}
    def ratios(e):
        rs = [a / b for a, b in zip(runs["simlab"], runs[e]) if a and b]
        return (best["simlab"] / best[e] if best["simlab"] and best[e] else None,
                statistics.median(rs) if rs else None)
    ratio, median = ratios("mujoco")
    line = (f"{name:20s} {fmt(best['simlab'], 9)} {fmt(best['mujoco'], 12)} {fmt(ratio, 6, 2)} "
            f"{fmt(median, 9, 2)}  {workload_columns(path)}")
    if old:
        r2, _ = ratios("2.2.2")
        line += f"   {fmt(best['2.2.2'], 9)} {fmt(r2, 6, 2)}"
    print(line, flush=True)
print("\ncontacts, rows, solver iterations: per step, simlab/MuJoCo 3.12; * the rows differ by over 2%"
      "\nor the iterations by over 5% and 0.1 (different work)")
PY
