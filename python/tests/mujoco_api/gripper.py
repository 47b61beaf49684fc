"""The gantry gripper (models/gantry_gripper.xml attaching models/gripper.xml): keyframe
reset by name, controls by name, the grip tendon, elliptic-cone contacts, a slow lift.

Prints one JSON object. goldens/gripper.json holds what MuJoCo 3.5.1 prints.
"""
import json
from pathlib import Path

import numpy as np

import simlab as mujoco

HERE = Path(__file__).resolve().parent
MODELS = HERE.parents[2] / "models"

ACTUATORS = ["x", "y", "z", "gripper/grip"]


def report(model, data):
    """Carriage, fingers, tendon, cube and contacts."""
    force = np.zeros(6)
    forces = []
    for i in range(data.ncon):
        mujoco.mj_contactForce(model, data, i, force)
        forces.append(force.tolist())
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "ctrl": {name: data.actuator(name).ctrl.tolist() for name in ACTUATORS},
        "force": {name: data.actuator(name).force.tolist() for name in ACTUATORS},
        "fingers": [data.joint("gripper/finger_left").qpos.tolist(),
                    data.joint("gripper/finger_right").qpos.tolist()],
        "grip_length": data.tendon("gripper/grip").length.tolist(),
        "grip_velocity": data.tendon("gripper/grip").velocity.tolist(),
        "ten_length": data.ten_length.tolist(),
        "cube_qpos": data.joint("cube").qpos.tolist(),
        "cube_xpos": data.body("cube").xpos.tolist(),
        "palm_xpos": data.body("gripper/palm").xpos.tolist(),
        "finger_geom_xpos": data.geom("gripper/finger_left").xpos.tolist(),
        "ncon": data.ncon,
        "contact_geom": data.contact.geom.tolist(),
        "contact_dist": data.contact.dist.tolist(),
        "contact_frame": data.contact.frame.tolist(),
        "contact_force": forces,
    }


model = mujoco.MjModel.from_xml_path(str(MODELS / "gantry_gripper.xml"))
data = mujoco.MjData(model)
out = {}

# Reset to the "home" keyframe found by name: carriage above the cube, gripper open.
mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
out["home"] = report(model, data)

# Lower the carriage around the cube (400 steps).
data.actuator("z").ctrl = -0.33
mujoco.mj_step(model, data, nstep=400)
out["lowered"] = report(model, data)

# Close the grip (300 steps): the grip force saturates at its forcerange.
data.actuator("gripper/grip").ctrl = 0.0
mujoco.mj_step(model, data, nstep=300)
out["closed"] = report(model, data)

# Lift slowly, 1 cm every 25 steps, ten times: the cube comes along.
for k in range(1, 11):
    data.actuator("z").ctrl = -0.33 + 0.01 * k
    mujoco.mj_step(model, data, nstep=25)
out["lifted"] = report(model, data)

# The gripper's own keyframe, padded with this model's defaults.
mujoco.mj_resetDataKeyframe(model, data, 1)
out["key1"] = {"qpos": data.qpos.tolist(), "ctrl": data.ctrl.tolist(), "time": data.time}

print(json.dumps(out))
