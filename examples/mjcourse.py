"""The course helper the lesson scripts import: where the course's models are.

    from mjcourse import model_path
    model_path("gantry_gripper")   # -> <repository>/models/gantry_gripper.xml

The scripts in examples/ find this file beside them (Python puts a script's folder on
sys.path); the models are in the repository's models/ folder, or in the folder named by
the environment variable MJCOURSE_MODELS.
"""
import os
from pathlib import Path

__all__ = ["model_path", "models_dir"]


def models_dir() -> Path:
    """The folder of the course's models."""
    override = os.environ.get("MJCOURSE_MODELS")
    return Path(override) if override else Path(__file__).resolve().parent.parent / "models"


def model_path(name: str) -> Path:
    """The path of the model `name` ("gantry_gripper" or "gantry_gripper.xml")."""
    path = models_dir() / (name if name.endswith(".xml") else name + ".xml")
    if not path.is_file():
        known = sorted(p.stem for p in models_dir().glob("*.xml"))
        raise FileNotFoundError(f"no course model named {name!r} in {models_dir()} "
                                f"(there are: {', '.join(known)})")
    return path
