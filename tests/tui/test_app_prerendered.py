"""The picture's lines carry the very text Textual would write for them, framed or not."""

from __future__ import annotations

import numpy as np
import pytest
from rich.console import Console
from textual._styles_cache import StylesCache
from textual.geometry import Region
from textual.strip import Strip
from textual.widget import Widget

from biceps.tui.halfblocks import HalfBlocks
from biceps.terminal.palette import Palette256
from biceps.terminal.palette import colour as palette_colour
from biceps.tui.textual_private import PrerenderedStrip, framed
from biceps.tui.widgets.viewport import Viewport

# What only the private path does (tui/textual_private.py).
pytestmark = pytest.mark.usefixtures("private_path")

FRAME = np.random.default_rng(7).integers(0, 256, (12, 40, 3), dtype=np.uint8)
FRAME[:, 10:30] = (20, 30, 40)  # runs of equal cells too, written as spaces


def _as_textual_writes(strip: Strip, console: Console) -> str:
    """``strip`` as Textual writes a strip of the same segments."""
    return Strip(list(strip), strip.cell_length).render(console)


def _encoder(system: str) -> tuple[HalfBlocks, np.ndarray]:
    if system == "256":
        return HalfBlocks(palette_colour, system), Palette256().mapped(FRAME, (20, 30, 40))
    return HalfBlocks(color_system=system), FRAME


@pytest.mark.parametrize("system", ["truecolor", "256", "standard"])
def test_a_line_carries_the_text_textual_writes_for_its_segments(system):
    encoder, frame = _encoder(system)
    console = Console(color_system=system, force_terminal=True)
    strips = encoder.encode(frame).strips
    assert all(isinstance(strip, PrerenderedStrip) for strip in strips)
    assert [strip.render(console) for strip in strips] == [
        _as_textual_writes(strip, console) for strip in strips
    ]


def test_a_console_of_other_colours_gets_textual_s_own_text():
    strips = HalfBlocks().encode(FRAME).strips  # made for truecolor
    console = Console(color_system="256", force_terminal=True)
    written = [strip.render(console) for strip in strips]
    assert written == [_as_textual_writes(strip, console) for strip in strips]
    assert "38;2;" not in "".join(written) and "38;5;" in "".join(written)


@pytest.mark.parametrize("system", ["truecolor", "256"])
def test_a_framed_line_is_written_as_its_sides_around_it(system):
    encoder, frame = _encoder(system)
    console = Console(color_system=system, force_terminal=True)
    line = encoder.encode(frame).strips[3]
    left, right = Strip([*Strip.blank(1)]), Strip.blank(2).apply_style(Console().get_style("red"))
    joined = framed(line, left, right, console)
    assert list(joined) == [*left, *line, *right]
    assert joined.cell_length == line.cell_length + 3
    assert joined.render(console) == _as_textual_writes(joined, console)


def _has_segments(strip: Strip) -> bool:
    try:
        Strip._segments.__get__(strip)  # the slot itself: no segments are made for this
    except AttributeError:
        return False
    return True


def test_a_line_is_written_without_making_its_segments():
    strips = HalfBlocks().encode(FRAME).strips
    console = Console(color_system="truecolor", force_terminal=True)
    left, right = Strip.blank(1), Strip.blank(1)
    joined = [framed(strip, left, right, console) for strip in strips]
    for line in joined + strips:
        # What the compositor does with a line that nothing covers.
        (whole,) = line.divide([line.cell_length, line.cell_length + 5])
        assert whole is line and line.crop(0, line.cell_length) is line
        line.render(console)
    assert not any(_has_segments(line) for line in joined + strips)
    assert list(joined[4]) == [*left, *strips[4], *right]  # made once asked for
    assert _has_segments(joined[4]) and _has_segments(strips[4])
    assert [piece.cell_length for piece in strips[5].divide([10, 40])] == [10, 30]


async def test_the_viewport_s_lines_are_composed_without_their_segments(biceps):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        await session.pilot.press("right")
        await session.settle()
        session.app.screen._compositor.render_update(full=True)  # as a repaint does
        lines = [line for _, _, line in viewport._framed_lines.values()]
        assert lines and not any(_has_segments(line) for line in lines)


def _lines(viewport: Viewport, crop: Region) -> tuple[list[Strip], list[Strip]]:
    """The viewport's lines for ``crop``, and those Textual would style for it itself."""
    return viewport.render_lines(crop), Widget.render_lines(viewport, crop)


def _assert_same(ours: list[Strip], textual: list[Strip], console: Console) -> None:
    assert [list(line) for line in ours] == [list(line) for line in textual]
    assert [line.render(console) for line in ours] == [
        _as_textual_writes(line, console) for line in textual
    ]


async def test_the_viewport_frames_its_lines_as_textual_would_style_them(biceps):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        await session.pilot.press("right")
        await session.settle()
        console = session.app.console
        width, height = viewport.outer_size
        for crop in (Region(0, 0, width, height), Region(3, 2, 20, 5), Region(0, 5, width, 1)):
            ours, textual = _lines(viewport, crop)
            _assert_same(ours, textual, console)
        ours, _ = _lines(viewport, Region(0, 0, width, height))
        assert isinstance(ours[5], PrerenderedStrip)  # framed here, not by Textual
        viewport.blur()  # another border colour
        await session.pilot.pause()
        _assert_same(*_lines(viewport, Region(0, 0, width, height)), console)


async def test_textual_styles_only_the_border_rows_that_changed(biceps, monkeypatch):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        await session.pilot.press("right")
        await session.settle()
        whole = Region(0, 0, *viewport.outer_size)
        viewport.render_lines(whole)
        styled: list[Region] = []
        render_widget = StylesCache.render_widget

        def recording(cache, widget, crop):
            styled.append(crop)
            return render_widget(cache, widget, crop)

        monkeypatch.setattr(StylesCache, "render_widget", recording)
        viewport.render_lines(whole)
        assert styled == []  # all as Textual has them already
        viewport._caption("a new title", viewport.border_subtitle)
        lines = viewport.render_lines(whole)
        assert styled == [Region(0, 0, whole.width, 1)]  # the title's row alone
        _assert_same(lines, Widget.render_lines(viewport, whole), session.app.console)


async def test_a_viewport_with_effects_has_textual_style_its_lines(biceps):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        viewport.styles.tint = "red 40%"
        await session.settle()
        width, height = viewport.outer_size
        ours, textual = _lines(viewport, Region(0, 0, width, height))
        _assert_same(ours, textual, session.app.console)
        assert not any(isinstance(line, PrerenderedStrip) for line in ours)
