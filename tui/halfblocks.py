"""Pictures as terminal lines: each cell shows two pixels, one above the other. The first
:class:`~tui.encoder.PictureEncoder`, and the viewport's default.

The upper half block "▀" takes the top pixel as its foreground and the bottom one as its
background. Cells with two equal pixels are written as a plain space on that background,
which leaves the foreground out of the colour codes. Neighbouring cells that look the same
are merged into one segment, so a flat background costs one segment per line.

Kernels pack each cell's two pixels into one number, find the rows that differ from the
last frame and the runs of equal cells in them; Python only turns runs into segments, with
one cached :class:`~rich.style.Style` per cell colour, and each line's terminal text
from the codes cached with it (``tui/prerendered.py``): Textual composes the lines with
whatever is drawn over the picture, and writes the text. For a 256-colour
terminal the frames come already mapped onto the palette (``tui/palette.py``), and each
colour is written as its palette entry.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from biceps.engine.jit import ngjit
from biceps.tui.encoder import Picture
from biceps.tui.prerendered import RESET, PrerenderedStrip, codes

UPPER_HALF = "▀"
BOTTOM = (1 << 24) - 1  # a cell's bottom pixel, as packed below


@ngjit
def pack_cells(frame, cells):
    """Each cell's two pixels as one number: ``top << 24 | bottom``, each ``r << 16 | g << 8 | b``.

    frame: (2 h, w, 3) uint8; cells: (h, w) int64, written.
    """
    height, width = cells.shape
    for y in range(height):
        for x in range(width):
            top, bottom = frame[2 * y, x], frame[2 * y + 1, x]
            cells[y, x] = (
                (np.int64(top[0]) << 40) | (np.int64(top[1]) << 32) | (np.int64(top[2]) << 24)
                | (np.int64(bottom[0]) << 16) | (np.int64(bottom[1]) << 8) | np.int64(bottom[2])
            )  # fmt: skip


@ngjit
def mark_changed_rows(cells, previous, changed):
    """``changed[y]``: whether row ``y`` of ``cells`` differs from that of ``previous``.

    cells, previous: (h, w) int64; changed: (h,) bool, written.
    """
    height, width = cells.shape
    for y in range(height):
        changed[y] = False
        for x in range(width):
            if cells[y, x] != previous[y, x]:
                changed[y] = True
                break


@ngjit
def find_runs(cells, changed, starts, counts):
    """Where the runs of equal cells begin, in each changed row: ``starts[y, :counts[y]]``.

    cells: (h, w) int64; changed: (h,) bool; starts: (h, w) int32 and counts: (h,) int32,
    written (``counts[y]`` is 0 for a row that has not changed).
    """
    height, width = cells.shape
    for y in range(height):
        count = 0
        if changed[y]:
            for x in range(width):
                if x == 0 or cells[y, x] != cells[y, x - 1]:
                    starts[y, count] = x
                    count += 1
        counts[y] = count


class _Colours(dict):
    """One colour per pixel colour, made on first use by ``colour``."""

    def __init__(self, colour: Callable[[int], Color]) -> None:
        super().__init__()
        self._colour = colour

    def __missing__(self, rgb: int) -> Color:
        self[rgb] = colour = self._colour(rgb)
        return colour


class _Styles(dict):
    """One style per cell colour, and the codes Textual writes for it on a terminal of
    ``color_system``, made on first use; ``colour`` makes a pixel's colour.

    A turning model makes a few hundred new cells a frame: their two pixels' colours are
    mostly ones seen before, so those are kept apart, and the style is made with
    ``Style.from_color``, which skips the parsing of ``Style()``: the same style, equal
    and with the same codes, in a tenth of the time.
    """

    def __init__(self, colour: Callable[[int], Color], color_system: str) -> None:
        super().__init__()
        self._colours = _Colours(colour)
        self._color_system = color_system

    def __missing__(self, cell: int) -> tuple[Style, str]:
        top, bottom = cell >> 24, cell & BOTTOM
        colours = self._colours
        style = Style.from_color(None if top == bottom else colours[top], colours[bottom])
        self[cell] = entry = (style, codes(style, self._color_system))
        return entry

    def clear(self) -> None:
        super().clear()
        self._colours.clear()


def rgb_colour(rgb: int) -> Color:
    """The colour ``r << 16 | g << 8 | b``, in 24 bits."""
    return Color.from_rgb(rgb >> 16, (rgb >> 8) & 0xFF, rgb & 0xFF)


def cell_text(cell: int, length: int) -> str:
    """``length`` cells of the packed colour ``cell``: half blocks, or spaces if the two
    halves match."""
    return (" " if cell >> 24 == cell & BOTTOM else UPPER_HALF) * length


class HalfBlocks:
    """Turns frames into lines, making again only the lines that changed.

    Keeps the last frame's cells and lines: not thread-safe, give each thread its own.
    """

    cell = Size(1, 2)

    # Enough for every colour of a few frames; a turning model keeps making new ones.
    MAX_STYLES = 1 << 17

    def __init__(self, colour: Callable[[int], Color] = rgb_colour,
                 color_system: str = "truecolor") -> None:
        """``colour``: how a pixel's colour, ``r << 16 | g << 8 | b``, is written;
        ``color_system``: the terminal's, as a :class:`~rich.console.Console` names it, for
        which each line also carries its text (``tui/prerendered.py``)."""
        self._color_system = color_system
        self._cells = np.zeros((0, 0), np.int64)
        self._previous = np.zeros((0, 0), np.int64)
        self._starts = np.zeros((0, 0), np.int32)  # find_runs' output, kept for the size
        self._counts = np.zeros(0, np.int32)
        self._strips: list[Strip] = []
        self._styles = _Styles(colour, color_system)

    def encode(self, frame: np.ndarray) -> Picture:
        """The lines of ``frame`` ((2 h, w, 3) uint8): h lines of w cells."""
        height, width = frame.shape[0] // 2, frame.shape[1]
        self._cells, self._previous = self._previous, self._cells
        if self._cells.shape != (height, width):
            self._cells = np.empty((height, width), np.int64)
        pack_cells(frame, self._cells)
        changed = np.ones(height, np.bool_)
        if self._previous.shape == self._cells.shape:
            mark_changed_rows(self._cells, self._previous, changed)
        if self._starts.shape != (height, width):
            self._starts = np.empty((height, width), np.int32)
            self._counts = np.empty(height, np.int32)
        starts, counts = self._starts, self._counts
        find_runs(self._cells, changed, starts, counts)
        if len(self._styles) > self.MAX_STYLES:
            self._styles.clear()
        # A frame of another size changes every row, so no old strip is kept from it.
        old = self._strips if len(self._strips) == height else [None] * height
        strips = [
            self._strip(self._cells[y], starts[y, : counts[y]]) if row_changed else strip
            for y, (row_changed, strip) in enumerate(zip(changed.tolist(), old))
        ]
        self._strips = strips
        return Picture(strips, _spans(changed))

    def reset(self) -> None:
        # No cells of the right size to compare with: every row is made again.
        self._cells = np.zeros((0, 0), np.int64)
        self._previous = np.zeros((0, 0), np.int64)
        self._strips = []

    def clear(self) -> str:
        return ""  # the lines are all there is, and Textual writes them

    def _strip(self, cells: np.ndarray, starts: np.ndarray) -> Strip:
        width = len(cells)
        styles = self._styles
        first = starts.tolist()
        ends = first[1:] + [width]
        runs = [(styles[cell], cell_text(cell, end - start))
                for cell, start, end in zip(cells[starts].tolist(), first, ends)]
        return PrerenderedStrip(
            [Segment(text, style) for (style, _), text in runs],
            width,
            "".join([f"{codes}{text}{RESET}" for (_, codes), text in runs]),
            self._color_system,
        )


def _spans(changed: np.ndarray) -> list[tuple[int, int]]:
    """The runs of True in ``changed`` as (first, length)."""
    edges = np.flatnonzero(np.diff(changed.astype(np.int8), prepend=0, append=0))
    return [(start, end - start) for start, end in zip(edges[0::2].tolist(), edges[1::2].tolist())]

