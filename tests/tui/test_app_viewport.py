"""The viewport repaints only the lines a new frame changed, and nothing for the same frame;
it writes them itself, as Textual would, unless something else is drawn over it."""

from __future__ import annotations

import re
import threading

import pytest

from textual._compositor import ChopsUpdate

from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.app import BicepsApp
from biceps.tui.rendering import Frames
from biceps.tui.widgets.viewport import Viewport
from vt import Screen
from waiting import until

# A cursor move the viewport writes a line after (not the one that leaves the cursor where
# Textual keeps it, at the end of the update).
LINE_WRITTEN = re.compile(r"\x1b\[(\d+);\d+H(?!$|\x1b\[\?2026l)")


def _record_painted(monkeypatch, border: int) -> list[int]:
    """Every line of the viewport's picture written to the terminal, in order, by Textual
    or by the viewport itself, and ``border`` rows above and below it."""
    lines: list[int] = []
    repainted, write = Viewport.repainted, Viewport._write_synchronized

    def record(viewport, rows) -> None:
        area = viewport.content_region
        lines.extend(y - area.y for y in rows if area.y - border <= y < area.bottom + border)

    def recording(viewport, update):
        area = viewport.content_region
        if isinstance(update, ChopsUpdate):
            rows = [y for y, x1, x2 in update.spans if x1 < area.right and x2 >= area.x]
        else:
            rows = list(range(area.y - border, area.bottom + border))
        record(viewport, rows)
        return repainted(viewport, update)

    def writing(viewport, text):
        record(viewport, [int(row) - 1 for row in LINE_WRITTEN.findall(text)])
        return write(viewport, text)

    monkeypatch.setattr(Viewport, "repainted", recording)
    monkeypatch.setattr(Viewport, "_write_synchronized", writing)
    return lines


@pytest.fixture
def painted(monkeypatch) -> list[int]:
    """Every picture line Textual writes to the terminal, in order."""
    return _record_painted(monkeypatch, 0)


@pytest.fixture
def painted_framed(monkeypatch) -> list[int]:
    """The same, and the border's rows above (-1) and below the picture."""
    return _record_painted(monkeypatch, 1)


async def test_a_new_frame_repaints_only_the_lines_that_changed(private_path, biceps, painted):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        rows = range(viewport.size.height)
        before = [viewport.render_line(y) for y in rows]
        painted.clear()
        await session.pilot.press("up")
        await session.settle()
        repainted = set(painted)
        changed = {y for y in rows if viewport.render_line(y) is not before[y]}
        assert changed and len(changed) < len(rows)  # the arm does not fill the picture
        assert repainted == changed


async def test_a_frame_like_the_last_repaints_nothing(biceps, painted):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        painted.clear()
        viewport.show(session.app.scene)  # a new request, and the same picture
        assert not viewport.up_to_date
        await session.settle()
        assert painted == []


async def test_the_captions_follow_the_picture_on_screen(biceps):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        await session.pilot.press("right")
        await session.settle()
        assert viewport.border_title.startswith(f"yaw {session.app.scene.view.yaw:g}°")


async def test_a_caption_s_row_is_repainted_only_when_it_changes(private_path, biceps,
                                                                  painted_framed, monkeypatch):
    # A frame that takes longer than BUSY_AFTER (a loaded machine) has the subtitle say
    # "drawing…" until it comes, which repaints that row for a reason of its own.
    monkeypatch.setattr(Frames, "busy", lambda frames: False)
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        below = viewport.size.height
        painted_framed.clear()
        await session.pilot.press("right")  # the yaw in the title changes, the subtitle not
        await session.settle()
        assert -1 in painted_framed and below not in painted_framed
        painted_framed.clear()
        await session.pilot.press("l")  # the light, in the subtitle
        await session.settle()
        assert below in painted_framed and -1 not in painted_framed


