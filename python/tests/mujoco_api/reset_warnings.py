"""Keyframe resets, data.time, and the automatic reset that follows a NaN in the state,
counted in data.warning.

Prints one JSON object. goldens/reset_warnings.json holds what MuJoCo 3.5.1 prints.
"""
import json

import simlab as mujoco

# A pendulum on a hinge driven through a first-order filter (so the state has an
# activation), a slider with a position servo, and two keyframes that set everything.
XML = """
<mujoco model="keys">
  <option timestep="0.005"/>
  <worldbody>
    <body name="pendulum" pos="0 0 1">
      <joint name="swing" type="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.03"/>
    </body>
    <body name="slider" pos="0.5 0 1">
      <joint name="slide" type="slide" axis="1 0 0" range="-0.2 0.2"/>
      <geom type="box" size="0.05 0.05 0.05"/>
    </body>
  </worldbody>
  <actuator>
    <general name="filtered" joint="swing" dyntype="filter" dynprm="0.05" gainprm="2"/>
    <position name="servo" joint="slide" kp="50" kv="2"/>
  </actuator>
  <keyframe>
    <key name="raised" time="1.5" qpos="1.2 0.1" qvel="-0.5 0" act="0.3" ctrl="0.7 -0.15"/>
    <key name="still" qpos="0 -0.1"/>
  </keyframe>
</mujoco>
"""


def state(data):
    """Time, state, controls and the warning counters."""
    return {
        "time": data.time,
        "qpos": data.qpos.tolist(),
        "qvel": data.qvel.tolist(),
        "act": data.act.tolist(),
        "ctrl": data.ctrl.tolist(),
        "warnings": [data.warning[i].number for i in range(len(data.warning))],
    }


model = mujoco.MjModel.from_xml_string(XML)
data = mujoco.MjData(model)
out = {"nkey": model.nkey, "na": model.na, "nwarning": len(data.warning)}

# A keyframe by name: time, qpos, qvel, act and ctrl all come from it.
mujoco.mj_resetDataKeyframe(model, data, model.key("raised").id)
out["raised"] = state(data)
mujoco.mj_step(model, data, nstep=200)
out["raised_200"] = state(data)
out["raised_200"]["actuator_force"] = data.actuator_force.tolist()

# A keyframe by index that gives only qpos: the rest takes the model's defaults.
mujoco.mj_resetDataKeyframe(model, data, 1)
out["still"] = state(data)

# data.time is writable and advances by the timestep.
data.time = 10.0
mujoco.mj_step(model, data, nstep=3)
out["time_after_3"] = data.time

# A NaN in qpos: mj_step warns (mjWARN_BADQPOS, index of the bad coordinate in
# lastinfo), resets the data to qpos0 and carries on with the step.
mujoco.mj_resetDataKeyframe(model, data, 0)
data.qpos[1] = float("nan")
mujoco.mj_step(model, data)
out["bad_qpos"] = state(data)
badqpos = data.warning[mujoco.mjtWarning.mjWARN_BADQPOS]
out["bad_qpos"]["number"] = badqpos.number
out["bad_qpos"]["lastinfo"] = badqpos.lastinfo

# An infinite velocity: mjWARN_BADQVEL, counted the same way.
mujoco.mj_resetDataKeyframe(model, data, 0)
data.qvel[0] = float("inf")
mujoco.mj_step(model, data, nstep=2)
out["bad_qvel"] = state(data)
out["bad_qvel"]["number"] = data.warning[mujoco.mjtWarning.mjWARN_BADQVEL].number
out["bad_qvel"]["lastinfo"] = data.warning[mujoco.mjtWarning.mjWARN_BADQVEL].lastinfo

# mj_resetData clears the counters.
mujoco.mj_resetData(model, data)
out["reset"] = state(data)

print(json.dumps(out))
