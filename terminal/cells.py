"""Pictures as text: a frame's pixels a few to a character cell, each cell a block character
in two colours, the pixels it covers in the foreground and the rest in the background.

Three shapes of cell (:data:`SHAPES`):

- half-blocks, 1 x 2 pixels: "▀", in every font (the default);
- quadrants, 2 x 2: the quadrant characters of Block Elements (U+2580 to U+259F), in
  every font too: twice the pixels, all of them across;
- sextants, 2 x 3: the sextants of Symbols for Legacy Computing (U+1FB00 to U+1FB3B, Unicode
  13), with "▌" and "▐" from Block Elements: three times the pixels, and pixels nearer to
  square (on a cell twice as tall as wide, three quarters as wide as tall, where quadrants'
  are half). Few fonts have them (not DejaVu; Cascadia Code, Iosevka, JuliaMono and GNU
  Unifont do), but the terminals that draw block characters themselves draw them whatever
  the font: kitty, WezTerm, foot, VTE's (GNOME Terminal, xfce4-terminal), Windows Terminal
  and Ghostty.

A cell of more than two pixels is shown in two colours, so each cell's pixels are split in
two groups (2-means: around the two pixels that differ most, then again around the groups'
means), each shown in its mean colour; or, for a frame already in a palette's colours (a
256-colour terminal's, ``terminal/palette.py``), in the colour of one of its pixels, so that the
cell stays in the palette. A 2 x 2 dither of two entries fills its cell exactly.

A cell is one number, ``foreground << 29 | background << 5 | pattern`` (each colour ``r <<
16 | g << 8 | b``; the pattern has bit ``i`` set where pixel ``i``, row by row, takes the
foreground), with its last pixel always in the background, so that half the patterns (the
others are the same with the colours swapped) name every cell: 16 sextants, 8 quadrants, a
half block. A cell of one colour is a space on it, pattern 0, foreground the same. Kernels
fit the cells, find the rows that differ from the last frame and the runs of equal cells in
them, and write each changed row's terminal text in 24-bit colour, each run as Textual
writes a segment: ``CSI`` foreground ``;`` background ``m``, the characters, ``CSI 0 m``.
Free of Textual: the viewport's encoder (``tui/halfblocks.py``) and ``snapshot --ansi``
(``terminal/ansi.py``) build on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from biceps.engine.jit import helper, ngjit
from biceps.terminal.writing import RGB, put_colour

FOREGROUND, BACKGROUND = 29, 5  # where each colour starts in a cell's number
PATTERN = (1 << BACKGROUND) - 1
COLOUR = (1 << 24) - 1
MOST_PIXELS = 6


def _sextant(pattern: int) -> str:
    """The sextant whose pixels ``pattern`` sets (bit 0: top left, 1: top right, 2: middle
    left, ...), as Unicode numbers them: U+1FB00 is pattern 1, leaving out the two halves
    Block Elements has already (21: "▌", 42: "▐")."""
    special = {0: " ", 21: "▌", 42: "▐", 63: "█"}
    if pattern in special:
        return special[pattern]
    return chr(0x1FB00 + pattern - 1 - (pattern > 21) - (pattern > 42))


@dataclass(frozen=True)
class Shape:
    """How a cell is divided: ``columns x rows`` pixels, and the character of each pattern
    whose last pixel is in the background."""

    name: str
    columns: int
    rows: int
    glyphs: tuple[str, ...]

    @property
    def pixels(self) -> int:
        return self.columns * self.rows


HALF_BLOCKS = Shape("halfblocks", 1, 2, (" ", "▀"))
QUADRANTS = Shape("quadrants", 2, 2, (" ", "▘", "▝", "▀", "▖", "▌", "▞", "▛"))
SEXTANTS = Shape("sextants", 2, 3, tuple(_sextant(pattern) for pattern in range(32)))
SHAPES = {shape.name: shape for shape in (HALF_BLOCKS, QUADRANTS, SEXTANTS)}


def glyph_bytes(shape: Shape) -> tuple[np.ndarray, np.ndarray]:
    """The UTF-8 bytes of each of ``shape``'s characters, (n, 4) uint8, and their lengths,
    (n,) int64, for :func:`write_lines`."""
    encoded = [glyph.encode() for glyph in shape.glyphs]
    table = np.zeros((len(encoded), 4), np.uint8)
    for index, data in enumerate(encoded):
        table[index, :len(data)] = np.frombuffer(data, np.uint8)
    return table, np.array([len(data) for data in encoded], np.int64)


def unpacked(cell: int) -> tuple[int, int, int]:
    """A cell's foreground, background and pattern."""
    return cell >> FOREGROUND & COLOUR, cell >> BACKGROUND & COLOUR, cell & PATTERN


