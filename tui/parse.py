"""Reading what a person types into a dialog; each parser raises ValueError saying what is wrong.

Picture sizes are read by :func:`engine.export.parse_size`, shared with the command line.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from biceps.engine.errors import FileError, shown
from biceps.engine.files import check_name
from biceps.engine.names import printable
from biceps.tui import visitor


def parse_number(text: str) -> float:
    """A finite decimal number: ``2``, ``0.35``, ``1e-1``."""
    if not text.strip():
        raise ValueError("give a number")
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{shown(text)} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{shown(text)} is not a finite number")
    return value


def parse_path(text: str) -> Path:
    """A file name, with ``~`` for the home directory."""
    text = text.strip()
    if not text:
        raise ValueError("give a file name")
    path = visitor.confined(Path(text))  # under biceps serve, inside the visitor's folder
    try:
        path = path.expanduser()
    except RuntimeError:  # ~someone, and there is no such user
        user = text[1:].split("/", 1)[0]
        raise ValueError(f"there is no user {shown(user)} for ~{printable(user)} to "
                         "stand for") from None
    try:
        check_name(path)
    except FileError as error:
        raise ValueError(str(error)) from None
    if os.path.isdir(path):  # False, not OSError, for a folder that cannot be searched
        raise ValueError(f"{printable(path)} is a directory: give a file name")
    return path
