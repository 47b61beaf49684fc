"""Actuators of lesson 2.3's bench: named access, ctrl writes, stepping, gains changed
from Python, mj_step1/mj_step2 and mj_resetData.

Prints one JSON object. goldens/actuators.json holds what MuJoCo 3.5.1 prints.
"""
import json
from pathlib import Path

import simlab as mujoco

HERE = Path(__file__).resolve().parent
MODELS = HERE.parents[2] / "models"

NAMES = ["motor", "position", "velocity", "filter"]
JOINTS = ["motor_hinge", "position_hinge", "velocity_hinge", "filter_hinge"]


def snapshot(model, data):
    """The state and the actuator quantities, by name and as whole arrays."""
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "act": data.act.tolist(),
        "ctrl": data.ctrl.tolist(),
        "actuator_force": data.actuator_force.tolist(),
        "actuator_length": data.actuator_length.tolist(),
        "actuator_velocity": data.actuator_velocity.tolist(),
        "qfrc_actuator": data.qfrc_actuator.tolist(),
        "force_by_name": {n: data.actuator(n).force.tolist() for n in NAMES},
        "ctrl_by_name": {n: data.actuator(n).ctrl.tolist() for n in NAMES},
        "joints": {j: [data.joint(j).qpos.tolist(), data.joint(j).qvel.tolist()] for j in JOINTS},
    }


model = mujoco.MjModel.from_xml_path(str(MODELS / "actuator_bench.xml"))
data = mujoco.MjData(model)
out = {}

# The force law's parameters, read through the named actuator views.
out["params"] = {}
for name in NAMES:
    act = model.actuator(name)
    out["params"][name] = {
        "id": act.id, "gainprm": act.gainprm.tolist(), "biasprm": act.biasprm.tolist(),
        "dynprm": act.dynprm.tolist()[:3], "gear": act.gear.tolist(),
        "ctrlrange": act.ctrlrange.tolist(), "forcerange": act.forcerange.tolist(),
    }
out["names_by_index"] = [model.actuator(i).name for i in range(model.nu)]
out["actuator_gainprm"] = model.actuator_gainprm[:, :3].tolist()

# Controls written by name (whole view and element) and through a slice; 250 steps.
data.actuator("motor").ctrl = 0.5
data.actuator("position").ctrl[0] = 1.2
data.ctrl[2:4] = [2.0, 1.0]
mujoco.mj_step(model, data, nstep=250)
out["after_250"] = snapshot(model, data)

# A control outside ctrlrange is clamped by the engine, not in data.ctrl.
data.actuator("motor").ctrl = 3.0
mujoco.mj_forward(model, data)
out["clamped"] = {"ctrl": data.actuator("motor").ctrl.tolist(),
                  "force": data.actuator("motor").force.tolist(),
                  "qfrc": data.joint("motor_hinge").qfrc_actuator.tolist()}

# The motor's gain changed from Python takes effect at the next mj_forward.
model.actuator_gainprm[0, 0] = 5
mujoco.mj_forward(model, data)
out["gain5"] = {"gainprm": model.actuator("motor").gainprm.tolist(),
                "force": data.actuator_force.tolist(),
                "qacc": data.qacc.tolist()}

# A controller between mj_step1 and mj_step2, 100 times: ctrl from the current velocity.
for _ in range(100):
    mujoco.mj_step1(model, data)
    data.ctrl[0] = -0.25 * data.qvel[0]
    data.ctrl[3] = 0.5
    mujoco.mj_step2(model, data)
out["after_step12"] = snapshot(model, data)

# mj_resetData: zero state and controls, time 0; then one plain mj_step.
mujoco.mj_resetData(model, data)
out["reset"] = snapshot(model, data)
data.ctrl[:] = [1.0, -1.0, 1.0, -1.0]
mujoco.mj_step(model, data)
out["one_step"] = snapshot(model, data)

print(json.dumps(out))
