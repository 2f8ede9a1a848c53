"""What the encoders of real pixels share: the kitty graphics protocol, sixel and iTerm2
images (``tui/kitty.py``, ``tui/sixel.py``, ``tui/iterm.py``).

Each sends the whole frame as one image, drawn from the picture's top-left cell over
``columns x rows`` cells, with the cursor left where it was. The lines under the image are
blank and are written only when the picture's size changes, so a new frame costs the image
alone. All three paint over the cells (kitty's Unicode placeholders would not, but the
kitty in Debian 12, 0.26, predates them): the viewport writes the image only when nothing
is drawn over the picture, and again when Textual has repainted the cells under it.

A frame may be smaller than the cells it fills (a fraction of the terminal's pixels, for a
slow link): kitty and iTerm2 scale it up to the cells; sixel, which cannot, is always sent
at the terminal's own pixel size.
"""

from __future__ import annotations

import numpy as np
from textual.geometry import Size
from textual.strip import Strip

from biceps.tui.encoder import Picture


class ImageEncoder:
    """Frames as images over blank lines; subclasses say how a frame becomes an image.

    ``cell``: the frame's pixels per cell (the terminal's cell size, or a fraction of it).
    """

    def __init__(self, cell: Size) -> None:
        if cell.width < 1 or cell.height < 1:
            raise ValueError(f"a cell must be at least one pixel each way, not {cell}")
        self.cell = cell
        self._shape: tuple[int, int] | None = None  # the picture in cells: (rows, columns)
        self._strips: list[Strip] = []

    def encode(self, frame: np.ndarray) -> Picture:
        """The picture of ``frame`` ((h, w, 3) uint8, a whole number of cells)."""
        rows, columns = frame.shape[0] // self.cell.height, frame.shape[1] // self.cell.width
        changed = []
        if self._shape != (rows, columns):
            self._shape = rows, columns
            self._strips = [Strip.blank(columns)] * rows
            changed = [(0, rows)]
        return Picture(self._strips, changed, self.image(frame, columns, rows))

    def reset(self) -> None:
        self._shape = None

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        """Escape sequences drawing ``frame`` from the cursor over ``columns x rows`` cells
        (the viewport saves the cursor before and restores it after)."""
        raise NotImplementedError

    def clear(self) -> str:
        """Escape sequences taking the image off the screen, where the terminal can."""
        return ""
