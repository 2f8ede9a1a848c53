"""The encoders of real pixels: the kitty graphics protocol, sixel and iTerm2 images, each
sending the whole frame as one image (the protocols themselves are ``terminal/kitty.py``,
``terminal/sixel.py`` and ``terminal/iterm.py``).

The image is drawn from the picture's top-left cell over ``columns x rows`` cells. The
lines under it are blank and are written only when the picture's size changes, so a new
frame costs the image alone; while another screen is over the picture, the viewport shows
the frame in half-blocks instead (``Picture.behind``), which that screen's backdrop dims. All three paint over the cells: the viewport writes the image
only while nothing is drawn over the picture, and again when Textual has repainted the
cells under it. Inside tmux, kitty's images are placed by Unicode placeholders instead
(:class:`KittyPlaceholders`), which are the lines; kitty's own placements are used
elsewhere, as the kitty in Debian 12 (0.26) predates placeholders.

A frame may be smaller than the cells it fills (a fraction of the terminal's pixels, for a
slow link): kitty and iTerm2 scale it up to the cells; sixel, which cannot, is always sent
at the terminal's own pixel size, and where that is larger than the terminal takes a sixel
image (xterm's 1000x1000 pixels unless told more, which it answers XTSMGRAPHICS with), the
frame is scaled down to fit and drawn in the middle of its cells.
"""

from __future__ import annotations

import os

import numpy as np
from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from biceps.terminal import iterm, kitty, sixel
from biceps.terminal.cells import SHAPES
from biceps.terminal.choose import Choice
from biceps.tui.encoder import Picture, PictureEncoder
from biceps.tui.halfblocks import HalfBlocks, TextCells


class ImageEncoder:
    """Frames as images over blank lines; subclasses say how a frame becomes an image.

    ``cell``: the frame's pixels per cell (the terminal's cell size, or a fraction of it).
    """

    aspect = 1.0  # the terminal's pixels are square

    def __init__(self, cell: Size) -> None:
        if cell.width < 1 or cell.height < 1:
            raise ValueError(f"a cell must be at least one pixel each way, not {cell}")
        self.cell = cell
        # The style of the lines under the image, the picture's background: where an image
        # is smaller than its cells (sixel), the terminal's own (xterm's white) would show.
        # Set by the viewport; read as the lines are made.
        self.background = Style()
        # The picture in cells, (rows, columns), and the background its lines were made in.
        self._shape: tuple[tuple[int, int], Style] | None = None
        self._strips: list[Strip] = []

    def encode(self, frame: np.ndarray) -> Picture:
        """The picture of ``frame`` ((h, w, 3) uint8, a whole number of cells)."""
        rows, columns = frame.shape[0] // self.cell.height, frame.shape[1] // self.cell.width
        changed = []
        background = self.background
        if self._shape != ((rows, columns), background):
            self._shape = (rows, columns), background
            self._strips = self.lines(columns, rows)
            changed = [(0, rows)]
        return Picture(self._strips, changed, self.image(frame, columns, rows),
                       self.behind(frame, columns, rows))

    def reset(self) -> None:
        self._shape = None

    def lines(self, columns: int, rows: int) -> list[Strip]:
        """The lines under the image: blank, on the background."""
        return [Strip.blank(columns, self.background)] * rows

    def behind(self, frame: np.ndarray, columns: int, rows: int) -> np.ndarray | None:
        """``frame`` at two pixels a cell, one above the other: each the mean of four of
        the half-cell's pixels, a quarter of the way in from each side, which is enough for
        a picture dimmed behind another screen and costs little on every frame."""
        height, width = frame.shape[:2]
        ys = [(np.arange(2 * rows) * 4 + quarter) * height // (8 * rows) for quarter in (1, 3)]
        xs = [(np.arange(columns) * 4 + quarter) * width // (4 * columns) for quarter in (1, 3)]
        total = sum(frame[y[:, None], x].astype(np.uint16) for y in ys for x in xs)
        return ((total + 2) // 4).astype(np.uint8)

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        """Escape sequences drawing ``frame`` from the cursor over ``columns x rows`` cells
        (the viewport saves the cursor before and restores it after)."""
        raise NotImplementedError

    def clear(self) -> str:
        """Escape sequences taking the image off the screen, where the terminal can."""
        return ""


class KittyGraphics(ImageEncoder):
    """Frames as kitty graphics images, one image id for them all."""

    def __init__(self, cell: Size, image_id: int | None = None) -> None:
        super().__init__(cell)
        # Ids are shared by every program in the window: one of this process's own.
        self.image_id = image_id if image_id is not None else 0x4200_0000 | os.getpid()

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        return "".join(kitty.transmit(frame, self.image_id, columns, rows))

    def clear(self) -> str:
        return kitty.delete(self.image_id)


class KittyPlaceholders(ImageEncoder):
    """Frames as kitty graphics images through tmux, placed by Unicode placeholders.

    The image id is the placeholders' colour: one of the 256-colour palette, which tmux
    passes on as it is (a 24-bit one it would round without its RGB feature).
    """

    def __init__(self, cell: Size, image_id: int | None = None) -> None:
        super().__init__(cell)
        self.image_id = image_id if image_id is not None else 16 + os.getpid() % 240
        self._style = Style(color=Color.from_ansi(self.image_id))

    def lines(self, columns: int, rows: int) -> list[Strip]:
        # The diacritics number 297 rows and columns; cells beyond stay blank.
        shown = min(columns, len(kitty.DIACRITICS))
        return [Strip([Segment(kitty.placeholders(row, shown), self._style),
                       Segment(" " * (columns - shown))], columns)
                if row < len(kitty.DIACRITICS) else Strip.blank(columns)
                for row in range(rows)]

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        columns, rows = (min(count, len(kitty.DIACRITICS)) for count in (columns, rows))
        return kitty.through_tmux(kitty.transmit(frame, self.image_id, columns, rows, True))

    def clear(self) -> str:
        return kitty.through_tmux([kitty.delete(self.image_id)])


class Sixel(ImageEncoder):
    """Frames as sixel images of at most ``colours`` colours, at the terminal's pixels, and
    at most ``limit`` (width, height) pixels."""

    def __init__(self, cell: Size, colours: int = sixel.MAX_COLOURS,
                 limit: tuple[int, int] | None = None) -> None:
        super().__init__(cell)
        self.colours = max(2, min(colours, sixel.MAX_COLOURS))
        self.limit = limit

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        frame, moved = sixel.fitted(frame, self.limit, columns, rows, self.cell)
        return moved + sixel.sixel_image(*sixel.quantised(frame, self.colours))


class ItermImages(ImageEncoder):
    """Frames as iTerm2 inline PNG images."""

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        return iterm.inline_image(iterm.png(frame), columns, rows)


def encoder_for(choice: Choice, fraction: float = 1.0) -> PictureEncoder:
    """The encoder for ``choice``, its frames ``fraction`` of the terminal's pixels each
    way (kitty and iTerm2; sixel is always sent whole)."""
    width, height = choice.cell
    scaled = Size(max(1, round(width * fraction)), max(1, round(height * fraction)))
    if choice.graphics == "kitty" and choice.multiplexer == "tmux":
        return KittyPlaceholders(scaled)
    if choice.graphics == "kitty":
        return KittyGraphics(scaled)
    if choice.graphics == "iterm":
        return ItermImages(scaled)
    if choice.graphics == "sixel":
        return Sixel(Size(width, height), choice.colours, choice.sixel_limit)
    if choice.graphics in ("quadrants", "sextants"):
        return TextCells(SHAPES[choice.graphics], terminal_cell=choice.cell)
    return HalfBlocks()
