"""Jacobians and the mass matrix of an arm with hinge, slide and ball joints:
mj_jac, mj_jacBody, mj_jacBodyCom, mj_jacSite, mj_jacGeom, mj_fullM, mj_mulM.

Prints one JSON object. goldens/jacobians.json holds what MuJoCo 3.5.1 prints.
"""
import json

import numpy as np

import simlab as mujoco

# A turret (yaw hinge) carrying a lifted, pitched upper arm and a wrist on a ball joint
# holding a hand with a tool site; nq = 7, nv = 6.
XML = """
<mujoco model="arm">
  <worldbody>
    <body name="base" pos="0 0 0.5">
      <joint name="yaw" type="hinge" axis="0 0 1" armature="0.01"/>
      <geom name="base" type="cylinder" size="0.05 0.05" mass="2"/>
      <body name="upper" pos="0 0 0.1">
        <joint name="lift" type="slide" axis="0 0 1" stiffness="200" damping="2"/>
        <joint name="pitch" type="hinge" axis="0 1 0"/>
        <geom name="upper" type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
        <body name="wrist" pos="0.3 0 0">
          <joint name="wrist" type="ball"/>
          <geom name="hand" type="box" size="0.04 0.02 0.01" pos="0.05 0 0" euler="0 0 30"/>
          <site name="tool" pos="0.1 0.01 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""

model = mujoco.MjModel.from_xml_string(XML)
data = mujoco.MjData(model)
out = {"nv": model.nv, "nM": model.nM}

# A pose and velocities through the joint views (the ball's quaternion is a unit one).
data.joint("yaw").qpos = 0.4
data.joint("lift").qpos = 0.05
data.joint("pitch").qpos = -0.6
data.joint("wrist").qpos = [0.5, 0.5, -0.5, 0.5]
data.qvel[:] = [0.3, -0.1, 0.2, 1.0, -0.5, 0.25]
mujoco.mj_forward(model, data)

wrist = model.body("wrist").id
tool = model.site("tool").id
hand = model.geom("hand").id
out["ids"] = [wrist, tool, hand]
out["masses"] = {name: model.body(name).mass.tolist() for name in ["base", "upper", "wrist"]}

# Translational and rotational Jacobians, (3, nv) each.
jacp = np.zeros((3, model.nv))
jacr = np.zeros((3, model.nv))
mujoco.mj_jacSite(model, data, jacp, jacr, tool)
out["jacSite"] = [jacp.tolist(), jacr.tolist()]
out["tool_velocity"] = (jacp @ data.qvel).tolist()

mujoco.mj_jacBody(model, data, jacp, jacr, wrist)
out["jacBody"] = [jacp.tolist(), jacr.tolist()]

# Only the translational part; jacr=None is allowed.
jacp_com = np.zeros((3, model.nv))
mujoco.mj_jacBodyCom(model, data, jacp_com, None, model.body("upper").id)
out["jacBodyCom"] = jacp_com.tolist()

mujoco.mj_jacGeom(model, data, jacp, jacr, hand)
out["jacGeom"] = [jacp.tolist(), jacr.tolist()]

# A point fixed to the wrist body, away from its origin.
point = data.body("wrist").xpos + np.array([0.02, 0.05, -0.03])
mujoco.mj_jac(model, data, jacp, jacr, point, wrist)
out["jac_point"] = point.tolist()
out["jac"] = [jacp.tolist(), jacr.tolist()]

# The inertia matrix: sparse qM, dense from mj_fullM, and M times a vector.
M = np.zeros((model.nv, model.nv))
mujoco.mj_fullM(model, M, data.qM)
out["qM"] = data.qM.tolist()
out["fullM"] = M.tolist()
vec = np.array([1.0, -2.0, 0.5, 0.25, 3.0, -1.5])
res = np.zeros(model.nv)
mujoco.mj_mulM(model, data, res, vec)
out["mulM"] = res.tolist()
out["mulM_vs_fullM"] = float(np.max(np.abs(M @ vec - res)))

# The same after 200 steps under gravity (the arm folds, the Jacobians change).
mujoco.mj_step(model, data, nstep=200)
mujoco.mj_jacSite(model, data, jacp, jacr, tool)
out["stepped"] = {"qpos": data.qpos.tolist(), "jacSite": [jacp.tolist(), jacr.tolist()],
                  "tool": data.site("tool").xpos.tolist()}
mujoco.mj_fullM(model, M, data.qM)
out["stepped"]["fullM"] = M.tolist()

print(json.dumps(out))
