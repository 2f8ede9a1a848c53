"""The bundled models, installed as package data beside this module.

Kept free of the engine, so that the command line can name the default model without
importing numpy, pydantic or numba.
"""

from importlib.resources import files
from pathlib import Path

FOLDER = Path(str(files(__name__)))
"""The folder of the bundled models (installed unzipped, so a real folder)."""

DEFAULT = FOLDER / "biceps.toml"
"""The model the app and every command open when given none."""
