"""Printing one picture to the terminal in real pixels: ``biceps snapshot --kitty``,
``--sixel`` and ``--iterm``, as ``--ansi`` prints half-blocks (``tui/ansi.py``).

The picture is as wide as the terminal and 16:9, in whole cells of the size the terminal
says (``tui/detect.py``; 10x20 pixels if it does not). Room is made first (as many new
lines as the picture has rows), so that the image never scrolls the screen as it is drawn,
and the cursor ends below it, as after any output. Free of Textual, like ``--ansi``.
"""

from __future__ import annotations

import os
import shutil
import sys
from typing import Callable

import numpy as np

from biceps.tui import detect, iterm, kitty, sixel



def image(protocol: str, frame: np.ndarray, columns: int, rows: int, colours: int) -> str:
    """``frame`` ((h, w, 3) uint8) as an image in ``protocol`` over ``columns x rows``
    cells from the cursor."""
    if protocol == "kitty":
        # An id of this process's own: an id used before would take that picture away.
        return "".join(kitty.transmit(frame, 0x4300_0000 | os.getpid(), columns, rows))
    if protocol == "sixel":
        return sixel.sixel_image(*sixel.quantised(frame, colours))
    return iterm.inline_image(iterm.png(frame), columns, rows)


def print_image(protocol: str, render: Callable[[int, int], np.ndarray],
                size: tuple[int, int] | None = None) -> None:
    """Render a picture across the terminal, or of ``size`` pixels, and print it in
    ``protocol``."""
    answers = detect.ask() if sys.stdout.isatty() else None
    choice = detect.choose(protocol, answers, detect.Place())
    (cell_width, cell_height), colours = choice.cell, choice.colours
    if size is None:
        columns = max(shutil.get_terminal_size().columns, 8)
        rows = max(round(columns * cell_width * 9 / 16 / cell_height), 1)
        size = columns * cell_width, rows * cell_height
    else:  # the cells it covers, the last ones maybe in part
        columns, rows = -(-size[0] // cell_width), -(-size[1] // cell_height)
    frame = render(*size)
    sys.stdout.write("\n" * rows + f"\x1b[{rows}A\x1b7"
                     + image(protocol, frame, columns, rows, colours) + "\x1b8"
                     + f"\x1b[{rows}B\r")
    sys.stdout.flush()
