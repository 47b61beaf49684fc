"""Contacts: a box, a capsule and a sphere dropped on a plane; data.contact fields,
mj_contactForce and sensors after whole numbers of steps.

Prints one JSON object. goldens/contacts.json holds what MuJoCo 3.5.1 prints.
"""
import json

import numpy as np

import simlab as mujoco

# Three free bodies released above a plane, tilted so that they land on an edge and
# tumble; a touch sensor under the box and frame sensors on it.
XML = """
<mujoco model="drop">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1" friction="0.8 0.005 0.0001"/>
    <body name="box" pos="0 0 0.25" euler="15 25 5">
      <freejoint name="box"/>
      <geom name="box" type="box" size="0.06 0.04 0.03" mass="0.5"/>
      <site name="sole" type="box" pos="0 0 -0.03" size="0.065 0.045 0.01"/>
      <site name="corner" pos="0.06 0.04 0.03"/>
    </body>
    <body name="capsule" pos="0.3 0.1 0.2" euler="0 70 20">
      <freejoint name="capsule"/>
      <geom name="capsule" type="capsule" size="0.03 0.1"/>
    </body>
    <body name="ball" pos="-0.25 0 0.15">
      <freejoint name="ball"/>
      <geom name="ball" type="sphere" size="0.04" condim="6"/>
    </body>
  </worldbody>
  <sensor>
    <touch name="touch" site="sole"/>
    <framepos name="corner_pos" objtype="site" objname="corner"/>
    <framequat name="box_quat" objtype="body" objname="box"/>
    <accelerometer name="acc" site="corner"/>
    <velocimeter name="vel" site="corner"/>
  </sensor>
</mujoco>
"""

SENSORS = ["touch", "corner_pos", "box_quat", "acc", "vel"]


def contacts(model, data):
    """Every active contact, as whole arrays and one by one, with its force."""
    contact = data.contact
    out = {
        "ncon": data.ncon,
        "len": len(data.contact),
        "dist": contact.dist.tolist(),
        "pos": contact.pos.tolist(),
        "frame": contact.frame.tolist(),
        "geom1": contact.geom1.tolist(),
        "geom2": contact.geom2.tolist(),
        "geom": contact.geom.tolist(),
        "dim": contact.dim.tolist(),
        "friction": contact.friction.tolist(),
        "efc_address": contact.efc_address.tolist(),
        "shape_pos": list(contact.pos.shape),
        "shape_frame": list(contact.frame.shape),
    }
    out["each"] = [[data.contact[i].dist, data.contact[i].pos.tolist(),
                    int(data.contact[i].geom1), int(data.contact[i].geom2)]
                   for i in range(data.ncon)]
    out["names"] = [[mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in pair]
                    for pair in contact.geom.tolist()]
    force = np.zeros(6)
    out["force"] = []
    for i in range(data.ncon):
        mujoco.mj_contactForce(model, data, i, force)
        out["force"].append(force.tolist())
    return out


def state(data):
    """Where the bodies are and what the sensors read."""
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "box_qpos": data.joint("box").qpos.tolist(),
        "ball_qvel": data.joint("ball").qvel.tolist(),
        "box_xpos": data.body("box").xpos.tolist(),
        "box_xquat": data.body("box").xquat.tolist(),
        "capsule_geom_xpos": data.geom("capsule").xpos.tolist(),
        "corner_site": data.site("corner").xpos.tolist(),
        "sensors": {name: data.sensor(name).data.tolist() for name in SENSORS},
        "sensordata": data.sensordata.tolist(),
        "qfrc_constraint": data.qfrc_constraint.tolist(),
        "nefc": data.nefc,
    }


model = mujoco.MjModel.from_xml_string(XML)
data = mujoco.MjData(model)
out = {}

# Before anything touches the floor.
mujoco.mj_forward(model, data)
out["start"] = {"ncon": data.ncon, "len": len(data.contact), "dist": data.contact.dist.tolist()}

# Landing: 100 steps (0.2 s), the capsule and the ball are down.
mujoco.mj_step(model, data, nstep=100)
out["landing"] = {"contacts": contacts(model, data), "state": state(data)}

# 300 more steps: the box has tumbled onto a face.
mujoco.mj_step(model, data, nstep=300)
out["settled"] = {"contacts": contacts(model, data), "state": state(data)}

print(json.dumps(out))
