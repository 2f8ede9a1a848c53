"""Pictures as terminal lines: each cell shows two pixels, one above the other.

The upper half block "▀" takes the top pixel as its foreground and the bottom one as its
background. Cells with two equal pixels are written as a plain space on that background,
which sends half the colour codes over the wire. Neighbouring cells that look the same
are merged into one segment, so a flat background costs one segment per line.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.strip import Strip

UPPER_HALF = "▀"


def frame_to_strips(frame: np.ndarray) -> list[Strip]:
    """One strip per pair of pixel rows of ``frame`` ((2 h, w, 3) uint8): h strips of w cells."""
    pixels = frame.astype(np.int64)
    packed = (pixels[..., 0] << 16) | (pixels[..., 1] << 8) | pixels[..., 2]
    # One number per cell: the top pixel's colour in the high bits, the bottom one's below.
    cells = (packed[0::2] << 24) | packed[1::2]
    width = cells.shape[1]
    strips = []
    for row in cells:
        starts = np.flatnonzero(np.diff(row, prepend=-1))
        lengths = np.diff(starts, append=width)
        strips.append(
            Strip(
                [
                    _cell_run(cell, length)
                    for cell, length in zip(row[starts].tolist(), lengths.tolist())
                ],
                width,
            )
        )
    return strips


def _cell_run(cell: int, length: int) -> Segment:
    top, bottom = cell >> 24, cell & 0xFFFFFF
    text = " " if top == bottom else UPPER_HALF
    return Segment(text * length, _style(cell))


@lru_cache(maxsize=65536)
def _style(cell: int) -> Style:
    top, bottom = cell >> 24, cell & 0xFFFFFF
    background = _colour(bottom)
    if top == bottom:
        return Style(bgcolor=background)
    return Style(color=_colour(top), bgcolor=background)


def _colour(rgb: int) -> Color:
    return Color.from_rgb(rgb >> 16, (rgb >> 8) & 0xFF, rgb & 0xFF)
