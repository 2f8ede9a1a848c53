"""Output with only the colour codes that change draws the same cells as Textual's own."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from rich.color import Color
from rich.console import Console
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from biceps.tui.halfblocks import HalfBlocks
from biceps.tui.pixels import ItermImages, KittyGraphics, Sixel
from biceps.tui.sgr import minimized
from vt import Screen

RED_ON_BLUE = "\x1b[38;2;255;0;0;48;2;0;0;255m"


def test_a_colour_that_stays_is_not_sent_again():
    # Textual: every segment its codes, then a reset. Only the background changes here.
    written = f"{RED_ON_BLUE}▀\x1b[0m\x1b[38;2;255;0;0;48;2;0;9;0m▀▀\x1b[0m"
    assert minimized(written) == f"{RED_ON_BLUE}▀\x1b[48;2;0;9;0m▀▀\x1b[0m"


def test_a_colour_dropped_goes_back_to_the_default():
    written = f"{RED_ON_BLUE}▀\x1b[0m\x1b[48;2;0;0;255m \x1b[0mplain"
    assert minimized(written) == f"{RED_ON_BLUE}▀\x1b[39m \x1b[0mplain"


def test_an_attribute_dropped_starts_again_from_a_reset():
    written = "\x1b[1;3;38;5;200mbold\x1b[0m\x1b[3;38;5;200mitalic\x1b[0m"
    assert minimized(written) == "\x1b[1;3;38;5;200mbold\x1b[0;3;38;5;200mitalic\x1b[0m"


def test_cursor_moves_wait_for_the_state_and_other_sequences_do_not():
    written = f"{RED_ON_BLUE}a\x1b[0m\x1b[3;1H{RED_ON_BLUE}b\x1b[0m\x1b[?25l"
    assert minimized(written) == f"{RED_ON_BLUE}a\x1b[3;1Hb\x1b[0m\x1b[?25l"


def test_a_new_line_between_rows_waits_for_the_state_like_a_cursor_move():
    written = f"{RED_ON_BLUE}a\x1b[0m\n\x1b[3;1H{RED_ON_BLUE}b\x1b[0m\r\n"
    assert minimized(written) == f"{RED_ON_BLUE}a\n\x1b[3;1Hb\r\n\x1b[0m"


def test_codes_it_does_not_know_pass_through_with_the_rest():
    underline_colour = "\x1b[4;58;2;1;2;3m"
    written = f"{RED_ON_BLUE}a\x1b[0m{underline_colour}b\x1b[0m{RED_ON_BLUE}c\x1b[0m"
    assert minimized(written) == written  # the reset it needs first, then all as it was


def test_output_without_colour_codes_is_left_alone():
    for written in ("", "plain", "\x1b[?2026h", "\x1b7\x1b[1;3H\x1b[6n\x1b8"):
        assert minimized(written) == written


colours = st.one_of(
    st.none(),
    st.builds(Color.from_rgb, st.integers(0, 255), st.integers(0, 255), st.integers(0, 255)),
    st.builds(Color.from_ansi, st.integers(0, 255)),
    st.sampled_from([Color.parse(name) for name in ("red", "bright_green", "default")]),
)
styles = st.one_of(
    st.none(),
    st.builds(Style, color=colours, bgcolor=colours, bold=st.booleans(), dim=st.booleans(),
              italic=st.booleans(), underline=st.booleans(), reverse=st.booleans(),
              strike=st.booleans(), overline=st.booleans()),
)
segments = st.builds(Segment, st.text("ab ▀é", min_size=1, max_size=4), styles)
lines = st.lists(st.lists(segments, min_size=1, max_size=12), min_size=1, max_size=6)


@settings(max_examples=200, deadline=None)
@given(lines=lines, system=st.sampled_from(["truecolor", "256", "standard"]))
def test_the_screen_is_the_same_for_any_styles(lines, system):
    console = Console(color_system=system, force_terminal=True)
    written = "\n".join(  # as Textual writes an update's rows
        f"\x1b[{y + 1};1H" + Strip(line).render(console) for y, line in enumerate(lines)
    )
    screen, lean = Screen(60, 6).feed(written), Screen(60, 6).feed(minimized(written))
    assert lean.cells == screen.cells
    assert lean.pen == screen.pen
    assert len(minimized(written)) <= len(written)


def test_a_picture_comes_back_exactly_and_shorter():
    frame = np.random.default_rng(7).integers(0, 256, (20, 30, 3), dtype=np.uint8)
    frame[:, :10] = (20, 22, 28)  # a flat background, and a ramp of one colour
    frame[:, 10:14] = np.arange(40, dtype=np.uint8).reshape(20, 2, 1).repeat(2, 1)
    console = Console(color_system="truecolor", force_terminal=True)
    strips = HalfBlocks().encode(frame).strips
    written = "".join(f"\x1b[{y + 1};1H" + strip.render(console) for y, strip in enumerate(strips))
    lean = minimized(written)
    np.testing.assert_array_equal(Screen(30, 10).feed(lean).pixels(0, 0, 30, 10), frame)
    assert len(lean) < len(written)


def test_images_pass_through_untouched_between_colour_codes():
    # Kitty (APC), sixel (DCS) and iTerm2 (OSC) images, whose payloads hold "[", "m" and ";"
    # a plenty, go out byte for byte; the colour codes around them are still made lean.
    frame = np.random.default_rng(3).integers(0, 256, (40, 30, 3)).astype(np.uint8)
    images = [encoder.encode(frame).image for encoder in
              (KittyGraphics(Size(3, 4), 9), Sixel(Size(3, 4)), ItermImages(Size(3, 4)))]
    text = "".join(f"\x1b[31mA\x1b[31mB\x1b7\x1b[2;3H{image}\x1b8\x1b[0;31mC" for image in images)
    out = minimized(text)
    assert [image in out for image in images] == [True, True, True]
    assert out.count("\x1b[31m") == 1  # red once, whatever came between
