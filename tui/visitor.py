"""A visitor's files under ``biceps serve``: its own scratch folder, and nothing else.

A visitor's process works in a folder of its own, where what it exports, saves or records is
written before the browser downloads it, and where the server puts the models it uploads
(``biceps/uploads.py``). Every file name it types is taken inside that
folder: an absolute name, ``~``, ``..`` or a symbolic link leading out of it is refused; a
bundled model is still opened by its name. Set once, at the visitor's entry point (``biceps
visit``), for the whole process, which serves one visitor only.
"""

from __future__ import annotations

import os
from pathlib import Path

from biceps.engine.names import printable

_folder: Path | None = None


def confine_to(folder: Path) -> None:
    """Take every file name the app is given inside ``folder`` from now on, and work there."""
    global _folder
    _folder = folder.resolve()
    os.chdir(_folder)


def folder() -> Path | None:
    """The folder file names are confined to, or None outside ``biceps serve``."""
    return _folder


def confined(path: Path) -> Path:
    """``path`` as the visitor may use it, relative to the folder; raises ValueError with
    the reason for a name that leads out of it. Outside ``biceps serve``, ``path`` as it is."""
    if _folder is None:
        return path
    text = str(path)
    if path.is_absolute() or text.startswith("~"):
        raise ValueError(f"{printable(text)}: give a name in your own folder, not a path on "
                         "the server")
    if ".." in path.parts:
        raise ValueError(f"{printable(text)}: '..' leads out of your own folder")
    if not (_folder / path).resolve().is_relative_to(_folder):
        raise ValueError(f"{printable(text)} is a link that leads out of your own folder")
    return path


def models_in(folder: Path) -> list[str]:
    """The names of the models (``*.toml`` files, not hidden, not links) in ``folder``,
    sorted."""
    return sorted(entry.name for entry in folder.iterdir()
                  if entry.suffix.lower() == ".toml" and not entry.name.startswith(".")
                  and entry.is_file() and not entry.is_symlink())


def models() -> list[str]:
    """The models in the visitor's folder, uploaded or saved there; none outside
    ``biceps serve``."""
    return [] if _folder is None else models_in(_folder)
