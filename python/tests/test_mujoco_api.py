"""simlab's Python module against MuJoCo's own numbers.

Each script in mujoco_api/ is a MuJoCo Python program whose only change is its import
line (`import simlab as mujoco`); it prints one JSON object. mujoco_api/goldens/NAME.json
is what the same computation gives with MuJoCo 3.5.1 (made by mujoco_api/make_goldens.mjs,
committed, so these tests never need MuJoCo). Each script is one test: it is run with this
interpreter and environment (so PYTHONPATH must reach the built module), and every key
of the JSON object on its last output line is compared with the golden:

- strings, booleans, None and integers exactly (an integer printed by the script must be
  an integer in the golden: ids, sizes, counts, addresses);
- floats with |a - b| <= tol * max(1, |b|), tol = 1e-9 unless the script is listed in
  TOLERANCE below;
- dicts key for key (no key missing or extra), lists element for element (same length,
  so numpy shapes must agree too).

Run: PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests/test_mujoco_api.py
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import subprocess_env

HERE = Path(__file__).resolve().parent
SCRIPTS_DIR = HERE / "mujoco_api"
GOLDENS_DIR = SCRIPTS_DIR / "goldens"
SCRIPTS = sorted(p.stem for p in SCRIPTS_DIR.glob("*.py"))

DEFAULT_TOL = 1e-9

# A looser tolerance only where contacts make it necessary. The constraint solver stops
# iterating once its improvement falls below opt.tolerance (1e-8), so a last-bit
# difference in a contact-rich step can end the iterations one step earlier or later and
# move the constraint forces, and from them the state, by up to about that tolerance.
# Measured with `simlab rollout` against the oracle on the same schedules: the falling
# humanoid's qfrc_constraint differs by 3.2e-9 (relative) after 153 steps (qvel 2.7e-11),
# so humanoid_state gets 1e-8, the tolerance of the C++ conformance suite's contact cases
# (tests/conformance/contact_cases.txt). The other contact scripts agree to 1e-13 (contacts)
# and bit for bit (gripper), so they keep 1e-9.
TOLERANCE = {
    "humanoid_state": 1e-8,  # a falling humanoid, up to 9 contacts, 300 steps
}

MAX_REPORTED = 12


def _environment():
    """This process's environment with the built package on PYTHONPATH (conftest)."""
    return subprocess_env()


def _import_check():
    """The reason simlab cannot be imported by the interpreter the scripts run with."""
    probe = subprocess.run([sys.executable, "-c", "import simlab"], capture_output=True,
                           text=True, env=_environment(), timeout=120)
    if probe.returncode == 0:
        return None
    return probe.stderr.strip().splitlines()[-1] if probe.stderr.strip() else "unknown error"


_IMPORT_ERROR = []


def _simlab_import_error():
    if not _IMPORT_ERROR:
        _IMPORT_ERROR.append(_import_check())
    return _IMPORT_ERROR[0]


