"""The viewport repaints only the lines a new frame changed, and nothing for the same frame."""

from __future__ import annotations

import time

import pytest

from textual._compositor import ChopsUpdate

from biceps.engine.scene import SceneRenderer
from biceps.tui.widgets.viewport import Viewport


def _record_painted(monkeypatch, border: int) -> list[int]:
    """Every line of the viewport's picture Textual writes to the terminal, in order, and
    ``border`` rows above and below it."""
    lines: list[int] = []
    repainted = Viewport.repainted

    def recording(viewport, update):
        area = viewport.content_region
        if isinstance(update, ChopsUpdate):
            rows = [y for y, x1, x2 in update.spans if x1 < area.right and x2 >= area.x]
        else:
            rows = list(range(area.y - border, area.bottom + border))
        lines.extend(y - area.y for y in rows if area.y - border <= y < area.bottom + border)
        return repainted(viewport, update)

    monkeypatch.setattr(Viewport, "repainted", recording)
    return lines


@pytest.fixture
def painted(monkeypatch) -> list[int]:
    """Every picture line Textual writes to the terminal, in order."""
    return _record_painted(monkeypatch, 0)


@pytest.fixture
def painted_framed(monkeypatch) -> list[int]:
    """The same, and the border's rows above (-1) and below the picture."""
    return _record_painted(monkeypatch, 1)


async def test_a_new_frame_repaints_only_the_lines_that_changed(biceps, painted):
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


async def test_a_caption_s_row_is_repainted_only_when_it_changes(biceps, painted_framed):
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
    render = SceneRenderer.render

    def slow_phong(renderer, scene, width, height):
        if scene.render.shading == "phong":  # as a first Phong frame compiles its kernels
            time.sleep(1.0)
        return render(renderer, scene, width, height)

    monkeypatch.setattr(SceneRenderer, "render", slow_phong)
    async with biceps() as session:
        viewport = session.app.screen.query_one(Viewport)
        assert "drawing" not in viewport.border_subtitle
        await session.pilot.press("g")
        await session.pilot.pause(0.6)
        assert viewport.border_subtitle == "drawing…"
        await session.settle()
        assert viewport.border_subtitle.startswith("phong")
