"""Reading what a person types into a dialog; each parser raises ValueError saying what is wrong."""

from __future__ import annotations

import math
import re
from pathlib import Path

LARGEST_PICTURE_SIDE = 8192  # pixels; beyond this a picture takes gigabytes to render

_SIZE = re.compile(r"^\s*(\d+)\s*[x×X*, ]\s*(\d+)\s*$")


def parse_number(text: str) -> float:
    """A finite decimal number: ``2``, ``0.35``, ``1e-1``."""
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{_shown(text)} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{_shown(text)} is not a finite number")
    return value


def parse_size(text: str) -> tuple[int, int]:
    """A picture size written ``WIDTHxHEIGHT`` in pixels, such as ``1920x1080``."""
    match = _SIZE.match(text)
    if match is None:
        raise ValueError(f"{_shown(text)} is not a size: write it as 1920x1080")
    width, height = int(match[1]), int(match[2])
    for side in (width, height):
        if not 1 <= side <= LARGEST_PICTURE_SIDE:
            raise ValueError(f"each side must be 1 to {LARGEST_PICTURE_SIDE} pixels, not {side}")
    return width, height


def parse_path(text: str) -> Path:
    """A file name, with ``~`` for the home directory."""
    text = text.strip()
    if not text:
        raise ValueError("give a file name")
    path = Path(text).expanduser()
    if path.is_dir():
        raise ValueError(f"{path} is a directory: give a file name")
    return path


def _shown(text: str) -> str:
    return repr(text.strip()) if text.strip() else "nothing"
