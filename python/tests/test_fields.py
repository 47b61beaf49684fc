"""Every array of MjModel and MjData: the names and shapes `simlab rollout` lists in its
header (model_fields, data_fields), each a numpy view of the engine's memory; and the
named views' attributes sliced as MuJoCo's bindings slice them."""
import json
import subprocess

import numpy as np
import pytest

import simlab
from conftest import model_file

MODELS = ["actuator_bench", "gantry_gripper", "double_pendulum", "tests/models/ball_joint.xml",
          "mujoco/model/humanoid/humanoid.xml",
          "mujoco/test/engine/testdata/sensor/contact.xml"]


def rollout_header(binary, path):
    out = subprocess.run([str(binary), "rollout", str(path)], capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout.splitlines()[0])


def array_attributes(obj):
    """The numpy-array attributes of an MjModel or MjData, by name."""
    arrays = {}
    for name in dir(obj):
        if name.startswith("_"):
            continue
        value = getattr(obj, name)
        if isinstance(value, np.ndarray):
            arrays[name] = value
    return arrays


@pytest.mark.parametrize("name", MODELS)
def test_every_array_has_the_headers_name_and_shape(simlab_binary, name):
    path = model_file(name)
    header = rollout_header(simlab_binary, path)
    model = simlab.MjModel.from_xml_path(str(path))
    data = simlab.MjData(model)
    for obj, listed in ((model, header["model_fields"]), (data, header["data_fields"])):
        arrays = array_attributes(obj)
        for field, shape in listed.items():
            assert field in arrays, f"{type(obj).__name__}.{field} is missing"
            assert arrays[field].shape == tuple(shape), field
        # The arrays beyond the table: data's energy and the constraint rows (copies).
        extra = set(arrays) - set(listed)
        if obj is model:
            assert not extra, extra
        else:
            assert extra == {"energy"} | {f for f in extra if f.startswith("efc_")}, extra


@pytest.mark.parametrize("name", MODELS)
def test_arrays_view_the_engines_memory(name):
    model = simlab.MjModel.from_xml_path(str(model_file(name)))
    data = simlab.MjData(model)
    for obj in (model, data):
        for field, array in array_attributes(obj).items():
            if field.startswith("efc_") or array.size == 0:
                continue
            # A view of the object's memory: the same address each time, based on the
            # keeper all of the object's views share (not the object itself).
            assert array.base is not obj and array.base is obj.qpos0.base \
                if obj is model else array.base is obj.qpos.base, field
            again = getattr(obj, field)
            assert again.ctypes.data == array.ctypes.data, field
            assert array.flags.writeable, field


def test_joint_views_slice_qpos_and_dofs_by_joint_type():
    model = simlab.MjModel.from_xml_path(str(model_file("mujoco/model/humanoid/humanoid.xml")))
    data = simlab.MjData(model)
    sizes = {int(simlab.mjtJoint.mjJNT_FREE): (7, 6), int(simlab.mjtJoint.mjJNT_BALL): (4, 3),
             int(simlab.mjtJoint.mjJNT_SLIDE): (1, 1), int(simlab.mjtJoint.mjJNT_HINGE): (1, 1)}
    for j in range(model.njnt):
        nq, nv = sizes[int(model.jnt_type[j])]
        view = data.joint(j)
        assert view.qpos.shape == (nq,)
        assert view.qvel.shape == (nv,)
        assert view.cdof.shape == (nv, 6)
        adr = model.jnt_qposadr[j]
        assert np.shares_memory(view.qpos, data.qpos)
        assert view.qpos.ctypes.data == data.qpos[adr:].ctypes.data
        assert model.joint(j).qpos0.shape == (nq,)
        assert model.joint(j).type.shape == (1,)


def test_views_of_every_kind_have_the_tables_attributes():
    model = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    data = simlab.MjData(model)
    assert model.actuator("gripper/grip").gainprm.shape == (10,)
    assert model.body("cube").mass.shape == (1,)
    assert model.geom("cube").size.shape == (3,)
    assert model.tendon("gripper/grip")._range.shape == (2,)  # MuJoCo's name for it
    assert model.key("home").qpos.shape == (model.nq,)
    assert model.keyframe(0).ctrl.shape == (model.nu,)
    assert model.eq(0).data.shape == (11,) and model.equality(0).id == 0
    assert data.actuator("gripper/grip").force.shape == (1,)
    assert data.actuator("gripper/grip").moment.shape == (model.nv,)
    assert data.body("cube").xpos.shape == (3,)
    assert data.geom("cube").xmat.shape == (9,)
    assert data.tendon("gripper/grip").length.shape == (1,)
    assert data.ten("gripper/grip").J.shape == (model.nv,)
    assert data.joint("cube").qpos.shape == (7,)
    assert set(dir(data.actuator(0))) >= {"id", "name", "ctrl", "force", "length",
                                           "velocity", "moment"}
