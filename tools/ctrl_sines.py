#!/usr/bin/env python3
"""Smooth controls for models ctrlgen.mjs (the npm MuJoCo 3.5.1) cannot load: one CSV row
of NU numbers per step, in the format of ../shared/oracle/FORMAT.md.

    tools/ctrl_sines.py NU STEPS TIMESTEP [--amp A] [--ramp COL:RATE ...] > CTRL.csv

Control c at step k (time t = (k + 1) * TIMESTEP) is A * sin(w_c t + phase_c) with
w_c = 1.5 + 0.7 c rad/s and phase_c = 0.9 c, every entry moving at its own frequency;
--ramp COL:RATE adds RATE * t to column COL (a setpoint that winds around a joint).
"""
import argparse
import math

parser = argparse.ArgumentParser()
parser.add_argument("nu", type=int)
parser.add_argument("steps", type=int)
parser.add_argument("timestep", type=float)
parser.add_argument("--amp", type=float, default=1.2)
parser.add_argument("--ramp", action="append", default=[])
args = parser.parse_args()
ramps = {int(c): float(r) for c, r in (item.split(":") for item in args.ramp)}
print(f"# {args.nu} smooth controls per step (tools/ctrl_sines.py, amplitude {args.amp})")
for k in range(args.steps):
    t = (k + 1) * args.timestep
    row = [args.amp * math.sin((1.5 + 0.7 * c) * t + 0.9 * c) + ramps.get(c, 0) * t
           for c in range(args.nu)]
    print(",".join(repr(x) for x in row))