class Comparison:
    """Walks the script's output beside the golden and collects every disagreement."""

    def __init__(self, tol):
        self.tol = tol
        self.mismatches = []
        self.worst = (0.0, None, None, None)  # (error / allowed, path, got, expected)
        self.nfloats = 0

    def fail(self, path, message):
        self.mismatches.append(f"{path or '(top level)'}: {message}")

    def compare(self, path, got, expected):
        if isinstance(expected, dict):
            if not isinstance(got, dict):
                return self.fail(path, f"expected an object, got {type(got).__name__}")
            missing = sorted(set(expected) - set(got))
            extra = sorted(set(got) - set(expected))
            if missing:
                self.fail(path, f"missing keys {missing}")
            if extra:
                self.fail(path, f"unexpected keys {extra}")
            for key in expected:
                if key in got:
                    self.compare(f"{path}.{key}" if path else key, got[key], expected[key])
        elif isinstance(expected, list):
            if not isinstance(got, list):
                return self.fail(path, f"expected a list of {len(expected)}, got {got!r:.80}")
            if len(got) != len(expected):
                return self.fail(path, f"length {len(got)}, expected {len(expected)}")
            for i, (g, e) in enumerate(zip(got, expected)):
                self.compare(f"{path}[{i}]", g, e)
        elif expected is None or isinstance(expected, (str, bool)) or isinstance(got, (str, bool)):
            if got is not expected and not (type(got) is type(expected) and got == expected):
                self.fail(path, f"got {got!r}, expected {expected!r}")
        elif isinstance(got, int):
            # An integer from the script (an id, a size, a count) must be exact.
            if not (isinstance(expected, int) or float(expected).is_integer()) or got != expected:
                self.fail(path, f"got {got}, expected {expected}")
        elif isinstance(got, float) and isinstance(expected, (int, float)):
            self.nfloats += 1
            allowed = self.tol * max(1.0, abs(expected))
            if not math.isfinite(got):
                return self.fail(path, f"got {got}, expected {expected!r}")
            err = abs(got - expected)
            if err / allowed > self.worst[0]:
                self.worst = (err / allowed, path, got, expected)
            if err > allowed:
                self.fail(path, f"got {got!r}, expected {expected!r} (|diff| {err:.3e} > {allowed:.1e})")
        else:
            self.fail(path, f"got {got!r} ({type(got).__name__}), expected {expected!r}")

    def report(self, name):
        lines = [f"{name}: {len(self.mismatches)} disagreement(s) with MuJoCo 3.5.1 "
                 f"(float tolerance {self.tol:g} * max(1, |expected|))"]
        lines += self.mismatches[:MAX_REPORTED]
        if len(self.mismatches) > MAX_REPORTED:
            lines.append(f"... and {len(self.mismatches) - MAX_REPORTED} more")
        ratio, path, got, expected = self.worst
        if path is not None:
            lines.append(f"worst float: {path}: got {got!r}, expected {expected!r} "
                         f"({ratio:.3g} x the allowed error)")
        return "\n".join(lines)


@pytest.mark.parametrize("name", SCRIPTS)
def test_script_matches_mujoco(name, tmp_path):
    error = _simlab_import_error()
    if error is not None:
        pytest.fail(f"cannot import simlab with {sys.executable} ({error}); build the module "
                    f"and put it on PYTHONPATH, e.g. PYTHONPATH=build/python", pytrace=False)

    golden_file = GOLDENS_DIR / f"{name}.json"
    assert golden_file.exists(), (f"no golden {golden_file}; run "
                                  f"node python/tests/mujoco_api/make_goldens.mjs {name}")
    expected = json.loads(golden_file.read_text())

    # Run in a scratch folder: MuJoCo's default warning handler appends to MUJOCO_LOG.TXT
    # in the working directory (and prints "WARNING: ..." to stdout, so the JSON object is
    # taken from the last line).
    run = subprocess.run([sys.executable, str(SCRIPTS_DIR / f"{name}.py")],
                         capture_output=True, text=True, env=_environment(),
                         cwd=tmp_path, timeout=600)
    if run.returncode != 0:
        pytest.fail(f"{name}.py exited with {run.returncode}:\n{run.stderr[-4000:]}",
                    pytrace=False)
    lines = run.stdout.strip().splitlines()
    try:
        got = json.loads(lines[-1])
        assert isinstance(got, dict)
    except (IndexError, AssertionError, json.JSONDecodeError) as e:
        pytest.fail(f"{name}.py did not end its output with one JSON object ({e!r}):\n"
                    f"{run.stdout[:2000]}", pytrace=False)

    comparison = Comparison(TOLERANCE.get(name, DEFAULT_TOL))
    comparison.compare("", got, expected)
    if comparison.mismatches:
        pytest.fail(comparison.report(name), pytrace=False)


def test_every_script_has_a_golden():
    """A script without a golden (or a golden without a script) is a mistake."""
    goldens = sorted(p.stem for p in GOLDENS_DIR.glob("*.json"))
    assert goldens == SCRIPTS
