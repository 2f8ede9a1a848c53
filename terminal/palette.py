"""Pictures in few colours: each frame mapped onto a palette as the eye sees colour, so that a
smooth red belly stays red, with a fine texture, and never turns into hue noise.

A 256-colour terminal has 16 system colours, which each terminal sets its own way (left out
here), a 6 x 6 x 6 colour cube and a ramp of 24 greys. The cube is coarse: the muscle's reds
lie between entries of other hues (pink, orange, magenta, grey), so error diffusion, which
takes whichever entry is nearest to the colour plus the error handed on from its neighbours,
scatters those hues across the belly (confetti); and Rich, left to itself, maps each colour
on its own and bands the shading.

Here each colour is shown as an ordered dither between two entries (a 2 x 2 Bayer matrix:
none, a quarter, half, three quarters or all of the pixels take the second), the pair
chosen in OKLab (Björn Ottosson, "A perceptual color space for image processing", 2020):
the one whose mixture, in a share the matrix can show, is nearest to the colour, plus a
penalty for how far the farther of the two is from it. That distance counts a difference of
hue :data:`HUE_WEIGHT` times over (and a grey's loss of all the target's hue as one), so a
red is mixed from reds, lighter and darker, and a bone's beige from beiges and greys, not
from a magenta and an orange, or a pink and a yellow, that average to it. Mixtures are
taken in sRGB, as the picture is measured (both blurred alike, ``benchmarks/palette.py``).
A pixel's pattern depends on its own colour and place alone, so a frame that changes in one
place changes only there (error diffusion would change the rest of the row too), and a
turning model does not shimmer.

Choosing a pair looks at every entry, so each choice is kept in a table of colours at
:data:`TABLE_BITS` bits a channel, filled as colours are met; the share of the second entry
is worked out for each pixel from its exact colour. The background is kept one flat colour,
its nearest entry, with nothing mixed into it. Sixel images with few colour registers are
mapped the same way onto their own palette (``terminal/sixel.py``). Free of Textual.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from rich.color import Color

from biceps.engine.jit import helper, ngjit

FIRST = 16  # the first entry after the system colours
CUBE_LEVELS = (0, 95, 135, 175, 215, 255)  # xterm's cube, per channel

HUE_WEIGHT = 4.0  # how much more a difference of hue counts than one of lightness or chroma
SPREAD = 0.25  # the weight of the farther entry's distance in a pair's cost
CANDIDATES = 10  # the entries nearest a colour that its pair is chosen from
GREY_CHROMA = 0.02  # OKLab chroma below which an entry has no hue to speak of
SHARES = 4  # a 2 x 2 matrix shows the second entry in 0 to 4 of its pixels
TABLE_BITS = 6  # bits a channel of the table of chosen pairs
TABLE_SIZE = 1 << (3 * TABLE_BITS)
NO_BACKGROUND = -1


def _xterm_colours() -> np.ndarray:
    """Entries 16 to 255 of xterm's palette, (240, 3) uint8: the cube, then the greys."""
    levels = np.array(CUBE_LEVELS, dtype=np.uint8)
    red, green, blue = np.meshgrid(levels, levels, levels, indexing="ij")
    cube = np.stack([red.ravel(), green.ravel(), blue.ravel()], axis=1)
    greys = np.repeat(np.arange(8, 239, 10, dtype=np.uint8)[:, None], 3, axis=1)
    return np.concatenate([cube, greys])


COLOURS = _xterm_colours()
COLOURS.flags.writeable = False
_PACKED = {(int(r) << 16) | (int(g) << 8) | int(b): FIRST + number
           for number, (r, g, b) in enumerate(COLOURS)}


@helper
def _linear(channel):
    """An sRGB channel, 0 to 255, as linear light, 0 to 1."""
    c = channel / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


@helper
def _to_oklab(red, green, blue, out):
    """The sRGB colour (0 to 255 each) in OKLab, written into ``out`` ((3,) float64)."""
    r, g, b = _linear(red), _linear(green), _linear(blue)
    long = np.cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b)
    medium = np.cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b)
    short = np.cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b)
    out[0] = 0.2104542553 * long + 0.7936177850 * medium - 0.0040720468 * short
    out[1] = 1.9779984951 * long - 2.4285922050 * medium + 0.4505937099 * short
    out[2] = 0.0259040371 * long + 0.7827717662 * medium - 0.8086757660 * short


@ngjit
def _to_oklab_all(colours, out):
    """colours: (n, 3) float64 sRGB, 0 to 255; out: (n, 3) float64 OKLab, written."""
    for index in range(colours.shape[0]):
        _to_oklab(colours[index, 0], colours[index, 1], colours[index, 2], out[index])


