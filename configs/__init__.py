"""The bundled models, installed as package data beside this module.

Kept free of the engine, so that the command line can name the default model without
importing numpy, pydantic or numba.
"""

from importlib.resources import files
from pathlib import Path, PurePath

FOLDER = Path(str(files(__name__)))
"""The folder of the bundled models (installed unzipped, so a real folder)."""

DEFAULT = FOLDER / "biceps.toml"
"""The model the app and every command open when given none."""


def named(word: str) -> Path | None:
    """The bundled model that ``word`` names, or None.

    Installed with pipx, the models are somewhere in site-packages, not beside the person
    typing: ``elbow``, ``elbow.toml`` and ``configs/elbow.toml`` (as README.md writes it)
    each name configs/elbow.toml wherever it was installed.
    """
    path = PurePath(word)
    if path.parent not in (PurePath("."), PurePath("configs")) or path.suffix not in ("", ".toml"):
        return None
    model = FOLDER / f"{path.stem}.toml"
    return model if path.stem and model.is_file() else None


def bundled_names() -> list[str]:
    """The names the bundled models go by (``biceps``, ``elbow``, ...), sorted."""
    return sorted(model.stem for model in FOLDER.glob("*.toml"))


def file_or_bundled(path: Path) -> Path:
    """``path`` if there is such a file or folder, else the bundled model it names, if any
    (a file of that name where one works comes first), else ``path`` (for the reader to say
    there is no such file)."""
    try:
        return path if path.exists() else named(str(path)) or path
    except OSError:  # a name too long to look up, say: the reader refuses it in its words
        return path