async def test_a_slow_picture_says_it_is_being_drawn_until_it_comes(biceps, monkeypatch):
    render, drawn = SceneRenderer.render, threading.Event()

    def slow_phong(renderer, scene, width, height, framed=None, pixel_aspect=1.0):
        if scene.render.shading == "phong":  # as a first Phong frame compiles its kernels
            drawn.wait(30)
        return render(renderer, scene, width, height, framed, pixel_aspect)

    monkeypatch.setattr(SceneRenderer, "render", slow_phong)
    async with biceps() as session:
        viewport = session.app.screen.query_one(Viewport)
        assert "drawing" not in viewport.border_subtitle
        await session.pilot.press("g")
        try:
            await until(session.pilot, lambda: viewport.border_subtitle == "drawing…")
        finally:
            drawn.set()
        await session.settle()
        assert viewport.border_subtitle.startswith("phong")


def _as_textual_writes_it(app) -> Screen:
    """The screen as Textual would write all of it now."""
    strips = app.screen._compositor.render_strips()  # (private: Textual is pinned to 8.x)
    return Screen(*app.size).feed("".join(
        f"\x1b[{y + 1};1H{strip.render(app.console)}" for y, strip in enumerate(strips)
    ))


async def test_the_viewport_writes_a_frame_as_textual_would(biceps, private_path):
    written: list[str] = []
    async with biceps(size=(100, 30)) as session:
        app, viewport = session.app, session.app.screen.query_one(Viewport)
        app._driver.write = written.append  # headless: Textual itself writes nothing
        await session.pilot.press("right")  # a new picture, and a new title
        await session.settle()
        text = "".join(written)
        rows = {int(row) - 1 for row in LINE_WRITTEN.findall(text)}
        region = viewport.region
        assert region.y in rows  # the title's border row
        assert len(rows) > 10 and rows <= set(range(region.y, region.bottom))
        ours, textual = Screen(*app.size).feed(text), _as_textual_writes_it(app)
        for y in rows:
            assert (ours.cells[y][region.x:region.right]
                    == textual.cells[y][region.x:region.right]), f"row {y}"
        # Each frame all at once, where the terminal can.
        assert text.startswith("\x1b[?2026h") == app._sync_available


async def test_a_frame_goes_through_textual_while_something_is_over_the_picture(
        private_path, config, painted):
    written: list[str] = []
    app = BicepsApp(config)
    async with app.run_test(size=(100, 30), notifications=True) as pilot:
        viewport = app.screen.query_one(Viewport)
        app._driver.write = written.append  # headless: Textual itself writes nothing
        await _caught_up(pilot, viewport)
        app.notify("over the picture's lower right corner", timeout=0.5)
        await until(pilot, lambda: app.screen.query("Toast"))
        painted.clear()
        written.clear()
        await pilot.press("right")
        await _caught_up(pilot, viewport)
        assert painted  # by Textual
        assert not LINE_WRITTEN.findall("".join(written))
        await until(pilot, lambda: not app.screen.query("Toast"))  # the notification gone
        await pilot.press("right")
        await _caught_up(pilot, viewport)
        assert LINE_WRITTEN.findall("".join(written))
        assert viewport.border_title.startswith(f"yaw {app.scene.view.yaw:g}°")


async def _caught_up(pilot, viewport: Viewport) -> None:
    await until(pilot, lambda: viewport.up_to_date)
    await pilot.pause()


@pytest.mark.parametrize("size", [(80, 24), (200, 60)])
async def test_m_changes_the_picture_at_every_size(biceps, size):
    # Both pictures are small (at most 120 pixel rows), drawn 2 x 2 without anti-aliasing:
    # with it, 4 x 4.
    async with biceps(size=size) as session:
        viewport = session.app.screen.query_one(Viewport)
        rows = range(viewport.size.height)
        before = [viewport.render_line(y) for y in rows]
        assert "AA 2x2 (small)" in viewport.border_subtitle
        await session.pilot.press("m")
        await session.settle()
        assert "AA 4x4 (small)" in viewport.border_subtitle
        assert [viewport.render_line(y) for y in rows] != before
