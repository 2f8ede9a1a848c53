"""Pictures for a terminal of 256 colours: each frame mapped onto xterm's palette as a whole,
with error diffusion, so that smooth shading stays smooth.

Such a terminal has 16 system colours, which each terminal sets its own way (left out here),
a 6 x 6 x 6 colour cube and a ramp of 24 greys. Left to itself, Textual has Rich map every
colour on its own to a palette entry (``rich.color.Color.downgrade``, from each channel
apart, or a grey below 15 % saturation): a smooth shadow falls into bands of one entry
(olive on the muscle's dark side), a pixel near the grey threshold jumps to another hue,
and the picture's dark blue-grey background becomes pure black. Here Pillow maps the whole
frame at once with Floyd-Steinberg error diffusion, which hands each pixel's error on to
its neighbours, so that the colours average out to the right ones; and the background is
kept one flat colour: the palette entry nearest to it as the eye sees it (the least CIE76
distance in CIELAB, from Little CMS through Pillow), with no error spread from it or
onto it.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from PIL import Image, ImageCms
from rich.color import Color

FIRST = 16  # the first entry after the system colours
CUBE_LEVELS = (0, 95, 135, 175, 215, 255)  # xterm's cube, per channel


def _xterm_colours() -> np.ndarray:
    """Entries 16 to 255 of xterm's palette, (240, 3) uint8: the cube, then the greys."""
    levels = np.array(CUBE_LEVELS, dtype=np.uint8)
    red, green, blue = np.meshgrid(levels, levels, levels, indexing="ij")
    cube = np.stack([red.ravel(), green.ravel(), blue.ravel()], axis=1)
    greys = np.repeat(np.arange(8, 239, 10, dtype=np.uint8)[:, None], 3, axis=1)
    return np.concatenate([cube, greys])


COLOURS = _xterm_colours()
COLOURS.flags.writeable = False


def _palette_image() -> Image.Image:
    """A palette image holding :data:`COLOURS`, padded to Pillow's 256 entries with copies
    of the first (black), so that any entry Pillow picks is one of ours."""
    padding = np.repeat(COLOURS[:1], 256 - len(COLOURS), axis=0)
    image = Image.new("P", (1, 1))
    image.putpalette(np.concatenate([COLOURS, padding]).ravel().tolist())
    return image


_ENTRY = np.arange(256)
_ENTRY[len(COLOURS):] = 0  # the padding is black, entry 0
_PACKED = {(int(r) << 16) | (int(g) << 8) | int(b): FIRST + number
           for number, (r, g, b) in enumerate(COLOURS)}


@lru_cache(maxsize=64)
def nearest(rgb: tuple[int, int, int]) -> int:
    """The palette number (16 to 255) of the entry that looks nearest to ``rgb``."""
    lab = _lab(np.concatenate([np.array([rgb], dtype=np.uint8), COLOURS]))
    distances = np.sum((lab[1:] - lab[0]) ** 2, axis=1)
    return FIRST + int(np.argmin(distances))


def _lab(colours: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 sRGB as (n, 3) CIELAB floats (L in 0 to 100)."""
    image = ImageCms.applyTransform(Image.fromarray(colours[None]), _srgb_to_lab())
    raw = np.asarray(image)[0]
    # Pillow's LAB: L scaled to 0-255, a and b as signed bytes.
    return np.column_stack([raw[:, 0] * (100.0 / 255.0), raw[:, 1:].view(np.int8)])


@lru_cache(maxsize=1)
def _srgb_to_lab() -> ImageCms.ImageCmsTransform:
    return ImageCms.buildTransform(ImageCms.createProfile("sRGB"), ImageCms.createProfile("LAB"),
                                   "RGB", "LAB")


def colour(packed: int) -> Color:
    """The colour ``r << 16 | g << 8 | b`` as a palette entry when it is one (as every
    colour of :func:`mapped` is), so that Textual writes that entry and no other."""
    number = _PACKED.get(packed)
    if number is None:
        return Color.from_rgb(packed >> 16, (packed >> 8) & 0xFF, packed & 0xFF)
    return Color.from_ansi(number)


def background_colour(rgb: tuple[int, int, int]) -> Color:
    """The palette entry the background ``rgb`` is shown in."""
    return Color.from_ansi(nearest(rgb))


class Palette256:
    """Maps frames onto the palette. Keeps Pillow's palette image: give each thread its own."""

    def __init__(self) -> None:
        self._palette = _palette_image()

    def mapped(self, frame: np.ndarray, background: tuple[int, int, int]) -> np.ndarray:
        """``frame`` ((h, w, 3) uint8) in palette colours only, dithered, with every pixel of
        the ``background`` colour in that colour's nearest entry; a new (h, w, 3) uint8."""
        flat = np.all(frame == np.array(background, dtype=np.uint8), axis=2)
        entry = nearest(tuple(background)) - FIRST
        source = frame.copy()
        source[flat] = COLOURS[entry]  # exact, so there is no error to spread from it
        dithered = Image.fromarray(source, "RGB").quantize(
            palette=self._palette, dither=Image.Dither.FLOYDSTEINBERG)
        entries = _ENTRY[np.asarray(dithered)]
        entries[flat] = entry  # nor any spread onto it from the picture beside it
        return COLOURS[entries]