def oklab(colours: np.ndarray) -> np.ndarray:
    """sRGB colours ((..., 3), 0 to 255) in OKLab ((..., 3) float64; L from 0 to 1)."""
    colours = np.asarray(colours)
    flat = np.ascontiguousarray(colours.reshape(-1, 3), dtype=np.float64)
    out = np.empty_like(flat)
    _to_oklab_all(flat, out)
    return out.reshape(colours.shape)


@helper
def _distances(target, lab, chroma, weighted):
    """Each entry's distance squared from ``target`` ((3,) OKLab), a difference of hue
    counted HUE_WEIGHT times: weighted: (n,) float64, written. lab: (n, 3) float64, the
    entries in OKLab; chroma: (n,) float64, theirs."""
    target_chroma = np.sqrt(target[1] * target[1] + target[2] * target[2])
    for index in range(lab.shape[0]):
        lightness = lab[index, 0] - target[0]
        saturation = chroma[index] - target_chroma
        if chroma[index] >= GREY_CHROMA:
            # The difference of hue (CIE's delta H): what is left of the distance in a, b
            # once that of chroma is taken out, 2 C1 C2 (1 - cos dh).
            hue = (2.0 * (chroma[index] * target_chroma - lab[index, 1] * target[1]
                          - lab[index, 2] * target[2]))
        else:  # an entry without hue loses all the target's: counted as hue too
            hue = target_chroma * target_chroma
        weighted[index] = lightness * lightness + saturation * saturation + HUE_WEIGHT * hue


@helper
def _nearest(weighted, nearest):
    """The indices of the ``len(nearest)`` (or fewer) least of ``weighted``, least first,
    into ``nearest`` ((k,) int64); returns how many."""
    filled = 0
    for index in range(weighted.shape[0]):
        value = weighted[index]
        if filled < nearest.shape[0]:
            position = filled
            filled += 1
        elif value < weighted[nearest[filled - 1]]:
            position = filled - 1
        else:
            continue
        while position > 0 and weighted[nearest[position - 1]] > value:
            nearest[position] = nearest[position - 1]
            position -= 1
        nearest[position] = index
    return filled


@helper
def _choose_pair(red, green, blue, entries, lab, chroma, weighted, nearest, target, mixed):
    """The two entries that show the colour (sRGB, 0 to 255) best, packed as ``1 << 16 |
    second << 8 | first`` (the same twice for one entry alone). entries: (n, 3) float64
    sRGB; lab, chroma: theirs in OKLab, (n, 3) and (n,); scratch: weighted (n,) float64,
    nearest (CANDIDATES,) int64, target and mixed (3,) float64."""
    _to_oklab(red, green, blue, target)
    _distances(target, lab, chroma, weighted)
    count = _nearest(weighted, nearest)
    best, least = 0, np.inf
    for i in range(count):
        first = nearest[i]
        for j in range(i, count):
            second = nearest[j]
            for share in range(SHARES + 1 if second != first else 1):
                t = share / SHARES
                _to_oklab(entries[first, 0] + t * (entries[second, 0] - entries[first, 0]),
                          entries[first, 1] + t * (entries[second, 1] - entries[first, 1]),
                          entries[first, 2] + t * (entries[second, 2] - entries[first, 2]),
                          mixed)
                error = ((mixed[0] - target[0]) ** 2 + (mixed[1] - target[1]) ** 2
                         + (mixed[2] - target[2]) ** 2)
                spread = max(weighted[first] if share < SHARES else 0.0,
                             weighted[second] if share > 0 else 0.0)
                cost = error + SPREAD * spread
                if cost < least:
                    least = cost
                    shown_first = second if share == SHARES else first
                    shown_second = first if share == 0 else second
                    best = (1 << 16) | (shown_second << 8) | shown_first
    return best


