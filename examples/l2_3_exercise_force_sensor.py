"""Lesson 2.3, exercise 2: a force and a torque sensor on the gantry carriage.

INPUT gantry_gripper.xml, with a site on the carriage and a <force> and a <torque> sensor
at it added to the XML text before loading
PROCESS from the home keyframe: lower the carriage around the cube with the gripper open,
close the grip, raise the carriage slowly; read the force sensor's vertical component
with the gripper open, after closing, and with the cube held in the air
OUTPUT the readings, the rise when the cube leaves the floor against its weight
(0.08 kg x 9.81 m/s^2), and which subtree and frame the sensor measures

Run: python examples/l2_3_exercise_force_sensor.py
"""
import textwrap

import simlab as mujoco

from mjcourse import model_path

CUBE_WEIGHT = 0.08 * 9.81
SITE = '<site name="carriage_ft" pos="0 0 0.01"/>\n      '
SENSORS = ('<sensor>\n    <force name="carriage_force" site="carriage_ft"/>\n'
           '    <torque name="carriage_torque" site="carriage_ft"/>\n  </sensor>\n  ')


def sensorized_gantry():
    """The gantry with the site beside the carriage's geom and the two sensors."""
    path = model_path("gantry_gripper")
    xml = path.read_text()
    xml = xml.replace('<attach model="gripper"', SITE + '<attach model="gripper"', 1)
    xml = xml.replace("<keyframe>", SENSORS + "<keyframe>", 1)
    # The gripper it attaches is read from the models folder, given as an asset.
    return mujoco.MjModel.from_xml_string(
        xml, assets={"gripper.xml": model_path("gripper").read_bytes()})


def controls(time):
    """Lower (0-1.5 s), close (2 s), raise slowly from 3 s at 2 cm/s."""
    z = -0.33 * min(time / 1.5, 1.0)
    grip = 0.04 if time < 2.0 else 0.0
    if time > 3.0:
        z = min(-0.33 + 0.02 * (time - 3.0), 0.0)
    return [0.12, 0.0, z, grip]


def cube_on_floor(model, data):
    """Whether a contact joins the floor and the cube."""
    pair = {model.geom("floor").id, model.geom("cube").id}
    return any(set(c.geom.tolist()) == pair for c in data.contact[:data.ncon])


if __name__ == "__main__":
    model = sensorized_gantry()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    force = data.sensor("carriage_force")

    readings, left_floor = {}, None
    while data.time < 8.0 - 1e-9:
        data.ctrl[:] = controls(data.time)
        mujoco.mj_step(model, data)
        step = round(data.time / model.opt.timestep)
        if step == 1000:
            readings["open"] = force.data[2]       # 2.0 s: lowered, gripper still open
        if step == 1500:
            readings["gripped"] = force.data[2]    # 3.0 s: closed, not yet raised
        if left_floor is None and data.time > 3.0 and not cube_on_floor(model, data):
            left_floor = data.time
    readings["lifted"] = force.data[2]
    rise = readings["lifted"] - readings["open"]

    print("force sensor at the carriage, vertical component (site frame z = world z):")
    print(f"  gripper open, cube on the floor:   {readings['open']:.4f} N")
    print(f"  gripper closed, cube on the floor: {readings['gripped']:.4f} N")
    print(f"  cube held in the air:              {readings['lifted']:.4f} N")
    print(f"  the cube left the floor at t = {left_floor:.3f} s, cube z {data.qpos[7]:.4f} m")
    print(f"rise {rise:.4f} N, cube weight 0.08 x 9.81 = {CUBE_WEIGHT:.4f} N "
          f"({100 * (rise - CUBE_WEIGHT) / CUBE_WEIGHT:+.2f}%)")
    torque = data.sensor("carriage_torque").data
    print(f"torque sensor, held: [{torque[0]:.4f} {torque[1]:.4f} {torque[2]:.4f}] N m")
    print(textwrap.fill("what it measures: the force sensor reads the interaction force between the site's "
          "body (the carriage, the child) and its parent (the world, through the three slide "
          "joints and their servos), acting on the subtree rooted at the carriage: carriage, "
          "palm, both fingers and whatever they hold. It is expressed in the site's frame, "
          "whose z axis is the world's up axis here (slide joints do not rotate the carriage); "
          "it counts every force on the subtree, contacts included, so the held cube's weight "
          "arrives through the finger contacts. The torque sensor is the same interaction's "
          "torque about the site.", width=88, subsequent_indent="  "))
    raise SystemExit(0 if abs(rise - CUBE_WEIGHT) < 0.02 * CUBE_WEIGHT else 1)
