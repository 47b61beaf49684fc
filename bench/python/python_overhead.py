"""The cost of stepping from Python, measured against a C++ loop of simlab::Step.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/python_overhead.py [--rounds 15]

Workload: MuJoCo's humanoid (model/humanoid/humanoid.xml, with its contacts) from
keyframe 0, STEPS steps per round (it falls and lies on the floor). Four ways, interleaved
round by round so that the machine's load hits them alike, each timed in thread CPU time:

  cpp     simlab._benchmark_step_loop: a plain C++ loop of simlab::Step inside the module,
          so the very machine code mj_step runs (the reference of the two ratios below)
  nstep   mj_step(m, d, nstep=STEPS): one call from Python
  loop    for _ in range(STEPS): mj_step(m, d): one call per step
  binary  build/simlab_step_loop: the same C++ loop in its own executable, for context
          only: two binaries of the same source differ by several percent either way
          (code placement), more than the 3% the criterion is about

Prints the median per-step cost of each, nstep's overhead in percent of cpp, the loop's
in microseconds per call, and checks that all of them end in the same state. Then the
rollout module's throughput with 1 and 2 threads (wall time: threads run in parallel).
"""
import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import simlab
import simlab.rollout

ROOT = Path(__file__).resolve().parents[2]
HUMANOID = ROOT.parent / "shared" / "corpus" / "mujoco" / "model" / "humanoid" / "humanoid.xml"


def cpp_round(binary, steps):
    out = subprocess.run([str(binary), str(HUMANOID), str(steps), "1"], capture_output=True,
                         text=True, check=True).stdout.split()
    return float(out[0]), float(out[1])


def python_round(model, data, steps, way):
    simlab.mj_resetDataKeyframe(model, data, 0)
    if way == "cpp":
        return simlab._simlab._benchmark_step_loop(model, data, steps), data.qpos[2]
    begin = time.thread_time()
    if way == "loop":
        for _ in range(steps):
            simlab.mj_step(model, data)
    else:
        simlab.mj_step(model, data, nstep=steps)
    return time.thread_time() - begin, data.qpos[2]


def rollout_rate(model, nthread, nbatch, nstep):
    """Steps per second (wall time) of nbatch rollouts of nstep steps on nthread threads."""
    data = [simlab.MjData(model) for _ in range(max(nthread, 1))]
    full = int(simlab.mjtState.mjSTATE_FULLPHYSICS)
    state0 = np.zeros((nbatch, simlab.mj_stateSize(model, full)))
    for b in range(nbatch):
        simlab.mj_resetDataKeyframe(model, data[0], 0)
        data[0].qvel[:] = 0.01 * b
        simlab.mj_getState(model, data[0], state0[b], full)
    begin = time.perf_counter()
    state, _ = simlab.rollout.rollout(model, data, state0, np.zeros((1, nstep, model.nu)),
                                      nthread=nthread)
    return nbatch * nstep / (time.perf_counter() - begin), state


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--binary", default=str(ROOT / "build" / "simlab_step_loop"))
    args = parser.parse_args()
    model = simlab.MjModel.from_xml_path(str(HUMANOID))
    data = simlab.MjData(model)

    # Interleaved rounds, thread CPU seconds per step.
    times = {"cpp": [], "nstep": [], "loop": [], "binary": []}
    finals = set()
    for _ in range(args.rounds):
        for name in times:
            if name == "binary":
                seconds, final = cpp_round(args.binary, args.steps)
            else:
                seconds, final = python_round(model, data, args.steps, name)
            times[name].append(seconds / args.steps)
            finals.add(final)
    median = {name: statistics.median(t) for name, t in times.items()}
    for name, value in median.items():
        print(f"{name:6s} {1e6 * value:8.3f} us/step (median of {args.rounds}; "
              f"min {1e6 * min(times[name]):.3f})")
    print(f"mj_step(nstep={args.steps}) vs C++ loop: "
          f"{100 * (median['nstep'] / median['cpp'] - 1):+.2f}%")
    print(f"Python loop of mj_step vs C++ loop: "
          f"{1e6 * (median['loop'] - median['cpp']):+.3f} us per call")
    print(f"(the separate C++ binary vs the loop in the module: "
          f"{100 * (median['binary'] / median['cpp'] - 1):+.2f}%)")
    print(f"same final state in all four: {len(finals) == 1}")

    # Rollouts: 1 thread against 2, alternating, best of each.
    rates = {1: [], 2: []}
    results = {}
    for _ in range(5):
        for nthread in (1, 2):
            rate, state = rollout_rate(model, nthread, nbatch=32, nstep=500)
            rates[nthread].append(rate)
            results[nthread] = state
    one, two = statistics.median(rates[1]), statistics.median(rates[2])
    print(f"rollout, 32 x 500 humanoid steps: 1 thread {one:,.0f} steps/s, "
          f"2 threads {two:,.0f} steps/s: {two / one:.2f}x "
          f"(identical results: {np.array_equal(results[1], results[2])})")


if __name__ == "__main__":
    sys.exit(main())