@ngjit
def dither(frame, entries, lab, chroma, table, background, background_entry, out,
           weighted, nearest, target, mixed):
    """``frame`` as entries of a palette: out[y, x] is the entry shown at (x, y).

    frame: (h, w, 3) uint8; entries: (n, 3) float64 sRGB (n <= 256); lab, chroma: theirs in
    OKLab, (n, 3) and (n,) float64; table: (TABLE_SIZE,) int32, the pairs chosen so far (0
    where none is), filled in; background: (3,) uint8, shown as the entry
    ``background_entry`` alone (NO_BACKGROUND: as any colour); out: (h, w) uint8, written.
    Scratch as for _choose_pair.
    """
    height, width = frame.shape[:2]
    shift = 8 - TABLE_BITS
    half = (1 << shift) / 2.0
    for y in range(height):
        for x in range(width):
            red, green, blue = frame[y, x, 0], frame[y, x, 1], frame[y, x, 2]
            if (background_entry >= 0 and red == background[0] and green == background[1]
                    and blue == background[2]):
                out[y, x] = background_entry
                continue
            key = ((np.int64(red) >> shift) << (2 * TABLE_BITS)
                   | (np.int64(green) >> shift) << TABLE_BITS | (np.int64(blue) >> shift))
            pair = table[key]
            if pair == 0:  # the pair of the middle of the table's cell
                pair = _choose_pair(((red >> shift) << shift) + half,
                                    ((green >> shift) << shift) + half,
                                    ((blue >> shift) << shift) + half,
                                    entries, lab, chroma, weighted, nearest, target, mixed)
                table[key] = pair
            first, second = pair & 255, (pair >> 8) & 255
            if first != second:
                # The share of the second entry that mixes to this pixel's colour, against
                # the matrix's threshold here: ([[0, 2], [3, 1]] + 1/2) / 4.
                along, length = 0.0, 0.0
                for channel in range(3):
                    step = entries[second, channel] - entries[first, channel]
                    along += (frame[y, x, channel] - entries[first, channel]) * step
                    length += step * step
                rank = (2 * (x & 1)) ^ (3 * (y & 1))
                if along > (rank + 0.5) / SHARES * length:
                    first = second
            out[y, x] = first


class Ditherer:
    """Maps frames onto the palette ``entries`` ((n, 3) uint8, n <= 256). Keeps the pairs it
    has chosen and scratch space: give each thread its own."""

    def __init__(self, entries: np.ndarray) -> None:
        self.entries = np.ascontiguousarray(entries, dtype=np.uint8)
        self._entries = self.entries.astype(np.float64)
        self._lab = oklab(self._entries)
        self._chroma = np.hypot(self._lab[:, 1], self._lab[:, 2])
        self._table = np.zeros(TABLE_SIZE, np.int32)
        self._weighted = np.empty(len(self.entries), np.float64)
        self._nearest = np.empty(min(CANDIDATES, len(self.entries)), np.int64)
        self._target, self._mixed = np.empty(3), np.empty(3)

    def indices(self, frame: np.ndarray, background: tuple[int, int, int] | None = None
                ) -> np.ndarray:
        """The entry of each pixel of ``frame`` ((h, w, 3) uint8): (h, w) uint8. Pixels of
        the ``background`` colour, if given, are its nearest entry, all of them."""
        out = np.empty(frame.shape[:2], np.uint8)
        if background is None:
            flat, entry = np.zeros(3, np.uint8), NO_BACKGROUND
        else:
            flat, entry = np.array(background, np.uint8), self.nearest(background)
        dither(np.ascontiguousarray(frame), self._entries, self._lab, self._chroma,
               self._table, flat, entry, out, self._weighted, self._nearest, self._target,
               self._mixed)
        return out

    def nearest(self, rgb: tuple[int, int, int]) -> int:
        """The index of the entry nearest to ``rgb`` in OKLab."""
        return int(np.argmin(np.sum((self._lab - oklab(np.array(rgb))) ** 2, axis=1)))


@lru_cache(maxsize=64)
def nearest(rgb: tuple[int, int, int]) -> int:
    """The palette number (16 to 255) of the entry that looks nearest to ``rgb``."""
    return FIRST + _xterm_ditherer().nearest(rgb)


@lru_cache(maxsize=1)
def _xterm_ditherer() -> Ditherer:
    return Ditherer(COLOURS)  # (for nearest alone, which uses none of its scratch)


def entry_numbers() -> dict[int, int]:
    """Each entry's number (16 to 255) by its colour, ``r << 16 | g << 8 | b``."""
    return _PACKED


def colour(packed: int) -> Color:
    """The colour ``r << 16 | g << 8 | b`` as a palette entry when it is one (as every
    colour of :meth:`Palette256.mapped` is), so that Textual writes that entry and no
    other."""
    number = _PACKED.get(packed)
    if number is None:
        return Color.from_rgb(packed >> 16, (packed >> 8) & 0xFF, packed & 0xFF)
    return Color.from_ansi(number)


def background_colour(rgb: tuple[int, int, int]) -> Color:
    """The palette entry the background ``rgb`` is shown in."""
    return Color.from_ansi(nearest(rgb))


class Palette256:
    """Maps frames onto xterm's 256 colours. Keeps the pairs it has chosen: give each
    thread its own."""

    def __init__(self) -> None:
        self._ditherer = Ditherer(COLOURS)

    def mapped(self, frame: np.ndarray, background: tuple[int, int, int]) -> np.ndarray:
        """``frame`` ((h, w, 3) uint8) in palette colours only, dithered, with every pixel of
        the ``background`` colour in that colour's nearest entry; a new (h, w, 3) uint8."""
        return COLOURS[self._ditherer.indices(frame, tuple(background))]
