"""Pictures as terminal lines of text cells (``terminal/cells.py``): half-blocks, two pixels a
cell, one above the other (the viewport's default, in every font), or the finer quadrants
and sextants. The :class:`~tui.encoder.PictureEncoder` of text.

The cells are fitted to the frame, and the rows that changed since the last frame found and
written, by kernels (``terminal/cells.py``), each changed line's terminal text as Textual would
write its segments (``tui/prerendered.py``). A line makes its segments, with one cached
:class:`~rich.style.Style` per cell, only if Textual asks for them (to crop it under a
dialog, say). Textual composes the lines with whatever is drawn over the picture and writes
their text. For a 256-colour terminal the frames come already mapped onto the palette
(``terminal/palette.py``), each colour is written as its palette entry, and the lines' text is
made from codes cached per cell.
"""

from __future__ import annotations

from functools import partial
from typing import Callable

import numpy as np
from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from biceps.terminal.cells import HALF_BLOCKS, CellRows, Shape, runs, unpacked
from biceps.tui.encoder import Picture
from biceps.tui.prerendered import RESET, codes
from biceps.tui.textual_private import text_strip

DEFAULT_CELL = (10, 20)  # a terminal's cell in pixels, when it does not say


class _Made(dict):
    """Values made on first use by ``make``."""

    def __init__(self, make: Callable) -> None:
        super().__init__()
        self._make = make

    def __missing__(self, key):
        self[key] = value = self._make(key)
        return value


def rgb_colour(rgb: int) -> Color:
    """The colour ``r << 16 | g << 8 | b``, in 24 bits."""
    return Color.from_rgb(rgb >> 16, (rgb >> 8) & 0xFF, rgb & 0xFF)


class TextCells:
    """Turns frames into lines of cells of ``shape``, making again only the lines that
    changed.

    Keeps the last frame's cells and lines: not thread-safe, give each thread its own.
    """

    # Enough for every colour of a few frames; a turning model keeps making new ones.
    MAX_STYLES = 1 << 17

    def __init__(self, shape: Shape, colour: Callable[[int], Color] = rgb_colour,
                 color_system: str = "truecolor",
                 terminal_cell: tuple[int, int] = DEFAULT_CELL) -> None:
        """``colour``: how a pixel's colour, ``r << 16 | g << 8 | b``, is written (anything
        but 24-bit: the frames are in a palette's colours, which the cells keep);
        ``color_system``: the terminal's, as a :class:`~rich.console.Console` names it, for
        which each line also carries its text (``tui/prerendered.py``); ``terminal_cell``:
        the terminal's cell in pixels, whose shape makes that of a pixel."""
        self.shape, self._terminal_cell = shape, terminal_cell
        self.cell = Size(shape.columns, shape.rows)
        width, height = terminal_cell
        self.aspect = (width / shape.columns) / (height / shape.rows)
        self._color_system = color_system
        self._rows = CellRows(shape, exact=colour is not rgb_colour)
        self._strips: list[Strip] = []
        # A turning model makes a few hundred new cells a frame: their colours are mostly
        # ones seen before, so those are kept apart, and the style is made with
        # Style.from_color, which skips the parsing of Style(): the same style, equal and
        # with the same codes, for much less work.
        self._colours = _Made(colour)
        self._styles = _Made(self._style)
        self._codes = _Made(lambda cell: codes(self._styles[cell], color_system))
        # The lines' text in 24-bit colour comes from a kernel, the rest from the codes.
        self._written = colour is rgb_colour and color_system == "truecolor"

    def recoloured(self, colour: Callable[[int], Color] = rgb_colour,
                   color_system: str = "truecolor") -> TextCells:
        """A new encoder of the same cells, writing colours with ``colour`` for a terminal
        of ``color_system`` (see __init__)."""
        return TextCells(self.shape, colour, color_system, self._terminal_cell)

    def encode(self, frame: np.ndarray) -> Picture:
        """The lines of ``frame`` ((rows h, columns w, 3) uint8): h lines of w cells."""
        changed = self._rows.fit(frame)
        cells = self._rows.cells
        height = len(cells)
        if len(self._styles) > self.MAX_STYLES:
            for made in (self._colours, self._styles, self._codes):
                made.clear()
        texts = self._rows.texts(changed) if self._written else [None] * height
        # A frame of another size changes every row, so no old strip is kept from it.
        old = self._strips if len(self._strips) == height else [None] * height
        strips = [
            self._strip(cells[y].copy(), text) if row_changed else strip
            for y, (row_changed, strip, text) in enumerate(zip(changed.tolist(), old, texts))
        ]
        self._strips = strips
        return Picture(strips, _spans(changed))

    def reset(self) -> None:
        # No cells of the right size to compare with: every row is made again.
        self._rows.reset()
        self._strips = []

    def clear(self) -> str:
        return ""  # the lines are all there is, and Textual writes them

    def _style(self, cell: int) -> Style:
        fore, back, pattern = unpacked(cell)
        colours = self._colours
        return Style.from_color(colours[fore] if pattern else None, colours[back])

    def _strip(self, cells: np.ndarray, text: str | None) -> Strip:
        """The line of ``cells`` ((w,) int64, kept by the line); ``text``: its terminal
        text, if made already."""
        if text is None:
            codes, glyphs = self._codes, self.shape.glyphs
            text = "".join([f"{codes[cell]}{glyphs[unpacked(cell)[2]] * length}{RESET}"
                            for cell, length in runs(cells)])
        return text_strip(partial(self._segments, cells), len(cells), text, self._color_system)

    def _segments(self, cells: np.ndarray) -> list[Segment]:
        # Made when Textual asks (tui/prerendered.py), on the UI thread: the styles are
        # shared with the render thread, each lookup and store one step under the GIL
        # (two threads missing one colour at once make the same style twice).
        styles, glyphs = self._styles, self.shape.glyphs
        return [Segment(glyphs[unpacked(cell)[2]] * length, styles[cell])
                for cell, length in runs(cells)]


class HalfBlocks(TextCells):
    """Two pixels a cell, one above the other: the default, which every font shows. Its
    pixels are taken to be square (a cell twice as tall as wide), whatever the terminal."""

    def __init__(self, colour: Callable[[int], Color] = rgb_colour,
                 color_system: str = "truecolor") -> None:
        super().__init__(HALF_BLOCKS, colour, color_system)

    def recoloured(self, colour: Callable[[int], Color] = rgb_colour,
                   color_system: str = "truecolor") -> HalfBlocks:
        return HalfBlocks(colour, color_system)


def _spans(changed: np.ndarray) -> list[tuple[int, int]]:
    """The runs of True in ``changed`` as (first, length)."""
    edges = np.flatnonzero(np.diff(changed.astype(np.int8), prepend=0, append=0))
    return [(start, end - start) for start, end in zip(edges[0::2].tolist(), edges[1::2].tolist())]
