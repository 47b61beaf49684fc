"""Loading: a model from an XML string and models from files, and their sizes.

Prints one JSON object. goldens/load_sizes.json holds what MuJoCo 3.5.1 prints.
"""
import json
from pathlib import Path

import simlab as mujoco

HERE = Path(__file__).resolve().parent
MODELS = HERE.parents[2] / "models"
HUMANOID = HERE.parents[3] / "shared/corpus/mujoco/model/humanoid/humanoid.xml"

# A free box and a capsule over a plane, with a site, two sensors and a keyframe.
XML = """
<mujoco model="from_string">
  <option timestep="0.004"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="box" pos="0 0 0.2">
      <freejoint/>
      <geom name="box" type="box" size="0.05 0.04 0.03"/>
      <site name="top" pos="0 0 0.03"/>
    </body>
    <body name="arm" pos="0.3 0 0.3">
      <joint name="swing" type="hinge" axis="0 1 0"/>
      <geom name="arm" type="capsule" fromto="0 0 0 0.2 0 0" size="0.02"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="swing" joint="swing"/>
  </actuator>
  <sensor>
    <framepos name="top_pos" objtype="site" objname="top"/>
    <jointpos name="swing_angle" joint="swing"/>
  </sensor>
  <keyframe>
    <key name="up" qpos="0 0 0.5 1 0 0 0 0.3"/>
  </keyframe>
</mujoco>
"""

SIZES = ["nq", "nv", "nu", "na", "nbody", "njnt", "ngeom", "nsite", "nsensor",
         "nsensordata", "ntendon", "neq", "nkey", "nM"]


def sizes(model):
    """The model's sizes by name, and the options a file can set."""
    out = {name: getattr(model, name) for name in SIZES}
    out["timestep"] = model.opt.timestep
    out["gravity"] = model.opt.gravity.tolist()
    return out


out = {}

# A model compiled from a string.
model = mujoco.MjModel.from_xml_string(XML)
out["from_string"] = sizes(model)

# Models loaded from files (gantry_gripper.xml attaches gripper.xml from its folder).
for name in ["actuator_bench", "gantry_gripper", "double_pendulum"]:
    model = mujoco.MjModel.from_xml_path(str(MODELS / f"{name}.xml"))
    out[name] = sizes(model)

# MuJoCo's humanoid, the bigger case.
model = mujoco.MjModel.from_xml_path(str(HUMANOID))
out["humanoid"] = sizes(model)

# A fresh MjData: time 0, qpos at qpos0, the keyframes' qpos as an (nkey, nq) array.
data = mujoco.MjData(model)
out["humanoid_data"] = {
    "time": data.time,
    "qpos_is_qpos0": bool((data.qpos == model.qpos0).all()),
    "qpos0": model.qpos0.tolist(),
    "key_qpos_1": model.key_qpos[1].tolist(),
    "body_mass": model.body_mass.tolist(),
}

# Array shapes as MuJoCo's bindings expose them, and whether each holds real numbers or
# integers (simlab keeps MuJoCo's float32 and uint8 arrays as float64 and int32).
arrays = {
    "qpos": data.qpos, "ctrl": data.ctrl, "xpos": data.xpos, "xquat": data.xquat,
    "xmat": data.xmat, "qM": data.qM, "sensordata": data.sensordata,
    "actuator_gainprm": model.actuator_gainprm, "body_mass": model.body_mass,
    "geom_size": model.geom_size, "geom_rgba": model.geom_rgba,
    "geom_type": model.geom_type, "jnt_limited": model.jnt_limited,
    "key_qpos": model.key_qpos,
}
out["shapes"] = {name: list(a.shape) for name, a in arrays.items()}
out["kinds"] = {name: "real" if a.dtype.kind == "f" else "integer" for name, a in arrays.items()}

print(json.dumps(out))
