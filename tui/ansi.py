"""Printing a picture to the terminal as half-block pixels, through rich-pixels.

Used by ``biceps snapshot --ansi``: one picture, so rich-pixels' convenience wins over the
viewport's fast path.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from PIL import Image
from rich.console import Console
from rich_pixels import Pixels


def print_picture(render: Callable[[int, int], np.ndarray]) -> None:
    """Render at the terminal's width (two pixels per cell, stacked) and print it."""
    console = Console()
    width = max(console.width, 8)
    # A cell is about twice as tall as wide, so square pixels give cells of 1 x 2 pixels.
    height = max(2 * round(width * 9 / 16 / 2), 2)
    frame = render(width, height)
    image = Image.fromarray(np.ascontiguousarray(frame), "RGB")
    console.print(Pixels.from_image(image))