@ngjit
def fit_cells(frame, columns, rows, exact, cells, pixels):
    """Each cell of ``columns x rows`` pixels of ``frame`` as two colours and a pattern,
    packed as the module says.

    frame: (rows h, columns w, 3) uint8; exact: keep the pixels' own colours (a frame in a
    palette's) rather than means; cells: (h, w) int64, written; pixels: (MOST_PIXELS, 3)
    int64, scratch.
    """
    height, width = cells.shape
    count = columns * rows
    for y in range(height):
        for x in range(width):
            for row in range(rows):
                for column in range(columns):
                    for channel in range(3):
                        pixels[row * columns + column, channel] = frame[
                            y * rows + row, x * columns + column, channel]
            # The two pixels that differ most start the two groups.
            first, second, farthest = 0, 0, 0
            for i in range(count):
                for j in range(i + 1, count):
                    distance = _distance(pixels, i, j)
                    if distance > farthest:
                        first, second, farthest = i, j, distance
            if farthest == 0:
                colour = _packed(pixels, 0)
                cells[y, x] = colour << FOREGROUND | colour << BACKGROUND
                continue
            pattern = _grouped(pixels, count, first, second)
            fore, back = _colours(pixels, count, pattern, exact, first, second)
            if not exact:  # once more, around the groups' means
                pattern = _grouped_around(pixels, count, fore, back)
                fore, back = _colours(pixels, count, pattern, exact, first, second)
            if pattern & (1 << (count - 1)):  # the last pixel takes the background
                pattern ^= (1 << count) - 1
                fore, back = back, fore
            if pattern == 0 or fore == back:
                cells[y, x] = back << FOREGROUND | back << BACKGROUND
            else:
                cells[y, x] = fore << FOREGROUND | back << BACKGROUND | pattern


@helper
def _distance(pixels, i, j):
    """The squared distance between pixels ``i`` and ``j`` in sRGB."""
    red = pixels[i, 0] - pixels[j, 0]
    green = pixels[i, 1] - pixels[j, 1]
    blue = pixels[i, 2] - pixels[j, 2]
    return red * red + green * green + blue * blue


@helper
def _packed(pixels, i):
    """Pixel ``i``'s colour as one number, ``r << 16 | g << 8 | b``."""
    return pixels[i, 0] << 16 | pixels[i, 1] << 8 | pixels[i, 2]


@helper
def _grouped(pixels, count, first, second):
    """The pattern of the pixels nearer to pixel ``first`` than to pixel ``second``."""
    pattern = 0
    for i in range(count):
        if _distance(pixels, i, first) <= _distance(pixels, i, second):
            pattern |= 1 << i
    return pattern


@helper
def _grouped_around(pixels, count, fore, back):
    """The pattern of the pixels nearer to the colour ``fore`` than to ``back`` (packed)."""
    pattern = 0
    for i in range(count):
        near, far = 0, 0
        for channel in range(3):
            shift = 16 - 8 * channel
            near += (pixels[i, channel] - (fore >> shift & 255)) ** 2
            far += (pixels[i, channel] - (back >> shift & 255)) ** 2
        if near <= far:
            pattern |= 1 << i
    return pattern


