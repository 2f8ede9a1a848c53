"""The seam between the picture and the terminal: an encoder turns each frame into what the
terminal is sent to show it.

The viewport uses encoders through this protocol alone. It asks the renderer for a frame of
its size in cells times the encoder's :attr:`~PictureEncoder.cell`, hands the frame to
:meth:`~PictureEncoder.encode` and shows the :class:`Picture` that comes back: its lines,
repainting only those that changed, then its image, if it has one. Half-blocks
(``tui/halfblocks.py``) are lines alone. An encoder for real pixels (the kitty graphics
protocol, sixel, iTerm2 images) would send the frame as an image, its lines being
placeholders for it, and :meth:`~PictureEncoder.clear` the images it left when the
viewport goes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from textual.geometry import Size
from textual.strip import Strip


@dataclass(frozen=True)
class Picture:
    """What the terminal is sent for one frame."""

    strips: list[Strip]  # one line per row of cells, as wide as the picture
    changed: list[tuple[int, int]]  # the rows to write again: (first row, number of rows)
    # Escape sequences drawing the frame as an image from the cursor, written once the lines
    # are out, with the cursor on the picture's top-left cell; "" for lines alone.
    image: str = ""
    # The frame at two pixels a cell ((2 rows, columns, 3) uint8), for half-block lines to
    # show while the image is hidden under another screen; None where the lines show it.
    behind: np.ndarray | None = None


class PictureEncoder(Protocol):
    """Turns frames into pictures for the terminal.

    :meth:`encode` and :meth:`reset` are called from the viewport's render thread only, so an
    encoder may keep what it sent last and send only what changed; :attr:`cell` and
    :meth:`clear` may be called from any thread.
    """

    @property
    def cell(self) -> Size:
        """The pixels of one cell: a picture of w x h cells is made from a frame of
        ``w * cell.width`` by ``h * cell.height`` pixels."""
        ...

    @property
    def aspect(self) -> float:
        """A pixel's width over its height on the screen, which the frame is drawn for."""
        ...

    def encode(self, frame: np.ndarray) -> Picture:
        """The picture of ``frame`` ((h, w, 3) uint8, a whole number of cells), and what
        changed since the last one."""
        ...

    def reset(self) -> None:
        """Forget what was sent: the next picture is sent whole, every row changed."""
        ...

    def clear(self) -> str:
        """Escape sequences taking off the terminal whatever images were sent (written when
        the viewport goes); "" for lines alone."""
        ...
