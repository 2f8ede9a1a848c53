"""Printing one picture to the terminal in real pixels: ``biceps snapshot --kitty``,
``--sixel`` and ``--iterm``, as ``--ansi`` prints text cells (``terminal/ansi.py``).

The picture fits the window: as wide as the terminal at 16:9, or, where that would be taller
than the window (less a line for the prompt after it), as tall as the window, in whole cells
of the size the terminal says (``terminal/detect.py``; 10x20 pixels if it does not). A sixel
image is kept within the size the terminal takes (xterm's 1000x1000 pixels unless told
more). Room is made first (as many new lines as the picture has rows), so that the image
never scrolls the screen as it is drawn, and the cursor ends below it, as after any output.
Inside tmux a kitty image goes through tmux's passthrough, placed by Unicode placeholders,
as the app's do. A terminal that answers without the protocol is told so, in words, rather
than given a blank. Free of Textual, like ``--ansi``.
"""

from __future__ import annotations

import os
import shutil
import sys
from typing import Callable

import numpy as np

from biceps.engine.errors import BicepsError
from biceps.terminal import choose, detect, iterm, kitty, sixel


def image(protocol: str, frame: np.ndarray, columns: int, rows: int, choice: choose.Choice
          ) -> str:
    """``frame`` ((h, w, 3) uint8) as an image in ``protocol`` over ``columns x rows``
    cells from the cursor."""
    if protocol == "kitty" and choice.multiplexer == "tmux":
        # An id of this process's own, in the palette, the placeholders' colour.
        image_id = 16 + os.getpid() % 240
        columns, rows = (min(count, len(kitty.DIACRITICS)) for count in (columns, rows))
        commands = kitty.transmit(frame, image_id, columns, rows, virtual=True)
        lines = "\r\n".join(f"\x1b[38;5;{image_id}m{kitty.placeholders(row, columns)}\x1b[0m"
                            for row in range(rows))
        return kitty.through_tmux(commands) + lines
    if protocol == "kitty":
        # An id of this process's own: an id used before would take that picture away.
        return "".join(kitty.transmit(frame, 0x4300_0000 | os.getpid(), columns, rows))
    if protocol == "sixel":
        frame, moved = sixel.fitted(frame, choice.sixel_limit, columns, rows, choice.cell)
        return moved + sixel.sixel_image(*sixel.quantised(frame, choice.colours))
    return iterm.inline_image(iterm.png(frame), columns, rows)


def print_image(protocol: str, render: Callable[[int, int], np.ndarray],
                size: tuple[int, int] | None = None) -> None:
    """Render a picture that fits the window, or of ``size`` pixels, and print it in
    ``protocol``; refuse, saying why, where the terminal answers that it cannot show it."""
    choice = choose.choose(protocol, terminal_answers(), detect.Place.here())
    if choice.graphics != protocol:
        why = choice.reason.removesuffix(": half-blocks")
        raise BicepsError(f"cannot print --{protocol} here: {why}{_instead(choice)}")
    cell_width, cell_height = choice.cell
    if size is None:
        columns, lines = shutil.get_terminal_size()
        columns, room = max(columns, 8), max(lines - 1, 1)
        rows = max(round(columns * cell_width * 9 / 16 / cell_height), 1)
        if rows > room:  # taller than the window: as tall as it instead
            rows = room
            columns = min(columns, max(round(rows * cell_height * 16 / 9 / cell_width), 1))
        size = columns * cell_width, rows * cell_height
    else:  # the cells it covers, the last ones maybe in part
        columns, rows = -(-size[0] // cell_width), -(-size[1] // cell_height)
    frame = render(*size)
    sys.stdout.write("\n" * rows + f"\x1b[{rows}A\x1b7"
                     + image(protocol, frame, columns, rows, choice) + "\x1b8"
                     + f"\x1b[{rows}B\r")
    sys.stdout.flush()


def terminal_answers() -> detect.Answers | None:
    """What the terminal the picture goes to answers; None if it goes elsewhere (a file)."""
    return detect.ask() if sys.stdout.isatty() else None


def _instead(choice: choose.Choice) -> str:
    if choice.could:
        return f"; it has --{choice.could}"
    return "; --ansi prints the picture in text, which every terminal shows"
