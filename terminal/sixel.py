"""Frames as sixel images, as xterm (``-ti vt340``), foot, mlterm, WezTerm, Windows Terminal
and iTerm2 show them.

Sixel (DEC's VT330/VT340 graphics, https://vt100.net/docs/vt3xx-gp/chapter14.html) draws an
image in bands six pixels tall; each band is sent once per colour in it, as one character
per column whose six bits say which of that column's six pixels take the colour, runs of
one character shortened to ``!count``. A sixel image has a palette, at most as many colours
as the terminal has registers (256 at most here; xterm's vt340 has 16 unless told more).

Pillow quantises the frame to that palette (its fast octree: about 6 ms for 1200x800, and
no dithering, whose noise would cost bytes in every band, where 64 registers or more leave
no bands to see; with fewer, as xterm's vt340 has unless told more, the frame is dithered
onto the octree's colours, choosing them as the eye sees them, ``terminal/palette.py``); a numba
kernel writes the bands.
textual-image's pure-Python encoder took about 50 ms for the same frame (measured with
version 0.12: too slow for 30 frames a second with the frame still to be drawn). (The
encoder is in ``tui/pixels.py``.)
"""

from __future__ import annotations

import numpy as np
from PIL import Image

from biceps.engine.jit import helper, ngjit
from biceps.terminal.palette import Ditherer
from biceps.terminal.writing import put_number

MAX_COLOURS = 256
FEW_COLOURS = 64  # registers below which a picture is dithered onto them
SIXEL = 63  # "?", the character of a column with no pixel set; "?" + bits for the others
REPEAT, NEXT_COLOUR, NEXT_BAND, SELECT = 33, 36, 45, 35  # "!", "$", "-", "#"


@helper
def _put_run(out, at, character, count):
    """Write ``count`` times ``character``, as ``!count`` when that is shorter."""
    if count > 3:
        out[at] = REPEAT
        at = put_number(out, at + 1, count)
        out[at] = character
        return at + 1
    for index in range(count):
        out[at + index] = character
    return at + count


@ngjit
def encode_bands(indices, colours, out, length, lows, highs, bits):
    """The sixel data of an image of palette indices: bands, colours, runs.

    indices: (h, w) uint8, each below ``colours``; out: (n,) uint8, written; length: (1,)
    int64, set to the bytes written, or -1 if ``out`` was too small. Scratch: lows, highs:
    (colours,) int64; bits: (colours, w) uint8, zeros (and left so).
    """
    height, width = indices.shape
    written = 0
    for top in range(0, height, 6):
        for colour in range(colours):
            lows[colour], highs[colour] = width, -1
        for row in range(top, min(top + 6, height)):
            bit = 1 << (row - top)
            for x in range(width):
                colour = indices[row, x]
                bits[colour, x] |= bit
                lows[colour] = min(lows[colour], x)
                highs[colour] = max(highs[colour], x)
        band_start = written
        for colour in range(colours):
            low, high = lows[colour], highs[colour]
            if high < 0:
                continue
            # The worst case: a character per column, and a selection and run on either side.
            if written + (high - low + 1) + 32 > len(out):
                length[0] = -1
                return
            out[written] = SELECT
            written = put_number(out, written + 1, colour)
            written = _put_run(out, written, SIXEL, low)
            run, count = bits[colour, low], 0
            for x in range(low, high + 1):
                value = bits[colour, x]
                bits[colour, x] = 0
                if value == run:
                    count += 1
                else:
                    written = _put_run(out, written, SIXEL + run, count)
                    run, count = value, 1
            written = _put_run(out, written, SIXEL + run, count)
            out[written] = NEXT_COLOUR
            written += 1
        if written > band_start:
            written -= 1  # the band's last "$" becomes the "-" that starts the next band
        out[written] = NEXT_BAND
        written += 1
    length[0] = written - 1 if written else 0  # no "-" after the last band


def quantised(frame: np.ndarray, colours: int) -> tuple[np.ndarray, np.ndarray]:
    """``frame`` ((h, w, 3) uint8) as palette indices ((h, w) uint8) and the palette
    ((n, 3) uint8, n <= ``colours``). With fewer than :data:`FEW_COLOURS` the frame is
    dithered onto the palette as a 256-colour terminal's picture is (``terminal/palette.py``),
    where the octree's nearest colours alone would band the shading."""
    image = Image.fromarray(np.ascontiguousarray(frame), "RGB").quantize(
        colours, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
    indices = np.asarray(image)
    palette = np.asarray(image.getpalette()[: 3 * colours], np.uint8).reshape(-1, 3)
    palette = palette[: int(indices.max()) + 1]
    if colours < FEW_COLOURS:
        indices = Ditherer(palette).indices(frame)
    return indices, palette


def fitted(frame: np.ndarray, limit: tuple[int, int] | None, columns: int, rows: int,
           cell: tuple[int, int]) -> tuple[np.ndarray, str]:
    """``frame`` ((h, w, 3) uint8, filling ``columns x rows`` cells of ``cell`` (width,
    height) pixels) scaled down, if it must be, to at most ``limit`` (width, height) pixels,
    and the cursor moves that put it in the middle of its cells ("" if it fills them)."""
    height, width = frame.shape[:2]
    if limit is None or (width <= limit[0] and height <= limit[1]):
        return frame, ""
    scale = min(limit[0] / width, limit[1] / height)
    size = max(1, int(width * scale)), max(1, int(height * scale))
    frame = np.asarray(Image.fromarray(np.ascontiguousarray(frame), "RGB").resize(
        size, Image.Resampling.BOX))
    right = (columns - -(-size[0] // cell[0])) // 2
    down = (rows - -(-size[1] // cell[1])) // 2
    return frame, (f"\x1b[{down}B" if down else "") + (f"\x1b[{right}C" if right else "")


def sixel_image(indices: np.ndarray, palette: np.ndarray) -> str:
    """The DCS sequence drawing ``indices`` ((h, w) uint8) in the colours ``palette``
    ((n, 3) uint8, 0-255) from the cursor."""
    height, width = indices.shape
    colours = len(palette)
    # P2 = 1: the bits left at 0 leave the screen as it is. Raster attributes: square
    # pixels, and the image's size. Colours in percent, as sixel has them.
    percent = (palette.astype(np.int64) * 100 + 127) // 255
    registers = "".join(f"#{index};2;{r};{g};{b}" for index, (r, g, b) in
                        enumerate(percent.tolist()))
    out = np.empty(max(width * height // 2, 1 << 16), np.uint8)
    length = np.zeros(1, np.int64)
    lows, highs = np.empty(colours, np.int64), np.empty(colours, np.int64)
    bits = np.zeros((colours, width), np.uint8)
    while True:
        encode_bands(indices, colours, out, length, lows, highs, bits)
        if length[0] >= 0:
            break
        out = np.empty(2 * len(out), np.uint8)
        bits[:] = 0
    data = out[: length[0]].tobytes().decode("ascii")
    return f'\x1bP0;1;0q"1;1;{width};{height}{registers}{data}\x1b\\'
