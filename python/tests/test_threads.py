"""Stepping releases the GIL, and batched rollouts (simlab.rollout) give the same numbers
whatever the thread count, equal to stepping the same inputs one by one from Python."""
import threading
import time

import numpy as np
import pytest

import simlab
import simlab.rollout
from conftest import model_file

HUMANOID = "mujoco/model/humanoid/humanoid.xml"
FULL = int(simlab.mjtState.mjSTATE_FULLPHYSICS)


def test_mj_step_releases_the_gil():
    model = simlab.MjModel.from_xml_path(str(model_file(HUMANOID)))
    data = simlab.MjData(model)
    started = threading.Event()

    def simulate():
        started.set()
        simlab.mj_step(model, data, nstep=3000)

    worker = threading.Thread(target=simulate)
    worker.start()
    started.wait()
    # Python code runs on this thread while the other one steps: were the GIL held for
    # the whole call, this loop would get (almost) no turns until it returned.
    spins, begin = 0, time.perf_counter()
    while worker.is_alive():
        spins += 1
    elapsed = time.perf_counter() - begin
    worker.join()
    assert data.time == pytest.approx(3000 * model.opt.timestep)
    assert elapsed > 0.02 and spins > 10000, (spins, elapsed)


def batch(model, nbatch, nstep, seed=1):
    """Initial states around the home pose and random controls in the actuators' ranges."""
    rng = np.random.default_rng(seed)
    data = simlab.MjData(model)
    state0 = np.zeros((nbatch, simlab.mj_stateSize(model, FULL)))
    for b in range(nbatch):
        simlab.mj_resetData(model, data)
        data.qvel[:] = 0.1 * rng.standard_normal(model.nv)
        simlab.mj_getState(model, data, state0[b], FULL)
    low, high = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    control = rng.uniform(low, high, size=(nbatch, nstep, model.nu))
    return state0, control


def stepped_by_hand(model, state0, control):
    """The reference: each rollout stepped from Python on a fresh MjData."""
    nbatch, nstep, _ = control.shape
    states = np.zeros((nbatch, nstep, state0.shape[1]))
    sensors = np.zeros((nbatch, nstep, model.nsensordata))
    for b in range(nbatch):
        data = simlab.MjData(model)
        simlab.mj_setState(model, data, state0[b], FULL)
        for t in range(nstep):
            data.ctrl[:] = control[b, t]
            simlab.mj_step(model, data)
            simlab.mj_getState(model, data, states[b, t], FULL)
            sensors[b, t] = data.sensordata
    return states, sensors


@pytest.mark.parametrize("name", [HUMANOID, "mujoco/test/engine/testdata/sensor/humanoid.xml"])
def test_rollouts_are_identical_whatever_the_thread_count(name):
    model = simlab.MjModel.from_xml_path(str(model_file(name)))
    state0, control = batch(model, nbatch=7, nstep=60)
    reference = stepped_by_hand(model, state0, control)
    for nthread in (0, 1, 2, 3):
        data = [simlab.MjData(model) for _ in range(max(nthread, 1))]
        state, sensordata = simlab.rollout.rollout(model, data, state0, control,
                                                   nthread=nthread, chunk_size=1)
        assert state.shape == (7, 60, state0.shape[1])
        assert np.array_equal(state, reference[0]), nthread
        assert np.array_equal(sensordata, reference[1]), nthread


def test_rollout_tiles_and_checks_its_inputs():
    model = simlab.MjModel.from_xml_path(str(model_file("actuator_bench")))
    data = simlab.MjData(model)
    state0 = np.zeros(simlab.mj_stateSize(model, FULL))
    simlab.mj_getState(model, data, state0, FULL)
    # One initial state, one control row for every step, three steps; and a batch of 4.
    state, _ = simlab.rollout.rollout(model, data, state0, [0.4, 0.5, 1.0, 0.8], nstep=3)
    assert state.shape == (1, 3, state0.size)
    state, _ = simlab.rollout.rollout(model, data, np.tile(state0, (4, 1)),
                                      np.zeros((1, 5, model.nu)))
    assert state.shape == (4, 5, state0.size) and np.all(state[0] == state[3])
    with pytest.raises(ValueError, match="trailing dimension of control"):
        simlab.rollout.rollout(model, data, state0, np.zeros((1, 2, 3)))
    with pytest.raises(ValueError, match="control_spec"):
        simlab.rollout.rollout(model, data, state0, control_spec=int(simlab.mjtState.mjSTATE_QPOS))
    with simlab.rollout.Rollout(nthread=2) as pool:
        a, _ = pool.rollout(model, [data], state0, np.ones((1, 4, model.nu)))
        b, _ = pool.rollout(model, [data], state0, np.ones((1, 4, model.nu)))
        assert np.array_equal(a, b)
    with pytest.raises(RuntimeError, match="closed"):
        pool.rollout(model, [data], state0)
