"""Names and enums: mj_name2id/mj_id2name with mjtObj, named model views, enum values.

Prints one JSON object. goldens/names_enums.json holds what MuJoCo 3.5.1 prints.
"""
import json
from pathlib import Path

import simlab as mujoco

HERE = Path(__file__).resolve().parent
MODELS = HERE.parents[2] / "models"

# One sensor of each kind read below, on a small arm with a tendon.
SENSOR_XML = """
<mujoco model="sensors">
  <worldbody>
    <body name="link" pos="0 0 1">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
      <site name="tip" pos="0.3 0 0" size="0.02"/>
    </body>
  </worldbody>
  <tendon>
    <fixed name="t"><joint joint="hinge" coef="2"/></fixed>
  </tendon>
  <actuator>
    <motor name="m" joint="hinge"/>
  </actuator>
  <sensor>
    <jointpos joint="hinge"/>
    <jointvel joint="hinge"/>
    <actuatorfrc actuator="m"/>
    <tendonpos tendon="t"/>
    <framepos objtype="site" objname="tip"/>
    <framequat objtype="body" objname="link"/>
    <accelerometer site="tip"/>
    <gyro site="tip"/>
    <touch site="tip"/>
    <subtreecom body="link"/>
  </sensor>
</mujoco>
"""

out = {}
gantry = mujoco.MjModel.from_xml_path(str(MODELS / "gantry_gripper.xml"))
bench = mujoco.MjModel.from_xml_path(str(MODELS / "actuator_bench.xml"))

# Every object's name by id through mj_id2name (None where the object has no name).
kinds = {
    "body": (mujoco.mjtObj.mjOBJ_BODY, gantry.nbody),
    "joint": (mujoco.mjtObj.mjOBJ_JOINT, gantry.njnt),
    "geom": (mujoco.mjtObj.mjOBJ_GEOM, gantry.ngeom),
    "actuator": (mujoco.mjtObj.mjOBJ_ACTUATOR, gantry.nu),
    "tendon": (mujoco.mjtObj.mjOBJ_TENDON, gantry.ntendon),
    "equality": (mujoco.mjtObj.mjOBJ_EQUALITY, gantry.neq),
    "key": (mujoco.mjtObj.mjOBJ_KEY, gantry.nkey),
}
out["id2name"] = {kind: [mujoco.mj_id2name(gantry, obj, i) for i in range(n)]
                  for kind, (obj, n) in kinds.items()}

# Ids by name through mj_name2id, prefixed names of the attached gripper included;
# a missing name gives -1.
lookups = [
    (mujoco.mjtObj.mjOBJ_BODY, "cube"), (mujoco.mjtObj.mjOBJ_BODY, "gripper/palm"),
    (mujoco.mjtObj.mjOBJ_BODY, "world"), (mujoco.mjtObj.mjOBJ_JOINT, "z"),
    (mujoco.mjtObj.mjOBJ_JOINT, "gripper/finger_right"), (mujoco.mjtObj.mjOBJ_GEOM, "cube"),
    (mujoco.mjtObj.mjOBJ_ACTUATOR, "gripper/grip"), (mujoco.mjtObj.mjOBJ_TENDON, "gripper/grip"),
    (mujoco.mjtObj.mjOBJ_EQUALITY, "gripper/mirror"), (mujoco.mjtObj.mjOBJ_KEY, "home"),
    (mujoco.mjtObj.mjOBJ_JOINT, "no_such_joint"), (mujoco.mjtObj.mjOBJ_ACTUATOR, "finger_left"),
]
out["name2id"] = [mujoco.mj_name2id(gantry, obj, name) for obj, name in lookups]

# Named views on the model: by index, by name; scalar fields are arrays of shape (1,).
out["actuator_names"] = [gantry.actuator(i).name for i in range(gantry.nu)]
grip = gantry.actuator("gripper/grip")
out["grip"] = {
    "id": grip.id, "name": grip.name, "gainprm": grip.gainprm.tolist(),
    "biasprm": grip.biasprm.tolist(), "forcerange": grip.forcerange.tolist(),
    "trnid": grip.trnid.tolist(), "gear0": float(grip.gear[0]),
}
out["qposadr"] = {name: gantry.joint(name).qposadr.tolist()
                  for name in ["x", "y", "z", "gripper/finger_left", "gripper/finger_right", "cube"]}
out["cube_dofadr"] = int(gantry.joint("cube").dofadr[0])
out["body_mass"] = {name: gantry.body(name).mass.tolist()
                    for name in ["carriage", "gripper/palm", "gripper/left", "cube"]}
out["body_by_index"] = [gantry.body(i).name for i in range(gantry.nbody)]
out["key_home"] = {"id": gantry.key("home").id, "qpos": gantry.key("home").qpos.tolist()}

# Enum names of the types stored in model arrays.
out["geom_types"] = [mujoco.mjtGeom(t).name for t in gantry.geom_type]
out["joint_types"] = [mujoco.mjtJoint(t).name for t in gantry.jnt_type]
out["actuators"] = {}
for label, model in [("bench", bench), ("gantry", gantry)]:
    out["actuators"][label] = {
        "trn": [mujoco.mjtTrn(t).name for t in model.actuator_trntype],
        "dyn": [mujoco.mjtDyn(t).name for t in model.actuator_dyntype],
        "gain": [mujoco.mjtGain(t).name for t in model.actuator_gaintype],
        "bias": [mujoco.mjtBias(t).name for t in model.actuator_biastype],
    }
sensors = mujoco.MjModel.from_xml_string(SENSOR_XML)
out["sensor_types"] = [mujoco.mjtSensor(t).name for t in sensors.sensor_type]
out["sensor_dim"] = sensors.sensor_dim.tolist()
out["sensor_adr"] = sensors.sensor_adr.tolist()

# Comparing array entries with enum members, and enum members as integers.
out["box_geoms"] = [i for i in range(gantry.ngeom)
                    if mujoco.mjtGeom(gantry.geom_type[i]) == mujoco.mjtGeom.mjGEOM_BOX]
out["slide_joints"] = [i for i in range(gantry.njnt)
                       if gantry.jnt_type[i] == mujoco.mjtJoint.mjJNT_SLIDE]
out["enum_values"] = {
    "mjOBJ_BODY": int(mujoco.mjtObj.mjOBJ_BODY),
    "mjOBJ_ACTUATOR": int(mujoco.mjtObj.mjOBJ_ACTUATOR),
    "mjGEOM_PLANE": int(mujoco.mjtGeom.mjGEOM_PLANE),
    "mjGEOM_BOX": int(mujoco.mjtGeom.mjGEOM_BOX),
    "mjJNT_FREE": int(mujoco.mjtJoint.mjJNT_FREE),
    "mjJNT_HINGE": int(mujoco.mjtJoint.mjJNT_HINGE),
    "mjTRN_TENDON": int(mujoco.mjtTrn.mjTRN_TENDON),
    "mjDYN_FILTER": int(mujoco.mjtDyn.mjDYN_FILTER),
    "mjGAIN_FIXED": int(mujoco.mjtGain.mjGAIN_FIXED),
    "mjBIAS_AFFINE": int(mujoco.mjtBias.mjBIAS_AFFINE),
    "mjSENS_TOUCH": int(mujoco.mjtSensor.mjSENS_TOUCH),
    "mjSTATE_FULLPHYSICS": int(mujoco.mjtState.mjSTATE_FULLPHYSICS),
    "mjWARN_BADQPOS": int(mujoco.mjtWarning.mjWARN_BADQPOS),
    "mjNWARNING": int(mujoco.mjtWarning.mjNWARNING),
}

print(json.dumps(out))
