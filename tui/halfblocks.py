"""Pictures as terminal lines: each cell shows two pixels, one above the other. The first
:class:`~tui.encoder.PictureEncoder`, and the viewport's default.

The upper half block "▀" takes the top pixel as its foreground and the bottom one as its
background. Cells with two equal pixels are written as a plain space on that background,
which leaves the foreground out of the colour codes. Neighbouring cells that look the same
are merged into one segment, so a flat background costs one segment per line.

Kernels pack each cell's two pixels into one number, find the rows that differ from the
last frame and the runs of equal cells in them, and write each changed line's terminal text
as Textual would write its segments (``tui/prerendered.py``). A line makes its segments,
with one cached :class:`~rich.style.Style` per cell colour, only if Textual asks for them
(to crop it under a dialog, say). Textual composes the lines with whatever is drawn over
the picture and writes their text. For a 256-colour terminal the frames come already
mapped onto the palette (``tui/palette.py``), each colour is written as its palette entry,
and the lines' text is made from codes cached per cell colour.
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

from biceps.engine.jit import ngjit
from biceps.tui.encoder import Picture
from biceps.tui.prerendered import RESET, PrerenderedStrip, codes
from biceps.tui.sgr import RGB, put_colour

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


# The longest run's codes: CSI 38;2;255;255;255;48;2;255;255;255 m ... CSI 0 m.
MOST_CODES = len("\x1b[38;2;255;255;255;48;2;255;255;255m\x1b[0m")
HALF_UTF8 = np.frombuffer(UPPER_HALF.encode(), np.uint8)


@ngjit
def write_lines(cells, changed, starts, counts, half, out, ends):
    """The text of each changed row as Textual writes its runs in 24-bit colour (the codes
    of ``Strip.render_ansi`` between ``CSI`` and ``m``, the cells, ``CSI 0 m``).

    cells: (h, w) int64; changed, starts, counts: as from find_runs; half: the UTF-8 bytes
    of UPPER_HALF; out: (h * (w * 3 + counts.max() * MOST_CODES),) uint8 or more, written;
    ends: (h,) int64, written: row y's text is ``out[ends[y - 1]:ends[y]]`` (empty for a
    row that has not changed).
    """
    height, width = cells.shape
    at = 0
    for y in range(height):
        if changed[y]:
            for run in range(counts[y]):
                start = starts[y, run]
                end = starts[y, run + 1] if run + 1 < counts[y] else width
                top, bottom = cells[y, start] >> 24, cells[y, start] & BOTTOM
                out[at], out[at + 1] = 27, 91  # ESC [
                at += 2
                if top != bottom:
                    at = put_colour(out, at, RGB | top, True)
                    out[at] = 59  # ;
                    at += 1
                at = put_colour(out, at, RGB | bottom, False)
                out[at] = 109  # m
                at += 1
                for _ in range(end - start):
                    if top != bottom:
                        for byte in range(len(half)):
                            out[at + byte] = half[byte]
                        at += len(half)
                    else:
                        out[at] = 32  # a space
                        at += 1
                out[at], out[at + 1], out[at + 2], out[at + 3] = 27, 91, 48, 109  # ESC [ 0 m
                at += 4
        ends[y] = at


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
        # A turning model makes a few hundred new cells a frame: their two pixels' colours
        # are mostly ones seen before, so those are kept apart, and the style is made with
        # Style.from_color, which skips the parsing of Style(): the same style, equal and
        # with the same codes, in a tenth of the time.
        self._colours = _Made(colour)
        self._styles = _Made(self._style)
        self._codes = _Made(lambda cell: codes(self._styles[cell], color_system))
        # The lines' text in 24-bit colour comes from a kernel, the rest from the codes.
        self._written = colour is rgb_colour and color_system == "truecolor"
        self._text = np.zeros(0, np.uint8)
        self._text_ends = np.zeros(0, np.int64)

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
            for made in (self._colours, self._styles, self._codes):
                made.clear()
        texts = self._texts(changed) if self._written else [None] * height
        # A frame of another size changes every row, so no old strip is kept from it.
        old = self._strips if len(self._strips) == height else [None] * height
        strips = [
            self._strip(self._cells[y].copy(), text) if row_changed else strip
            for y, (row_changed, strip, text) in enumerate(zip(changed.tolist(), old, texts))
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

    def _style(self, cell: int) -> Style:
        top, bottom = cell >> 24, cell & BOTTOM
        colours = self._colours
        return Style.from_color(None if top == bottom else colours[top], colours[bottom])

    def _texts(self, changed: np.ndarray) -> list[str | None]:
        """The text of each changed row (None for the others), from write_lines."""
        cells, counts = self._cells, self._counts
        height, width = cells.shape
        size = height * (width * len(HALF_UTF8) + int(counts.max(initial=0)) * MOST_CODES)
        if len(self._text) < size:
            self._text = np.empty(size, np.uint8)
        if len(self._text_ends) != height:
            self._text_ends = np.empty(height, np.int64)
        write_lines(cells, changed, self._starts, counts, HALF_UTF8, self._text,
                    self._text_ends)
        text, ends = self._text, self._text_ends.tolist()
        return [text[start:end].tobytes().decode() if row_changed else None
                for row_changed, start, end in zip(changed.tolist(), [0, *ends], ends)]

    def _strip(self, cells: np.ndarray, text: str | None) -> Strip:
        """The line of ``cells`` ((w,) int64, kept by the line); ``text``: its terminal
        text, if made already."""
        if text is None:
            codes = self._codes
            text = "".join([f"{codes[cell]}{cell_text(cell, length)}{RESET}"
                            for cell, length in _runs(cells)])
        return PrerenderedStrip(partial(self._segments, cells), len(cells), text,
                                self._color_system)

    def _segments(self, cells: np.ndarray) -> list[Segment]:
        # Made when Textual asks (tui/prerendered.py), on the UI thread: the styles are
        # shared with the render thread, each lookup and store one step under the GIL
        # (two threads missing one colour at once make the same style twice).
        styles = self._styles
        return [Segment(cell_text(cell, length), styles[cell]) for cell, length in _runs(cells)]


def _runs(cells: np.ndarray) -> list[tuple[int, int]]:
    """The runs of equal cells in ``cells`` ((w,) int64): (cell, length) each."""
    starts = np.flatnonzero(np.concatenate(([True], cells[1:] != cells[:-1])))
    lengths = np.diff(starts, append=len(cells))
    return list(zip(cells[starts].tolist(), lengths.tolist()))


def _spans(changed: np.ndarray) -> list[tuple[int, int]]:
    """The runs of True in ``changed`` as (first, length)."""
    edges = np.flatnonzero(np.diff(changed.astype(np.int8), prepend=0, append=0))
    return [(start, end - start) for start, end in zip(edges[0::2].tolist(), edges[1::2].tolist())]

