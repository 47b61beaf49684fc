"""simlab: MuJoCo's Python API on the simlab engine.

Scripts written for MuJoCo's Python bindings run on simlab with one line changed:

    import simlab as mujoco

    model = mujoco.MjModel.from_xml_path("models/gantry_gripper.xml")
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    data.actuator("gripper/grip").ctrl = 0.03
    mujoco.mj_step(model, data, nstep=1000)
    print(data.joint("gripper/finger_left").qpos[0])

Every array of MjModel and MjData is a numpy view of the engine's memory (writes go
through); named views (model.actuator("grip"), data.body("cube")) slice them per object.
Contacts (data.contact) and constraint rows (data.efc_*) change size every step: they
are read-only copies taken when asked for.
"""
import numpy as _np

from simlab._simlab import *  # noqa: F401,F403  (MjModel, MjData, mj_*, mjt* enums)
from simlab import rollout  # noqa: F401

# The floating-point type of every real-valued array (MuJoCo's mjtNum).
MJTNUM_DTYPE = _np.float64

__version__ = "0.14.0"
