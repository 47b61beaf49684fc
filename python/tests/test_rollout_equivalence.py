"""A simulation stepped from Python equals `simlab rollout` of the same model, state and
controls, bit for bit: the same engine, reached through the module's views and calls.

Cases: every case of the conformance lists (tests/conformance/*cases.txt: pendulums,
actuators, tendons, contacts, sensors, solvers...), and the gantry lab's slow lift from
keyframe 0 (tests/models/compose/gantry_lab_slow.csv, 3500 steps)."""
import json
import os
import subprocess

import numpy as np
import pytest

import simlab
from conftest import ROOT

FIELDS = ["qpos", "qvel", "qacc", "act", "ctrl", "actuator_force", "actuator_length",
          "actuator_velocity", "qfrc_actuator", "qfrc_passive", "qfrc_constraint",
          "sensordata", "ten_length", "ten_velocity"]
EVERY = 10


def cases():
    """(id, model, steps, state file or None, control file or None, key or None)."""
    out = []
    for listing in sorted((ROOT / "tests" / "conformance").glob("*cases.txt")):
        lines = [l.split() for l in listing.read_text().splitlines() if l.strip()]
        for words in lines:
            model, _, steps, state = words[:4]
            ctrl = words[4] if len(words) > 4 and words[4] != "-" else None
            # The state column: "-", a JSON file of fields, or "key:K".
            key = int(state[4:]) if state.startswith("key:") else None
            state = None if state == "-" or key is not None else state
            out.append((listing.stem + "/" + words[0].split("/")[-1], model, int(steps), state,
                        ctrl, key))
    out.append(("gantry_lab_slow", "models/gantry_gripper.xml", 3500, None,
                "tests/models/compose/gantry_lab_slow.csv", 0))
    # SIMLAB_TEST_SHARD=k/n: every n-th case from the k-th (ctest runs the shards side by
    # side; see python_tests.cmake)
    shard = os.environ.get("SIMLAB_TEST_SHARD")
    if shard:
        k, n = (int(x) for x in shard.split("/"))
        out = out[k::n]
    return out


def read_controls(path):
    rows = [l for l in (ROOT / path).read_text().splitlines()
            if l.strip() and not l.strip().startswith("#")]
    return [[float(x) for x in row.split(",")] for row in rows]


def command_line_rollout(binary, model, steps, state, ctrl, key):
    args = [str(binary), "rollout", model, "--steps", str(steps), "--every", str(EVERY)]
    if state:
        args += ["--state", state]
    if ctrl:
        args += ["--ctrl", ctrl]
    if key is not None:
        args += ["--key", str(key)]
    out = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, check=True)
    return [json.loads(line) for line in out.stdout.splitlines()[1:]]


def python_rollout(model_path, steps, state, ctrl, key):
    """What the command does, written with the Python API."""
    model = simlab.MjModel.from_xml_path(str(ROOT / model_path))
    data = simlab.MjData(model)
    if key is not None:
        simlab.mj_resetDataKeyframe(model, data, key)
    if state:
        for name, value in json.loads((ROOT / state).read_text()).items():
            if name == "time":
                data.time = value
            else:
                getattr(data, name)[:] = value
    controls = read_controls(ctrl) if ctrl else []

    def record(step):
        row = {"step": step, "time": data.time, "ncon": data.ncon}
        row.update({f: getattr(data, f).tolist() for f in FIELDS})
        return row

    simlab.mj_forward(model, data)
    rows = [record(0)]
    for step in range(1, steps + 1):
        if controls:
            data.ctrl[:] = controls[min(step - 1, len(controls) - 1)]
        simlab.mj_step(model, data)
        if step % EVERY == 0 or step == steps:
            rows.append(record(step))
    return rows


@pytest.mark.parametrize("case", cases(), ids=lambda c: c[0])
def test_python_stepping_equals_the_command_line(simlab_binary, case):
    _, model, steps, state, ctrl, key = case
    expected = command_line_rollout(simlab_binary, model, steps, state, ctrl, key)
    got = python_rollout(model, steps, state, ctrl, key)
    assert len(got) == len(expected)
    for ours, theirs in zip(got, expected):
        for name, value in theirs.items():
            # Same doubles: the JSON holds each with enough digits to read back exactly.
            assert np.array_equal(np.asarray(ours[name]), np.asarray(value)), (
                f"step {theirs['step']}: {name} differs")
