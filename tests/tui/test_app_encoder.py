"""The viewport works with any picture encoder: frames of its cells times the encoder's cell,
the encoder's lines on screen, its image and its clearing written to the terminal."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.app import App, ComposeResult
from textual.geometry import Size
from textual.strip import Strip

from biceps.engine.config import Config
from biceps.engine.scene import Scene
from biceps.tui.encoder import Picture, PictureEncoder
from biceps.tui.pacing import Pacer
from biceps.tui.widgets.viewport import Viewport
from waiting import until


class Corners:
    """Two pixels wide and four tall to a cell, each shown as a space on the colour of its
    top-left pixel; records the frames it is given."""

    cell = Size(2, 4)
    aspect = 1.0

    def __init__(self, image: str = "", clearing: str = "", fail: bool = False) -> None:
        self.image, self.clearing, self.fail = image, clearing, fail
        self.shapes: list[tuple[int, ...]] = []
        self.resets = 0
        self.last: Picture | None = None

    def encode(self, frame: np.ndarray) -> Picture:
        self.shapes.append(frame.shape)
        if self.fail:
            self.fail = False
            raise ValueError("halfway")
        strips = [
            Strip([Segment(" ", Style(bgcolor=Color.from_rgb(*pixel))) for pixel in row[::2]])
            for row in frame[::4].tolist()
        ]
        self.last = Picture(strips, [(0, len(strips))], self.image)
        return self.last

    def reset(self) -> None:
        self.resets += 1

    def clear(self) -> str:
        return self.clearing


class OneViewport(App[None]):
    CSS = "Viewport { width: 1fr; height: 1fr; margin: 1 2; }"

    def __init__(self, scene: Scene, encoder: PictureEncoder) -> None:
        super().__init__()
        self.scene, self.encoder = scene, encoder
        self.pacer = Pacer(lambda column: False, self.set_timer)  # no terminal to ask
        self.written: list[str] = []

    def compose(self) -> ComposeResult:
        yield Viewport(self.pacer, encoder=self.encoder)

    def on_mount(self) -> None:
        self._driver.write = self.written.append  # headless: nothing reaches a terminal
        self.query_one(Viewport).show(self.scene)


async def _shown(app: OneViewport, pilot) -> Viewport:
    viewport = app.query_one(Viewport)
    await until(pilot, lambda: viewport.up_to_date, "the picture caught up with the scene")
    await pilot.pause()
    return viewport


async def test_frames_are_the_cells_times_the_encoders_cell_and_its_lines_are_shown(
    config: Config,
):
    encoder = Corners()
    app = OneViewport(Scene.of(config), encoder)
    async with app.run_test(size=(34, 12)) as pilot:
        viewport = await _shown(app, pilot)
        assert viewport.size == (30, 10)  # the margin taken off
        assert encoder.shapes[-1] == (40, 60, 3)
        assert [viewport.render_line(y) for y in range(10)] == encoder.last.strips
        await pilot.resize_terminal(44, 8)
        await _shown(app, pilot)
        assert encoder.shapes[-1] == (24, 80, 3)
        assert viewport.render_line(5).cell_length == 40


async def test_the_image_is_written_at_the_pictures_corner_and_cleared_at_the_end(
    private_path: None, config: Config,
):
    app = OneViewport(Scene.of(config), Corners(image="<image>", clearing="<clear>"))
    async with app.run_test(size=(34, 12)) as pilot:
        await _shown(app, pilot)
        images = [text for text in app.written if "<image>" in text]
        assert images == ["\x1b7\x1b[2;3H<image>\x1b8"]  # below and right of the margin
        assert "<clear>" not in app.written
    assert "<clear>" in app.written


async def test_after_a_failed_frame_the_encoder_starts_afresh(config: Config):
    encoder = Corners(fail=True)
    app = OneViewport(Scene.of(config), encoder)
    async with app.run_test(size=(34, 12)) as pilot:
        viewport = await _shown(app, pilot)
        assert encoder.resets == 1
        viewport.show(app.scene)
        await _shown(app, pilot)
        assert viewport.render_line(5) is encoder.last.strips[5]


async def test_a_drag_is_measured_in_picture_heights_whatever_the_cell(config: Config):
    app = OneViewport(Scene.of(config), Corners())
    messages: list[object] = []
    async with app.run_test(size=(34, 12), message_hook=messages.append) as pilot:
        viewport = await _shown(app, pilot)
        move = SimpleNamespace(button=1, delta_x=5, delta_y=2, ctrl=False, shift=False,
                               meta=False)
        viewport.on_mouse_move(move)
        await pilot.pause()
    dragged = next(message for message in messages if isinstance(message, Viewport.Dragged))
    # 5 cells of 2 pixels across, 2 of 10 rows down, in a picture 40 pixels tall.
    assert (dragged.across, dragged.down) == (5 * 2 / 40, 2 / 10)
