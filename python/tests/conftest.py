"""Shared setup of simlab's Python tests.

The built package is build/python (or $SIMLAB_BUILD_DIR/python): ctest sets PYTHONPATH to
it; run by hand, this file puts it on sys.path. The tests need Debian's Python with numpy
(/usr/bin/python3 -m pytest python/tests).
"""
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("SIMLAB_BUILD_DIR", ROOT / "build")).resolve()
if str(BUILD / "python") not in sys.path:
    sys.path.insert(0, str(BUILD / "python"))
SHARED = ROOT.parent / "shared"


def subprocess_env():
    """This environment with the package on PYTHONPATH, for scripts run as programs."""
    env = os.environ.copy()
    paths = [str(BUILD / "python")] + [os.path.abspath(p) for p in
                                        env.get("PYTHONPATH", "").split(os.pathsep) if p]
    env["PYTHONPATH"] = os.pathsep.join(paths)
    return env


@pytest.fixture(scope="session")
def simlab_binary():
    """The `simlab` command line of the same build."""
    path = BUILD / "simlab"
    if not path.exists():
        pytest.fail(f"{path} is missing: build the `simlab` target first")
    return path


def model_file(name):
    """A model of the repository (models/NAME.xml) or of MuJoCo's corpus beside it."""
    for candidate in (ROOT / "models" / f"{name}.xml", ROOT / name, SHARED / "corpus" / name):
        if candidate.is_file():
            return candidate
    pytest.fail(f"no model {name}")
