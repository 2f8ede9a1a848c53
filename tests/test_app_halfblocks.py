"""Frames become terminal lines of half-block cells, two pixels to a cell."""

import numpy as np
from rich.color import Color

from tui.halfblocks import UPPER_HALF, frame_to_strips


def _frame(columns):
    """A 2-row frame from a list of (top, bottom) RGB pairs, one per column."""
    frame = np.zeros((2, len(columns), 3), np.uint8)
    for x, (top, bottom) in enumerate(columns):
        frame[0, x], frame[1, x] = top, bottom
    return frame


def test_a_cell_shows_the_top_pixel_in_front_of_the_bottom_one():
    (strip,) = frame_to_strips(_frame([((255, 0, 0), (0, 0, 255))]))
    (segment,) = list(strip)
    assert segment.text == UPPER_HALF
    assert segment.style.color == Color.from_rgb(255, 0, 0)
    assert segment.style.bgcolor == Color.from_rgb(0, 0, 255)


def test_a_cell_of_two_equal_pixels_is_a_space_on_that_colour():
    (strip,) = frame_to_strips(_frame([((9, 8, 7), (9, 8, 7))]))
    (segment,) = list(strip)
    assert segment.text == " "
    assert segment.style.color is None
    assert segment.style.bgcolor == Color.from_rgb(9, 8, 7)


def test_runs_of_equal_cells_merge_into_one_segment():
    red, blue = (255, 0, 0), (0, 0, 255)
    (strip,) = frame_to_strips(_frame([(red, blue)] * 3 + [(blue, blue)] * 2 + [(red, blue)]))
    assert [segment.text for segment in strip] == [UPPER_HALF * 3, "  ", UPPER_HALF]
    assert strip.cell_length == 6


def test_a_frame_gives_one_strip_per_pair_of_rows():
    frame = np.random.default_rng(1).integers(0, 256, (10, 7, 3), dtype=np.uint8)
    strips = frame_to_strips(frame)
    assert len(strips) == 5
    assert all(strip.cell_length == 7 for strip in strips)
