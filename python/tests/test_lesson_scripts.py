"""The lesson's Python programs on simlab: examples/l2_3_actuators.py (the lesson's script
with its import line changed) prints the lesson's output digit for digit, and the two
exercises' scripts show what the exercises ask."""
import re
import subprocess
import sys

import pytest

from conftest import BUILD, ROOT, SHARED, subprocess_env

LESSON = SHARED / "lesson" / "lesson-2.3-actuators.txt"


def run_example(name):
    """Runs examples/NAME.py as a student would (from another folder); its output."""
    out = subprocess.run([sys.executable, str(ROOT / "examples" / name)], cwd="/",
                         capture_output=True, text=True, env=subprocess_env(), timeout=300)
    assert out.returncode == 0, out.stderr + out.stdout
    return out.stdout


def lesson_output():
    """The printed output in the lesson's text: the block after "```text"."""
    lines = LESSON.read_text().splitlines()
    start = lines.index("```text") + 1
    end = next(i for i in range(start, len(lines)) if lines[i].startswith("Three things"))
    return lines[start:end]


def collapse(line):
    return " ".join(line.split())


def test_the_lessons_script_prints_the_lessons_output():
    printed = run_example("l2_3_actuators.py").splitlines()
    # The lesson's text lost its runs of spaces: compare words and numbers.
    assert [collapse(l) for l in printed] == lesson_output()
    # The exact layout (f-string widths, numpy's padding) is the C++ example's, which
    # tests/lesson_example_test.cc checks against the Python format specifications.
    cpp = subprocess.run([str(BUILD / "l2_3_actuators")], capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert printed == cpp


def test_the_script_differs_from_the_lessons_by_its_import_line_only():
    script = (ROOT / "examples" / "l2_3_actuators.py").read_text()
    assert "import simlab as mujoco\n" in script and "import mujoco\n" not in script
    assert "from mjcourse import model_path" in script


def test_exercise_general_equals_position():
    out = run_example("l2_3_exercise_general.py")
    assert "trajectories identical over 2500 steps: True (largest difference 0)" in out
    params = re.findall(r"gainprm\[0\] (\d+), biastype (\d), biasprm\[0:3\] (.*)", out)
    assert len(params) == 2 and params[0] == params[1] == ("500", "1", "[   0. -500.  -10.]")
    # The cube was lifted, in both models alike.
    lifted = re.search(r"t = 5.0 s: cube z (\S+) m \(position\) (\S+) m", out)
    assert float(lifted.group(1)) > 0.2 and lifted.group(1) == lifted.group(2)


def test_exercise_force_sensor_rises_by_the_cubes_weight():
    out = run_example("l2_3_exercise_force_sensor.py")
    rise = float(re.search(r"rise (\S+) N", out).group(1))
    assert rise == pytest.approx(0.08 * 9.81, rel=0.02)
    # It names the subtree and the frame it measures.
    text = " ".join(out.split())
    assert "subtree rooted at the carriage" in text and "site's frame" in text