@helper
def _colours(pixels, count, pattern, exact, first, second):
    """The colours of the pixels in ``pattern`` and of the rest, packed: their means
    (rounded), or, ``exact``, pixel ``first``'s and ``second``'s. A group left empty takes
    the other's colour."""
    if exact:
        return _packed(pixels, first), _packed(pixels, second)
    fore, back = 0, 0
    for channel in range(3):
        inside, outside, n_inside = 0, 0, 0
        for i in range(count):
            if pattern & (1 << i):
                inside += pixels[i, channel]
                n_inside += 1
            else:
                outside += pixels[i, channel]
        n_outside = count - n_inside
        mean_in = (inside + n_inside // 2) // n_inside if n_inside else -1
        mean_out = (outside + n_outside // 2) // n_outside if n_outside else -1
        if mean_in < 0:
            mean_in = mean_out
        if mean_out < 0:
            mean_out = mean_in
        fore = fore << 8 | mean_in
        back = back << 8 | mean_out
    return fore, back


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
MOST_BYTES = 4  # of a character in UTF-8


@ngjit
def write_lines(cells, changed, starts, counts, glyphs, lengths, out, ends):
    """The text of each changed row as Textual writes its runs in 24-bit colour (the codes
    of ``Strip.render_ansi`` between ``CSI`` and ``m``, the characters, ``CSI 0 m``).

    cells: (h, w) int64; changed, starts, counts: as from find_runs; glyphs, lengths: the
    characters' UTF-8 bytes, as from glyph_bytes; out: (h * (w * MOST_BYTES + counts.max()
    * MOST_CODES),) uint8 or more, written; ends: (h,) int64, written: row y's text is
    ``out[ends[y - 1]:ends[y]]`` (empty for a row that has not changed).
    """
    height, width = cells.shape
    at = 0
    for y in range(height):
        if changed[y]:
            for run in range(counts[y]):
                start = starts[y, run]
                end = starts[y, run + 1] if run + 1 < counts[y] else width
                cell = cells[y, start]
                pattern = cell & PATTERN
                out[at], out[at + 1] = 27, 91  # ESC [
                at += 2
                if pattern:
                    at = put_colour(out, at, RGB | (cell >> FOREGROUND & COLOUR), True)
                    out[at] = 59  # ;
                    at += 1
                at = put_colour(out, at, RGB | (cell >> BACKGROUND & COLOUR), False)
                out[at] = 109  # m
                at += 1
                size = lengths[pattern]
                for _ in range(end - start):
                    for byte in range(size):
                        out[at + byte] = glyphs[pattern, byte]
                    at += size
                out[at], out[at + 1], out[at + 2], out[at + 3] = 27, 91, 48, 109  # ESC [ 0 m
                at += 4
        ends[y] = at


class CellRows:
    """Frames fitted to cells of ``shape``, and which rows changed since the last frame.

    Keeps the last frame's cells: not thread-safe, give each thread its own.
    """

    def __init__(self, shape: Shape, exact: bool = False) -> None:
        """``exact``: the frames are in a palette's colours, which the cells keep."""
        self.shape, self._exact = shape, exact
        self.cells = np.zeros((0, 0), np.int64)
        self._previous = np.zeros((0, 0), np.int64)
        self._pixels = np.zeros((MOST_PIXELS, 3), np.int64)
        self._starts = np.zeros((0, 0), np.int32)  # find_runs' output, kept for the size
        self._counts = np.zeros(0, np.int32)
        self._glyphs, self._lengths = glyph_bytes(shape)
        self._text = np.zeros(0, np.uint8)
        self._text_ends = np.zeros(0, np.int64)

    def fit(self, frame: np.ndarray) -> np.ndarray:
        """The cells of ``frame`` ((rows h, columns w, 3) uint8) in :attr:`cells`, (h, w)
        int64; returns which rows changed, (h,) bool (all of them after :meth:`reset` or
        at a new size)."""
        shape = self.shape
        height, width = frame.shape[0] // shape.rows, frame.shape[1] // shape.columns
        self.cells, self._previous = self._previous, self.cells
        if self.cells.shape != (height, width):
            self.cells = np.empty((height, width), np.int64)
        fit_cells(frame, shape.columns, shape.rows, self._exact, self.cells, self._pixels)
        changed = np.ones(height, np.bool_)
        if self._previous.shape == self.cells.shape:
            mark_changed_rows(self.cells, self._previous, changed)
        if self._starts.shape != (height, width):
            self._starts = np.empty((height, width), np.int32)
            self._counts = np.empty(height, np.int32)
        find_runs(self.cells, changed, self._starts, self._counts)
        return changed

    def reset(self) -> None:
        """Forget the last frame: the next one changes every row."""
        self.cells = np.zeros((0, 0), np.int64)
        self._previous = np.zeros((0, 0), np.int64)

    def texts(self, changed: np.ndarray) -> list[str | None]:
        """The 24-bit text of each changed row (None for the others)."""
        cells, counts = self.cells, self._counts
        height, width = cells.shape
        size = height * (width * MOST_BYTES + int(counts.max(initial=0)) * MOST_CODES)
        if len(self._text) < size:
            self._text = np.empty(size, np.uint8)
        if len(self._text_ends) != height:
            self._text_ends = np.empty(height, np.int64)
        write_lines(cells, changed, self._starts, counts, self._glyphs, self._lengths,
                    self._text, self._text_ends)
        text, ends = self._text, self._text_ends.tolist()
        return [text[start:end].tobytes().decode() if row_changed else None
                for row_changed, start, end in zip(changed.tolist(), [0, *ends], ends)]


def runs(cells: np.ndarray) -> list[tuple[int, int]]:
    """The runs of equal cells in ``cells`` ((w,) int64): (cell, length) each."""
    starts = np.flatnonzero(np.concatenate(([True], cells[1:] != cells[:-1])))
    lengths = np.diff(starts, append=len(cells))
    return list(zip(cells[starts].tolist(), lengths.tolist()))


def palette_text(cells: np.ndarray, shape: Shape, entry: dict[int, int]) -> str:
    """The text of a row of ``cells`` ((w,) int64) in a 256-colour palette: each colour is
    written as ``entry[colour]``, its number (every colour of the row must have one)."""
    parts = []
    for cell, length in runs(cells):
        fore, back, pattern = unpacked(cell)
        colours = f"38;5;{entry[fore]};" if pattern else ""
        parts.append(f"\x1b[{colours}48;5;{entry[back]}m{shape.glyphs[pattern] * length}"
                     "\x1b[0m")
    return "".join(parts)
