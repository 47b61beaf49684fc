"""The double pendulum: writes through views, body/site/geom poses, options changed from
Python, mj_step1/mj_step2 against mj_step.

Prints one JSON object. goldens/pendulum_views.json holds what MuJoCo 3.5.1 prints.
"""
import json
from pathlib import Path

import numpy as np

import simlab as mujoco

HERE = Path(__file__).resolve().parent
MODELS = HERE.parents[2] / "models"


def poses(data):
    """Where the links, the tip site and the geoms are."""
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "qacc": data.qacc.tolist(),
        "upper_xpos": data.body("upper").xpos.tolist(),
        "lower_xpos": data.body("lower").xpos.tolist(),
        "lower_xquat": data.body("lower").xquat.tolist(),
        "lower_xmat": data.body("lower").xmat.tolist(),
        "lower_com": data.body("lower").xipos.tolist(),
        "tip": data.site("tip").xpos.tolist(),
        "tip_xmat": data.site("tip").xmat.tolist(),
        "geom_xpos": [data.geom(i).xpos.tolist() for i in range(2)],
        "xpos": data.xpos.tolist(),
        "xquat": data.xquat.tolist(),
    }


model = mujoco.MjModel.from_xml_path(str(MODELS / "double_pendulum.xml"))
data = mujoco.MjData(model)
out = {}

# The model as compiled: qpos0 and the links' masses.
out["masses"] = {name: model.body(name).mass.tolist() for name in ["upper", "lower"]}
out["shoulder_qposadr"] = int(model.joint("shoulder").qposadr[0])
out["elbow_dofadr"] = int(model.joint("elbow").dofadr[0])

# Pose written element by element through the joint views, then mj_forward.
data.joint("shoulder").qpos[0] = 0.3
data.joint("elbow").qvel[0] = -1.0
mujoco.mj_forward(model, data)
out["posed"] = poses(data)

# 300 steps from there.
mujoco.mj_step(model, data, nstep=300)
out["stepped"] = poses(data)

# The same start written through whole-array slices, stepped with mj_step1/mj_step2:
# the same trajectory as mj_step.
other = mujoco.MjData(model)
other.qpos[:] = [0.3, 0.0]
other.qvel[:] = np.array([0.0, -1.0])
for _ in range(300):
    mujoco.mj_step1(model, other)
    mujoco.mj_step2(model, other)
out["step12"] = poses(other)
out["step12_equal"] = bool(np.array_equal(other.qpos, data.qpos))

# A smaller timestep and a gravity with a sideways part, set from Python.
model.opt.timestep = 0.001
model.opt.gravity[:] = [2.0, 0.0, -9.81]
mujoco.mj_resetData(model, data)
mujoco.mj_step(model, data, nstep=500)
out["new_options"] = {"timestep": model.opt.timestep, "gravity": model.opt.gravity.tolist()}
out["tilted"] = poses(data)

# Gravity assigned as a whole attribute, and a whole-array qpos assignment.
model.opt.gravity = [0.0, 0.0, -1.62]
data.qpos = [1.0, -0.5]
data.qvel[:] = 0
mujoco.mj_step(model, data, nstep=200)
out["moon"] = poses(data)

print(json.dumps(out))
