"""Bad names, indices, files and arguments raise clear Python errors, never crash."""
import numpy as np
import pytest

import simlab
import simlab.rollout
from conftest import model_file


@pytest.fixture
def gantry():
    model = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    return model, simlab.MjData(model)


def test_unknown_names_raise_key_error_naming_them(gantry):
    model, data = gantry
    with pytest.raises(KeyError, match="Invalid name 'gripper/nope'. Valid names: "
                                       r"\['gripper/grip', 'x', 'y', 'z'\]"):
        model.actuator("gripper/nope")
    with pytest.raises(KeyError, match="'nobody'"):
        data.body("nobody")
    with pytest.raises(KeyError):
        model.joint()  # the default name "" names nothing
    assert simlab.mj_name2id(model, simlab.mjtObj.mjOBJ_BODY, "nobody") == -1
    assert simlab.mj_id2name(model, simlab.mjtObj.mjOBJ_BODY, 99) is None


def test_indices_out_of_range_raise_index_error(gantry):
    model, data = gantry
    with pytest.raises(IndexError, match=r"Invalid index 4\. Valid indices from 0 to 3"):
        model.actuator(4)
    with pytest.raises(IndexError, match="Invalid index -1"):
        data.joint(-1)
    with pytest.raises(IndexError):
        data.contact[0]  # no contact before the first forward
    with pytest.raises(IndexError):
        simlab.mj_jacBody(model, data, np.zeros((3, model.nv)), None, model.nbody)
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        model.actuator(0).nonsense
    with pytest.raises(AttributeError):
        data.actuator(0).id = 3


def test_bad_models_raise_value_error_with_file_and_line(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text('<mujoco>\n  <worldbody>\n    <geom type="sphere" size="-1"/>\n'
                   '  </worldbody>\n</mujoco>\n')
    with pytest.raises(ValueError, match=r"bad\.xml:3: <geom>: size\[0\] must be positive"):
        simlab.MjModel.from_xml_path(str(bad))
    with pytest.raises(ValueError, match="cannot open"):
        simlab.MjModel.from_xml_path(str(tmp_path / "missing.xml"))
    with pytest.raises(ValueError, match="malformed XML"):
        simlab.MjModel.from_xml_string("<mujoco><worldbody>")
    with pytest.raises(ValueError, match="no asset has that file name"):
        simlab.MjModel.from_xml_string('<mujoco><include file="parts.xml"/></mujoco>',
                                       assets={"other.xml": b"<mujoco/>"})
    with pytest.raises(simlab.FatalError, match="mj_resetDataKeyframe: "):
        simlab.mj_resetDataKeyframe(*_bench(), 5)
    with pytest.raises(simlab.FatalError,
                       match=r"mj_stateSize: invalid state signature 16384 >= 2\^mjNSTATE"):
        simlab.mj_stateSize(_bench()[0], 1 << 14)


def _bench():
    model = simlab.MjModel.from_xml_path(str(model_file("actuator_bench")))
    return model, simlab.MjData(model)


def test_bad_arrays_raise_type_error(gantry):
    model, data = gantry
    simlab.mj_forward(model, data)
    with pytest.raises(TypeError, match="jacp must have"):
        simlab.mj_jacBody(model, data, np.zeros((3, 2)), None, 1)
    with pytest.raises(TypeError, match="dtype"):
        simlab.mj_jacBody(model, data, np.zeros((3, model.nv), dtype=np.float32), None, 1)
    with pytest.raises(TypeError, match="C-contiguous"):
        simlab.mj_jacBody(model, data, np.zeros((model.nv, 3)).T, None, 1)
    with pytest.raises(TypeError, match="point must have 3"):
        simlab.mj_jac(model, data, None, None, [1.0, 2.0], 1)
    with pytest.raises(ValueError, match="could not broadcast"):
        data.qpos[:] = np.zeros(3)  # numpy's own broadcast error
    with pytest.raises(ValueError):
        data.qpos = np.zeros(model.nq + 1)
    with pytest.raises(TypeError):
        model.actuator(1.5)


def test_data_of_another_model_is_refused(gantry):
    model, data = gantry
    other, _ = _bench()
    with pytest.raises(ValueError, match="other sizes"):
        simlab.mj_step(other, data)
    # A second MjModel of the same file is compatible, as in MuJoCo.
    twin = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    simlab.mj_step(twin, data)


def test_options_that_do_not_exist_raise_fatal_error_not_a_crash():
    model, data = _bench()
    model.opt.solver = 10
    with pytest.raises(simlab.FatalError, match="mj_step: unknown solver type 10"):
        simlab.mj_step(model, data)
    with pytest.raises(simlab.FatalError, match="mj_forward: unknown solver type 10"):
        simlab.mj_forward(model, data)
    full = int(simlab.mjtState.mjSTATE_FULLPHYSICS)
    state = np.zeros((4, simlab.mj_stateSize(model, full)))
    # On a pool thread the error reaches the caller too.
    for nthread in (0, 2):
        with pytest.raises(simlab.FatalError, match="rollout: unknown solver type 10"):
            simlab.rollout.rollout(model, [simlab.MjData(model) for _ in range(max(nthread, 1))],
                                   state, np.zeros((4, 3, model.nu)), nthread=nthread)
    model.opt.solver = int(simlab.mjtSolver.mjSOL_NEWTON)
    model.opt.integrator = -1
    with pytest.raises(simlab.FatalError, match="unknown integrator -1"):
        simlab.mj_step(model, data)
    model.opt.integrator = 0
    simlab.mj_step(model, data)  # usable again
