"""What the issue asks of a framed picture, measured on a mask of the arm's pixels."""

from __future__ import annotations

import numpy as np
from textual.strip import Strip


def arm_mask(picture: np.ndarray, background: tuple[int, int, int]) -> np.ndarray:
    """(h, w) bool: the pixels of ``picture`` (h, w, 3) that are not ``background``."""
    return np.any(picture != background, axis=2)


def strips_mask(strips: list[Strip], background: tuple[int, int, int]) -> np.ndarray:
    """(2 h, w) bool: the same for a picture on screen, decoded from half-block lines (a
    space shows its background twice, an upper half block its colour above it)."""
    rows = []
    for strip in strips:
        top, bottom = [], []
        for segment in strip:
            style = segment.style
            below = style.bgcolor.get_truecolor()
            above = style.color.get_truecolor() if style.color is not None else below
            for character in segment.text:
                top.append(tuple(above) if character == "▀" else tuple(below))
                bottom.append(tuple(below))
        rows += [[pixel != tuple(background) for pixel in top],
                 [pixel != tuple(background) for pixel in bottom]]
    return np.array(rows, dtype=bool)


def box(mask: np.ndarray) -> tuple[int, int, int, int]:
    """The first and last row and column of ``mask``'s true pixels."""
    rows, columns = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return rows[0], rows[-1], columns[0], columns[-1]


def assert_fills_the_view(mask: np.ndarray) -> None:
    """The issue's framing: the arm's box spans at least 70 % of the width or the height,
    its centre lies within 10 % of the picture's, and nothing touches the edges."""
    height, width = mask.shape
    top, bottom, left, right = box(mask)
    assert max((bottom - top + 1) / height, (right - left + 1) / width) >= 0.7
    assert abs((top + bottom + 1) / 2 - height / 2) <= 0.1 * height
    assert abs((left + right + 1) / 2 - width / 2) <= 0.1 * width
    assert not (mask[0].any() or mask[-1].any() or mask[:, 0].any() or mask[:, -1].any())
