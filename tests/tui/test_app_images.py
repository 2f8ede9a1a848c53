"""Real pixels in the app: an image painted over the picture is written only while the main
screen is on top, taken off when another screen comes up or the size changes, and written
again when Textual repaints the cells under it."""

from __future__ import annotations

import pytest

import numpy as np
from textual._compositor import ChopsUpdate, LayoutUpdate
from textual.geometry import Region, Size

from biceps.engine.config import Config
from biceps.tui.app import BicepsApp
from biceps.tui.pixels import ImageEncoder
from biceps.tui.widgets.viewport import Viewport
from waiting import until

# What only the private path does (tui/textual_private.py).
pytestmark = pytest.mark.usefixtures("private_path")


class Numbered(ImageEncoder):
    """Each frame's image is its number."""

    def __init__(self) -> None:
        super().__init__(Size(4, 8))
        self.frames = 0

    def image(self, frame: np.ndarray, columns: int, rows: int) -> str:
        self.frames += 1
        self.last = frame.copy()
        return f"<image {self.frames}>"

    def clear(self) -> str:
        return "<clear>"


async def _a_frame_written(app: BicepsApp, pilot) -> tuple[Viewport, list[str]]:
    """The viewport, once a frame's image has been written, and what is written to the
    terminal from then on."""
    written: list[str] = []
    app._driver.write = written.append
    viewport = app.query_one(Viewport)
    await until(pilot, lambda: viewport.up_to_date)
    await pilot.press("right")
    await until(pilot, lambda: viewport.up_to_date and _images(written))
    return viewport, written


def _images(written: list[str]) -> list[str]:
    return [text[text.index("<"):text.index(">") + 1] for text in written if "<" in text]


async def test_an_image_is_never_painted_over_another_screen(config: Config):
    encoder = Numbered()
    app = BicepsApp(config, encoder=encoder)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport, written = await _a_frame_written(app, pilot)
        await pilot.press("question_mark")
        await until(pilot, lambda: "<clear>" in _images(written))
        del written[:]
        shown = encoder.frames
        viewport.show(app.scene)  # a new frame, made while the help is over the picture
        await until(pilot, lambda: viewport.up_to_date and encoder.frames == shown + 1)
        await pilot.pause(0.1)
        assert _images(written) == []
        await pilot.press("escape")
        await until(pilot, lambda: f"<image {shown + 1}>" in _images(written))


def _half_cells(strip) -> list[tuple[tuple[int, int, int], tuple[int, int, int]]]:
    """A line of half-blocks as the colours of its cells' upper and lower halves."""
    cells = []
    for segment in strip:
        style = segment.style
        for character in segment.text:
            lower = style.bgcolor.get_truecolor()
            upper = style.color.get_truecolor() if character == "\u2580" else lower
            assert character in " \u2580"
            cells.append((tuple(upper), tuple(lower)))
    return cells


async def test_behind_another_screen_the_picture_shows_in_half_blocks(config: Config):
    encoder = Numbered()
    app = BicepsApp(config, encoder=encoder)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport, written = await _a_frame_written(app, pilot)
        frame, (columns, rows) = encoder.last, viewport.size
        blank = viewport.render_line(rows // 2)
        assert blank.text.strip() == ""
        await pilot.press("question_mark")
        await until(pilot, lambda: "<clear>" in _images(written))
        # Each half-cell's colour is one its pixels (4 x 8 a cell) make: within their range.
        lines = [_half_cells(viewport.render_line(y)) for y in range(rows)]
        assert all(len(line) == columns for line in lines)
        for y, line in enumerate(lines):
            for x, halves in enumerate(line):
                for half, colour in enumerate(halves):
                    pixels = frame[8 * y + 4 * half:8 * y + 4 * half + 4, 4 * x:4 * x + 4]
                    assert (pixels.min(axis=(0, 1)) <= colour).all(), (x, y, half)
                    assert (colour <= pixels.max(axis=(0, 1))).all(), (x, y, half)
        assert len({cell for line in lines for cell in line}) > 10  # the arm, not a blank
        await pilot.press("escape")
        await until(pilot, lambda: viewport.render_line(rows // 2).text.strip() == "")


async def test_a_resize_takes_the_old_image_off_before_the_new_one(config: Config):
    encoder = Numbered()
    app = BicepsApp(config, encoder=encoder)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport, written = await _a_frame_written(app, pilot)
        before = f"<image {encoder.frames}>"
        del written[:]
        await pilot.resize_terminal(90, 28)
        await until(pilot, lambda: viewport.up_to_date and len(_images(written)) > 1)
        await pilot.pause(0.1)
        # Taken off, then the new size's image; never the old size's again.
        assert _images(written) == ["<clear>", f"<image {encoder.frames}>"] != before


async def test_only_a_repaint_of_the_pictures_cells_writes_the_image_again(config: Config):
    app = BicepsApp(config, encoder=Numbered())
    async with app.run_test(size=(100, 30)) as pilot:
        viewport = app.query_one(Viewport)
        await until(pilot, lambda: viewport.up_to_date)
        await pilot.pause(0.1)
        written: list[str] = []
        app._driver.write = written.append
        area = viewport.content_region
        side = (area.y + 2, area.right + 3, area.right + 10)  # a line of the side panel
        border = (area.y - 1, area.x, area.right)  # the captions above the picture
        viewport.repainted(ChopsUpdate([], [side, border], []))
        viewport.repainted(LayoutUpdate([], Region(area.right + 1, 0, 10, 5)))
        assert _images(written) == []
        viewport.repainted(ChopsUpdate([], [(area.bottom - 1, area.right - 1, area.right + 5)],
                                       []))
        viewport.repainted(LayoutUpdate([], Region(0, 0, 100, 30)))
        x, y = area.offset
        assert written == [f"\x1b7\x1b[{y + 1};{x + 1}H<image 1>\x1b8"] * 2


async def test_notifications_keep_to_the_side_panel_over_real_pixels(config: Config):
    app = BicepsApp(config, encoder=Numbered())
    async with app.run_test(size=(100, 30), notifications=True) as pilot:
        app.notify("a notification long enough to wrap over several lines of the toast")
        # (laid out a refresh or two later: on a busy machine, later than a set pause)
        await until(pilot, lambda: app.screen.query("Toast") and
                    app.screen.query_one("Toast").region.width)
        toast = app.screen.query_one("ToastRack").query_one("Toast")
        assert toast.region.x >= app.query_one(Viewport).content_region.right


async def test_with_real_pixels_the_side_panel_stays_for_the_notifications(config: Config):
    app = BicepsApp(config, encoder=Numbered())
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.pause()
        assert app.screen.query_one("#side").display  # narrow, but the toasts need its room
        await pilot.press("h")
        assert not app.screen.query_one("#side").display  # unless asked
