"""Frames as text cells of two colours: half-blocks, quadrants and sextants, read back."""

from __future__ import annotations

import unicodedata

import numpy as np
import pytest
from rich.console import Console
from textual.strip import Strip

from biceps.terminal.cells import HALF_BLOCKS, QUADRANTS, SEXTANTS, CellRows, unpacked
from biceps.tui.halfblocks import TextCells
from pictures import cell_pixels

SHAPES = [HALF_BLOCKS, QUADRANTS, SEXTANTS]


def _two_colour_frame(shape, rows: int, columns: int, seed: int) -> np.ndarray:
    """A frame whose every cell has two colours (or one) in a random pattern."""
    rng = np.random.default_rng(seed)
    frame = np.zeros((rows * shape.rows, columns * shape.columns, 3), np.uint8)
    for y in range(rows):
        for x in range(columns):
            colours = rng.integers(0, 256, (2, 3), dtype=np.uint8)
            pattern = rng.integers(0, 2, (shape.rows, shape.columns))
            frame[y * shape.rows:(y + 1) * shape.rows,
                  x * shape.columns:(x + 1) * shape.columns] = colours[pattern]
    return frame


@pytest.mark.parametrize("shape", SHAPES, ids=lambda shape: shape.name)
def test_cells_of_two_colours_are_shown_exactly(shape):
    frame = _two_colour_frame(shape, 7, 9, seed=len(shape.glyphs))
    cells = CellRows(shape)
    cells.fit(frame)
    np.testing.assert_array_equal(cell_pixels(shape, cells.cells), frame)


@pytest.mark.parametrize("shape", SHAPES, ids=lambda shape: shape.name)
def test_each_pattern_is_its_character_with_the_last_pixel_in_the_background(shape):
    for pattern, glyph in enumerate(shape.glyphs):
        assert not pattern >> (shape.pixels - 1) & 1
        if shape is SEXTANTS and glyph not in " ▌":
            # Unicode names a sextant by the pixels it sets, 1 to 6 row by row.
            lit = "".join(str(i + 1) for i in range(6) if pattern >> i & 1)
            assert unicodedata.name(glyph) == f"BLOCK SEXTANT-{lit}"
    assert SEXTANTS.glyphs[21] == "▌" and QUADRANTS.glyphs[5] == "▌"


def test_a_cell_of_more_colours_is_split_around_the_two_that_differ_most():
    # Four dark pixels and two light ones: the light two in the foreground, the means kept.
    cell = np.array([[[10, 10, 10], [250, 250, 250]], [[20, 20, 20], [240, 240, 240]],
                     [[14, 14, 14], [16, 16, 16]]], np.uint8)
    cells = CellRows(SEXTANTS)
    cells.fit(cell)
    fore, back, pattern = unpacked(int(cells.cells[0, 0]))
    assert pattern == 0b001010  # the right pixels of the top two rows
    assert (fore, back) == (245 * 0x010101, 15 * 0x010101)


def test_a_palette_frame_keeps_its_colours():
    # Three colours in a cell, in a 256-colour terminal: each shown in one of its own.
    cell = np.array([[[95, 0, 0], [175, 0, 0]], [[95, 0, 0], [175, 95, 95]],
                     [[95, 0, 0], [175, 0, 0]]], np.uint8)
    cells = CellRows(SEXTANTS, exact=True)
    cells.fit(cell)
    fore, back, _ = unpacked(int(cells.cells[0, 0]))
    pixels = {r << 16 | g << 8 | b for r, g, b in cell.reshape(-1, 3).tolist()}
    assert {fore, back} <= pixels


@pytest.mark.parametrize("shape", SHAPES, ids=lambda shape: shape.name)
def test_the_lines_text_is_what_textual_writes_for_their_segments(shape):
    frame = _two_colour_frame(shape, 5, 11, seed=3)
    strips = TextCells(shape).encode(frame).strips
    console = Console(color_system="truecolor", force_terminal=True)
    for strip in strips:
        assert strip.render(console) == Strip(list(strip), strip.cell_length).render(console)


def test_sextants_pixels_are_drawn_narrower_than_tall():
    # In a cell of 10 x 20 pixels: 5 across, 6.67 down.
    assert TextCells(SEXTANTS, terminal_cell=(10, 20)).aspect == pytest.approx(0.75)
    assert TextCells(QUADRANTS, terminal_cell=(10, 20)).aspect == pytest.approx(0.5)
