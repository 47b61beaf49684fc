"""MuJoCo's humanoid falling from a keyframe: copies of MjData (copy.copy, copy.deepcopy,
mj_copyData) stepped beside the original, and mj_stateSize/mj_getState/mj_setState with
mjSTATE_FULLPHYSICS to rewind and replay.

Prints one JSON object. goldens/humanoid_state.json holds what MuJoCo 3.5.1 prints.
"""
import copy
import json
from pathlib import Path

import numpy as np

import simlab as mujoco

HERE = Path(__file__).resolve().parent
HUMANOID = HERE.parents[3] / "shared/corpus/mujoco/model/humanoid/humanoid.xml"


def summary(data):
    """The state, the contacts and a few named quantities."""
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "ncon": data.ncon,
        "contact_geom": data.contact.geom.tolist(),
        "torso_xpos": data.body("torso").xpos.tolist(),
        "root_qpos": data.joint("root").qpos.tolist(),
        "knee_left": data.joint("knee_left").qpos.tolist(),
        "hamstring_right": data.tendon("hamstring_right").length.tolist(),
        "actuator_force": data.actuator_force.tolist(),
    }


model = mujoco.MjModel.from_xml_path(str(HUMANOID))
data = mujoco.MjData(model)
out = {}

# Start standing on the left leg (keyframe found by name), with constant torques.
mujoco.mj_resetDataKeyframe(model, data, model.key("stand_on_left_leg").id)
data.ctrl[:] = [0.1 * ((i % 5) - 2) for i in range(model.nu)]
mujoco.mj_step(model, data, nstep=100)
out["t100"] = summary(data)

# Three copies of the data, and the full physical state saved in a vector.
shallow = copy.copy(data)
deep = copy.deepcopy(data)
explicit = mujoco.MjData(model)
mujoco.mj_copyData(explicit, model, data)
sig = mujoco.mjtState.mjSTATE_FULLPHYSICS
size = mujoco.mj_stateSize(model, sig)
state = np.empty(size)
mujoco.mj_getState(model, data, state, sig)
out["state_size"] = size
out["state"] = state.tolist()

# The original and every copy stepped 150 steps: they stay bitwise equal.
mujoco.mj_step(model, data, nstep=150)
for other in [shallow, deep, explicit]:
    mujoco.mj_step(model, other, nstep=150)
out["t250"] = summary(data)
out["copies_equal"] = [bool(np.array_equal(other.qpos, data.qpos) and
                            np.array_equal(other.qvel, data.qvel) and other.time == data.time)
                       for other in [shallow, deep, explicit]]

# A copy is independent: new controls on it leave the original alone.
shallow.ctrl[:] = 0.0
mujoco.mj_step(model, shallow, nstep=50)
out["shallow_t300"] = summary(shallow)
out["original_untouched"] = out["t250"]["qpos"] == data.qpos.tolist()

# Rewind the original to t=0.5 with mj_setState and replay 150 steps. The warmstart is
# not part of mjSTATE_FULLPHYSICS, so the replay starts from the t=1.25 warmstart.
mujoco.mj_setState(model, data, state, sig)
out["rewound"] = {"time": data.time, "qpos": data.qpos.tolist()}
mujoco.mj_step(model, data, nstep=150)
out["replayed"] = summary(data)

# mj_resetData back to qpos0 then the "squat" keyframe by index.
mujoco.mj_resetData(model, data)
out["reset"] = {"time": data.time, "qpos": data.qpos.tolist(), "ctrl": data.ctrl.tolist()}
mujoco.mj_resetDataKeyframe(model, data, 0)
mujoco.mj_forward(model, data)
out["squat"] = summary(data)

print(json.dumps(out))
