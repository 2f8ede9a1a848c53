"""Frames become terminal lines of half-block cells, two pixels to a cell, and back exactly."""

import re

import numpy as np
import pytest
from rich.color import Color
from rich.console import Console
from textual.strip import Strip

from biceps.tui.halfblocks import HalfBlocks
from biceps.terminal.cells import HALF_BLOCKS

UPPER_HALF = HALF_BLOCKS.glyphs[1]


def frame_to_strips(frame: np.ndarray) -> list[Strip]:
    return HalfBlocks().encode(frame).strips


def _frame(columns):
    """A 2-row frame from a list of (top, bottom) RGB pairs, one per column."""
    frame = np.zeros((2, len(columns), 3), np.uint8)
    for x, (top, bottom) in enumerate(columns):
        frame[0, x], frame[1, x] = top, bottom
    return frame


def _pixels_of_segments(strips: list[Strip]) -> np.ndarray:
    """The frame the segments show: "▀" is fg above bg, a space is bg twice."""
    rows = []
    for strip in strips:
        top, bottom = [], []
        for segment in strip:
            background = segment.style.bgcolor.get_truecolor()
            above = background if segment.text[0] == " " else segment.style.color.get_truecolor()
            assert set(segment.text) == {segment.text[0]} and segment.text[0] in " ▀"
            top += [tuple(above)] * len(segment.text)
            bottom += [tuple(background)] * len(segment.text)
        rows += [top, bottom]
    return np.array(rows, np.uint8)


SGR = re.compile(r"\x1b\[([0-9;]*)m([^\x1b]*)\x1b\[0m")


def _pixels_of_output(text: str) -> np.ndarray:
    """The pixels of one line as Textual writes it: SGR codes, cells, a reset, and so on."""
    top, bottom = [], []
    end = 0
    for match in SGR.finditer(text):
        assert match.start() == end, "only styled cells, back to back"
        end = match.end()
        codes = match[1].split(";")
        colours = {codes[i]: tuple(map(int, codes[i + 2:i + 5])) for i in range(0, len(codes), 5)}
        assert all(codes[i + 1] == "2" for i in range(0, len(codes), 5))  # 24-bit
        below = colours["48"]
        above = colours["38"] if "38" in colours else below
        for character in match[2]:
            assert character == (UPPER_HALF if "38" in colours else " ")
            top.append(above)
            bottom.append(below)
    assert end == len(text)
    return np.array([top, bottom], np.uint8)


def _decoded(frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The frame back from the segments, and back from the codes Textual writes for them."""
    strips = HalfBlocks().encode(frame).strips
    console = Console(color_system="truecolor", force_terminal=True)
    written = np.concatenate([_pixels_of_output(strip.render(console)) for strip in strips])
    return _pixels_of_segments(strips), written


FRAMES = {
    "random": np.random.default_rng(1).integers(0, 256, (40, 33, 3), dtype=np.uint8),
    "random, few colours": np.random.default_rng(2).integers(0, 2, (24, 17, 3), np.uint8) * 255,
    "odd width": np.random.default_rng(3).integers(0, 256, (6, 1, 3), dtype=np.uint8),
    "one colour": np.full((8, 9, 3), (12, 34, 56), np.uint8),
    "every cell different": np.arange(2 * 5 * 7 * 3, dtype=np.uint8).reshape(10, 7, 3),
    "stripes": np.repeat(np.array([[[255, 0, 0]], [[0, 0, 255]]], np.uint8), 5, axis=1),
}


@pytest.mark.parametrize("frame", FRAMES.values(), ids=FRAMES.keys())
def test_the_lines_decode_back_to_the_frame_exactly(frame):
    from_segments, from_output = _decoded(frame)
    np.testing.assert_array_equal(from_segments, frame)
    np.testing.assert_array_equal(from_output, frame)


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


def test_a_256_colour_terminal_gets_palette_codes():
    frame = np.random.default_rng(4).integers(0, 256, (6, 20, 3), dtype=np.uint8)
    console = Console(color_system="256", force_terminal=True)
    # A new encoder, so no style has cached its codes for another colour system.
    written = "".join(strip.render(console) for strip in HalfBlocks().encode(frame).strips)
    codes = re.findall(r"\x1b\[([0-9;]*)m", written)
    assert codes
    assert all(re.fullmatch(r"(38;5;\d+;)?48;5;\d+|0", code) for code in codes), codes
    assert any(code.startswith("38;5;") for code in codes)


def test_an_identical_frame_changes_no_line_and_reuses_every_strip():
    frame = np.random.default_rng(5).integers(0, 256, (8, 6, 3), dtype=np.uint8)
    blocks = HalfBlocks()
    first = blocks.encode(frame)
    again = blocks.encode(frame.copy())
    assert first.changed == [(0, 4)]
    assert again.changed == []
    assert all(new is old for new, old in zip(again.strips, first.strips))


def test_only_the_rows_with_a_changed_pixel_are_new():
    frame = np.zeros((12, 5, 3), np.uint8)
    blocks = HalfBlocks()
    first = blocks.encode(frame)
    frame[3, 2] = (1, 2, 3)  # row 1 of cells
    frame[8, 0] = frame[11, 4] = (4, 5, 6)  # rows 4 and 5
    lines = blocks.encode(frame)
    assert lines.changed == [(1, 1), (4, 2)]
    unchanged = [0, 2, 3]
    assert all(lines.strips[y] is first.strips[y] for y in unchanged)
    np.testing.assert_array_equal(_pixels_of_segments(lines.strips), frame)


def test_a_frame_of_another_size_changes_every_line():
    blocks = HalfBlocks()
    blocks.encode(np.zeros((4, 3, 3), np.uint8))
    lines = blocks.encode(np.zeros((6, 3, 3), np.uint8))
    assert lines.changed == [(0, 3)]
    assert len(lines.strips) == 3


def test_after_a_reset_every_line_is_new():
    frame = np.random.default_rng(6).integers(0, 256, (8, 6, 3), dtype=np.uint8)
    blocks = HalfBlocks()
    blocks.encode(frame)
    blocks.reset()
    picture = blocks.encode(frame)
    assert picture.changed == [(0, 4)]
    np.testing.assert_array_equal(_pixels_of_segments(picture.strips), frame)
