"""simlab.lint: the findings of `simlab lint` from Python, for a model loaded from its
file or for a path."""
import pytest

import simlab
from conftest import ROOT, model_file

TRAPS = ROOT / "tests" / "lint_models"


def test_a_weak_servo_is_found_with_its_numbers_and_line():
    model = simlab.MjModel.from_xml_path(str(TRAPS / "weak_servo.xml"))
    findings = simlab.lint(model)
    assert [f["check"] for f in findings] == ["servo-too-weak"]
    found = findings[0]
    assert found["severity"] == "warning"
    assert found["element"] == 'actuator "servo"'
    assert found["line"] == 13 and found["file"].endswith("weak_servo.xml")
    assert "kp 1" in found["numbers"] and "sags 4.905 rad" in found["numbers"]
    assert found["meaning"] and found["advice"]


def test_a_path_and_a_keyframe():
    findings = simlab.lint(str(TRAPS / "key_ctrl.xml"), key=0)
    assert [f["check"] for f in findings] == ["key-ctrl-clamped"]


def test_the_lessons_gantry_is_clean():
    model = simlab.MjModel.from_xml_path(str(model_file("gantry_gripper")))
    assert simlab.lint(model, key=0) == []


def test_a_model_without_its_file_is_a_clear_error():
    model = simlab.MjModel.from_xml_string("<mujoco/>")
    with pytest.raises(ValueError, match="from_xml_path"):
        simlab.lint(model)
    with pytest.raises(ValueError, match="no keyframe 3"):
        simlab.lint(str(TRAPS / "gear.xml"), key=3)
