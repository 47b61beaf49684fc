"""Lesson 2.3, exercise 1: the gripper's position servo written out as a general actuator.

INPUT gantry_gripper.xml, which attaches gripper.xml, whose grip actuator is
    <position name="grip" tendon="grip" kp="500" kv="10" ctrlrange="0 0.04" forcerange="-5 5"/>
PROCESS replace it by a <general> with the same law written out: p = a u + b0 + b1 l + b2 l'
with a = kp, (b0, b1, b2) = (0, -kp, -kv), and biastype="affine" (without it the bias
parameters are compiled but ignored); load the scene with the edited gripper given as an
asset (from_xml_string(..., assets=...)); run both models from the home keyframe under the
same control sequence: lower the carriage, close the grip on the cube, lift it.
OUTPUT both actuators' parameters, the cube's height along the way, and whether the two
trajectories are identical (every qpos, qvel, act and actuator_force, bit for bit).

Run: python examples/l2_3_exercise_general.py
"""
import numpy as np

import simlab as mujoco

from mjcourse import model_path

POSITION = ('<position name="grip" tendon="grip" kp="500" kv="10" ctrlrange="0 0.04"\n'
            '              forcerange="-5 5"/>')
GENERAL = ('<general name="grip" tendon="grip" gainprm="500" biastype="affine"\n'
           '             biasprm="0 -500 -10" ctrlrange="0 0.04" forcerange="-5 5"/>')


def models():
    """The scene as written, and the scene with the grip written as a general actuator."""
    scene = model_path("gantry_gripper")
    gripper_xml = model_path("gripper").read_text()
    if POSITION not in gripper_xml:
        raise SystemExit("gripper.xml no longer has the position actuator this exercise edits")
    general_gripper = gripper_xml.replace(POSITION, GENERAL).encode()
    original = mujoco.MjModel.from_xml_path(str(scene))
    rewritten = mujoco.MjModel.from_xml_string(scene.read_text(),
                                               assets={"gripper.xml": general_gripper})
    return original, rewritten


def controls(time):
    """x, y, z targets and the grip half-opening at `time`: lower, close, lift slowly."""
    z = -0.33 * min(time / 1.0, 1.0)          # 0-1 s: lower onto the cube
    grip = 0.04 if time < 1.5 else 0.0        # 1.5 s: close
    if time > 2.5:                            # from 2.5 s: raise 0.1 m/s
        z = min(-0.33 + 0.1 * (time - 2.5), 0.0)
    return [0.12, 0.0, z, grip]


def describe(model, name):
    actuator = model.actuator(name)
    print(f"  gaintype {int(actuator.gaintype[0])}, gainprm[0] {actuator.gainprm[0]:g}, "
          f"biastype {int(actuator.biastype[0])}, biasprm[0:3] {actuator.biasprm[:3]}")


def run(model, nstep):
    """The trajectory from the home keyframe: per step qpos, qvel, act, actuator_force."""
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    rows = []
    for _ in range(nstep):
        data.ctrl[:] = controls(data.time)
        mujoco.mj_step(model, data)
        rows.append(np.concatenate([data.qpos, data.qvel, data.act, data.actuator_force]))
    return np.array(rows)


if __name__ == "__main__":
    original, rewritten = models()
    print("position shortcut:")
    describe(original, "gripper/grip")
    print("general, written out:")
    describe(rewritten, "gripper/grip")

    nstep = 2500  # 5 s
    a, b = run(original, nstep), run(rewritten, nstep)
    cube_z = 7  # qpos[7]: the cube's height
    for step in (500, 1250, 2500):
        print(f"  t = {step * original.opt.timestep:.1f} s: cube z {a[step - 1, cube_z]:.4f} m "
              f"(position) {b[step - 1, cube_z]:.4f} m (general)")
    identical = np.array_equal(a, b)
    print(f"trajectories identical over {nstep} steps: {identical} "
          f"(largest difference {np.max(np.abs(a - b)):.3g})")
    raise SystemExit(0 if identical else 1)
