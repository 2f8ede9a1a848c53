"""Printing a picture to the terminal as half-block pixels, through rich-pixels.

Used by ``biceps snapshot --ansi``: one picture, so rich-pixels' convenience wins over the
viewport's fast path. The colour codes are written even when the output is not a terminal
(``--ansi`` asks for them: ``| less -R``, ``> arm.ans``), in 24 bits or the 256 colours,
as ``colors`` says or the environment does, never fewer: a picture in 16 colours is no
picture. In 256 colours the frame is first mapped onto the palette as a whole, as the app
does (``tui/palette.py``).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from PIL import Image
from rich.console import Console
from rich_pixels import Pixels

from biceps.tui.detect import colour_system
from biceps.tui.palette import Palette256


def print_picture(render: Callable[[int, int], np.ndarray], background: tuple[int, int, int],
                  size: tuple[int, int] | None = None, colors: str = "auto") -> None:
    """Render at ``size`` pixels (``width x height``; default: the terminal's width at 16:9)
    and print it, two pixels a cell, stacked. ``background`` is the picture's background
    colour; ``colors`` is ``auto``, ``truecolor`` or ``256``."""
    if size is None:
        width = max(Console(force_terminal=True).width, 8)
        # A cell is about twice as tall as wide, so square pixels give cells of 1 x 2 pixels.
        size = width, max(2 * round(width * 9 / 16 / 2), 2)
    width, height = size
    console = Console(force_terminal=True, color_system=colour_system(colors),
                      width=width)  # no wrapping
    frame = render(width, height + height % 2)  # whole cells
    if console.color_system == "256":
        frame = Palette256().mapped(frame, background)
    image = Image.fromarray(np.ascontiguousarray(frame), "RGB")
    console.print(Pixels.from_image(image))
