"""Reading pictures back in tests: the pixels a viewport shows, and how many pieces an image
falls into."""

from __future__ import annotations

from typing import Iterator

import numpy as np
from rich.color import Color


def shown_cells(viewport) -> Iterator[tuple[int, int, Color, Color]]:
    """Each cell of the picture on screen: ``(x, y, top colour, bottom colour)``."""
    width, height = viewport.size
    for y in range(height):
        x = 0
        for segment in viewport.render_line(y):
            style = segment.style
            top = style.color if segment.text[:1] == "▀" else style.bgcolor
            for column in range(x, min(x + segment.cell_length, width)):
                yield column, y, top, style.bgcolor
            x += segment.cell_length


def shown_pixels(viewport) -> np.ndarray:
    """The picture on screen as (2 h, w, 3) uint8, from half-block cells in 24-bit colour."""
    width, height = viewport.size
    pixels = np.zeros((2 * height, width, 3), dtype=np.uint8)
    for x, y, top, bottom in shown_cells(viewport):
        pixels[2 * y, x], pixels[2 * y + 1, x] = top.get_truecolor(), bottom.get_truecolor()
    return pixels


def pieces(frame: np.ndarray, background: tuple[int, int, int]) -> int:
    """How many separate pieces (4-connected) what is drawn on ``background`` falls into."""
    drawn = np.abs(frame.astype(int) - np.array(background)).sum(axis=2) > 12
    found = np.zeros_like(drawn)
    count = 0
    while (left := drawn & ~found).any():
        piece = np.zeros_like(drawn)
        piece[tuple(np.argwhere(left)[0])] = True
        while True:  # grow it a pixel each way at a time, within what is drawn
            grown = piece.copy()
            grown[1:] |= piece[:-1]
            grown[:-1] |= piece[1:]
            grown[:, 1:] |= piece[:, :-1]
            grown[:, :-1] |= piece[:, 1:]
            grown &= drawn
            if np.array_equal(grown, piece):
                break
            piece = grown
        found |= piece
        count += 1
    return count


def cell_pixels(shape, cells: np.ndarray) -> np.ndarray:
    """The pixels that text cells of ``shape`` (terminal/cells.py) show, each in its cell's
    foreground or background colour: (rows h, columns w, 3) uint8 for (h, w) cells."""
    from biceps.terminal.cells import unpacked

    height, width = cells.shape
    pixels = np.zeros((height * shape.rows, width * shape.columns, 3), np.uint8)
    for (y, x), cell in np.ndenumerate(cells):
        fore, back, pattern = unpacked(int(cell))
        for index in range(shape.pixels):
            row, column = divmod(index, shape.columns)
            colour = fore if pattern >> index & 1 else back
            pixels[y * shape.rows + row, x * shape.columns + column] = (
                colour >> 16, colour >> 8 & 255, colour & 255)
    return pixels
