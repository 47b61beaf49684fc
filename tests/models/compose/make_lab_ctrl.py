"""Control schedules of lesson 2.3's gantry lab, for models/gantry_gripper.xml from key 0.

Rows are ctrl = [x, y, z, grip] per step (timestep 0.002 s):
  0.0-0.5 s  hold home (gripper open, z = 0)
  0.5-2.0 s  lower z to -0.33 (the open fingers surround the cube)
  2.0-3.0 s  close the grip (target 0: the grip force saturates at its forcerange)
  then       slow: raise z linearly to 0 over 3 s and hold 1 s
             jump: set z to 0.05 at once and hold 2 s
             hold: raise as slow does, then hold z = 0 for 10 s (the cube stays held)
Run: python3 make_lab_ctrl.py (writes gantry_lab_{slow,jump,hold}.csv here).
"""
import os

DT = 0.002
X, Y = 0.12, 0.0


def rows(schedule):
    out = []
    for seconds, target in schedule:
        n = round(seconds / DT)
        for i in range(n):
            out.append(target(i / n))
    return out


def lab(finish):
    start = [
        (0.5, lambda s: (X, Y, 0.0, 0.04)),
        (1.5, lambda s: (X, Y, -0.33, 0.04)),
        (1.0, lambda s: (X, Y, -0.33, 0.0)),
    ]
    return rows(start + finish)


SLOW = [(3.0, lambda s: (X, Y, -0.33 + 0.33 * s, 0.0)), (1.0, lambda s: (X, Y, 0.0, 0.0))]
JUMP = [(2.0, lambda s: (X, Y, 0.05, 0.0))]
HOLD = SLOW[:1] + [(10.0, lambda s: (X, Y, 0.0, 0.0))]

here = os.path.dirname(os.path.abspath(__file__))
for name, finish in (("slow", SLOW), ("jump", JUMP), ("hold", HOLD)):
    with open(os.path.join(here, f"gantry_lab_{name}.csv"), "w") as f:
        f.write(f"# gantry lab, {name} raise (make_lab_ctrl.py)\n")
        for r in lab(finish):
            f.write(",".join(repr(round(v, 9)) for v in r) + "\n")
