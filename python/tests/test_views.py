"""Views stay valid and writable: writes through numpy views and named views reach the
engine; views outlive the Python objects they came from; copies are independent."""
import copy
import gc

import numpy as np

import simlab
from conftest import model_file


def gantry():
    model = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    data = simlab.MjData(model)
    simlab.mj_resetDataKeyframe(model, data, 0)
    return model, data


def test_writes_through_data_views_reach_the_engine():
    model, data = gantry()
    qpos = data.qpos
    qpos[0] = 0.25                      # carriage x
    simlab.mj_forward(model, data)
    assert data.body("carriage").xpos[0] == 0.25
    data.joint("z").qpos = -0.1         # assignment to a named view copies into qpos
    assert data.qpos[2] == -0.1
    data.qvel[:] = 0.5
    assert np.all(data.qvel == 0.5)
    data.ctrl = [0.1, 0.0, -0.2, 0.02]  # assigning a whole array copies too
    assert data.actuator("gripper/grip").ctrl[0] == 0.02


def test_writes_through_model_views_change_the_simulation():
    model, data = gantry()
    data.ctrl[:] = [0.2, 0, 0, 0.04]
    simlab.mj_forward(model, data)
    before = data.actuator("x").force[0]
    model.actuator_gainprm[0, 0] *= 2            # kp 400 -> 800
    model.actuator("x").biasprm[1] *= 2          # and the matching -kp bias
    simlab.mj_forward(model, data)
    # At rest (qvel 0) the force is kp (u - l): doubling kp doubles it.
    assert before != 0 and np.isclose(data.actuator("x").force[0], 2 * before, rtol=1e-12)
    model.opt.timestep = 0.001
    model.opt.gravity[2] = -1.0
    assert model.opt.timestep == 0.001 and model.opt.gravity[2] == -1.0
    simlab.mj_step(model, data)
    assert np.isclose(data.time, 0.001)


def test_views_follow_the_state_across_steps():
    model, data = gantry()
    qpos, force, finger = data.qpos, data.actuator_force, data.joint("gripper/finger_left")
    data.ctrl[3] = 0.0
    for _ in range(300):
        simlab.mj_step(model, data)
    # The same memory, now holding the stepped state.
    assert qpos[3] == data.qpos[3] and qpos[3] < 0.04
    assert force[3] == data.actuator_force[3] != 0
    assert finger.qpos[0] == data.qpos[3]
    assert data.joint("gripper/finger_left") is finger  # views are cached, as in MuJoCo


def test_views_keep_their_objects_alive():
    model, data = gantry()
    qpos, gain, grip = data.qpos, model.actuator_gainprm, data.actuator("gripper/grip")
    del model, data
    gc.collect()
    # The arrays and the view still read (and write) live engine memory.
    qpos[0] = 0.1
    assert qpos[0] == 0.1 and gain[3, 0] == 500 and grip.ctrl.shape == (1,)
    model = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    data = simlab.MjData(model)
    del model
    gc.collect()
    simlab.mj_step(data.model, data)  # data keeps its model
    assert data.time > 0


def test_contacts_and_constraint_rows_are_read_only_snapshots():
    model, data = gantry()
    data.qpos[2] = -0.33
    simlab.mj_forward(model, data)
    assert data.ncon > 0 and len(data.contact) == data.ncon
    dist = data.contact.dist
    assert dist.shape == (data.ncon,) and not dist.flags.writeable
    assert data.contact.frame.shape == (data.ncon, 9)
    assert data.efc_J.shape == (data.nefc, model.nv)
    assert not data.efc_force.flags.writeable
    first = data.contact[0]
    assert first.dist == dist[0] and first.geom.tolist() == data.contact.geom[0].tolist()
    assert [c.dist for c in data.contact[:2]] == dist[:2].tolist()


def test_copies_are_independent_and_equal():
    model, data = gantry()
    data.ctrl[3] = 0.0
    simlab.mj_step(model, data, nstep=100)
    for twin in (copy.copy(data), copy.deepcopy(data), simlab.mj_copyData(simlab.MjData(model),
                                                                          model, data)):
        assert np.array_equal(twin.qpos, data.qpos) and twin.time == data.time
        twin.qpos[0] = 1.0
        assert data.qpos[0] != 1.0
    a, b = copy.copy(data), copy.copy(data)
    simlab.mj_step(model, a, nstep=50)
    for _ in range(50):
        simlab.mj_step(model, b)
    assert np.array_equal(a.qpos, b.qpos) and np.array_equal(a.qacc, b.qacc)


def test_warnings_view_the_counters():
    model, data = gantry()
    data.qvel[0] = float("inf")
    simlab.mj_step(model, data)
    bad = data.warning[simlab.mjtWarning.mjWARN_BADQVEL]
    assert bad.number == 1 and data.warning.number[int(simlab.mjtWarning.mjWARN_BADQVEL)] == 1
    assert np.all(np.isfinite(data.qvel))  # the data was reset
    bad.number = 0
    assert data.warning.number.sum() == 0
