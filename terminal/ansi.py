"""Printing a picture to the terminal as half-block cells, two pixels a cell
(``terminal/cells.py``): ``biceps snapshot --ansi``.

The colour codes are written even when the output is not a terminal
(``--ansi`` asks for them: ``| less -R``, ``> arm.ans``), in 24 bits or the 256 colours, as
``colors`` says or the terminal answers (``terminal/detect.py``), never fewer: a picture in 16
colours is no picture. In 256 colours the frame is first mapped onto the palette as a
whole, as the app does (``terminal/palette.py``), and each colour written as its entry. Free of
Textual.
"""

from __future__ import annotations

import shutil
import sys
from typing import Callable

import numpy as np

from biceps.terminal.cells import HALF_BLOCKS, CellRows, palette_text
from biceps.terminal.palette import Palette256, entry_numbers


def print_picture(render: Callable[[int, int], np.ndarray], background: tuple[int, int, int],
                  size: tuple[int, int] | None = None, colors: str = "truecolor") -> None:
    """Render at ``size`` pixels (``width x height``; default: the terminal's width at 16:9)
    and print it, two pixels a cell, stacked. ``background`` is the picture's background
    colour; ``colors`` is ``truecolor`` or ``256``."""
    if size is None:
        width = max(shutil.get_terminal_size().columns, 8)
        # A cell is about twice as tall as wide, so square pixels give cells of 1 x 2 pixels.
        size = width, max(2 * round(width * 9 / 16 / 2), 2)
    width, height = size
    frame = render(width, height + height % 2)  # whole cells
    cells = CellRows(HALF_BLOCKS, exact=colors == "256")
    if colors == "256":
        frame = Palette256().mapped(frame, background)
    changed = cells.fit(np.ascontiguousarray(frame))
    if colors == "256":
        lines = [palette_text(row, HALF_BLOCKS, entry_numbers()) for row in cells.cells]
    else:
        lines = cells.texts(changed)
    sys.stdout.write("".join(f"{line}\n" for line in lines))
    sys.stdout.flush()
