"""The picture: the scene rendered off the UI thread and shown as half-block pixels.

A widget of ``w x h`` cells shows a frame of ``w x 2h`` pixels (cells are about twice as
tall as wide, so the pixels are about square). One worker thread owns a
:class:`~engine.scene.SceneRenderer` and serves requests through a :class:`LatestOnly`
hand-over: however fast keys repeat or the mouse drags, it renders only the newest scene,
and a new frame replaces the shown one in a single refresh.
"""

from __future__ import annotations

from dataclasses import dataclass

from rich.color import Color
from rich.style import Style
from textual import events, work
from textual.message import Message
from textual.strip import Strip
from textual.widget import Widget

from engine.config import rgb
from engine.scene import Scene, SceneRenderer
from tui.halfblocks import frame_to_strips
from tui.latest_only import LatestOnly


@dataclass(frozen=True)
class _Request:
    number: int
    scene: Scene
    width: int  # cells
    height: int  # cells


class Viewport(Widget, can_focus=True):
    """Shows a :class:`Scene`; drags and wheel turns become messages for the app to act on."""

    ALLOW_SELECT = False  # a drag turns the model; it does not select text

    class FrameRendered(Message, bubble=False):
        def __init__(self, number: int, strips: list[Strip]) -> None:
            super().__init__()
            self.number = number
            self.strips = strips

    class RenderFailed(Message, bubble=False):
        def __init__(self, number: int, reason: str) -> None:
            super().__init__()
            self.number = number
            self.reason = reason

    class Dragged(Message):
        """The mouse moved with a button held; ``pan`` to move the model, else to turn it.

        ``across`` and ``down`` are in picture heights, so a drag of the same length on
        screen means the same whichever way it goes (a cell is two pixels tall, one wide).
        """

        def __init__(self, across: float, down: float, pan: bool) -> None:
            super().__init__()
            self.across = across
            self.down = down
            self.pan = pan

    class Zoomed(Message):
        """The wheel turned by ``steps`` notches (positive: scroll up, towards bigger)."""

        def __init__(self, steps: int) -> None:
            super().__init__()
            self.steps = steps

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._scene: Scene | None = None
        self._requests: LatestOnly[_Request] = LatestOnly()
        self._requested = 0  # the number of the newest request
        self._shown = 0  # the number of the request whose frame is on screen
        self._strips: list[Strip] = []
        self._background = Style()

    @property
    def up_to_date(self) -> bool:
        """Whether the frame on screen is that of the latest scene and size."""
        return self._shown == self._requested

    def show(self, scene: Scene) -> None:
        self._scene = scene
        self._background = Style(bgcolor=Color.from_rgb(*rgb(scene.render.background)))
        self._request_frame()

    def on_mount(self) -> None:
        self._render_frames()

    def on_unmount(self) -> None:
        self._requests.close()

    def on_resize(self) -> None:
        self._request_frame()

    def _request_frame(self) -> None:
        width, height = self.size
        if self._scene is None or not width or not height:
            return
        self._requested += 1
        self._requests.put(_Request(self._requested, self._scene, width, height))

    @work(thread=True, exclusive=True, group="render")
    def _render_frames(self) -> None:
        renderer = SceneRenderer()  # not thread-safe: this thread's own
        while (request := self._requests.take()) is not None:
            try:
                frame = renderer.render(request.scene, request.width, 2 * request.height)
                message = self.FrameRendered(request.number, frame_to_strips(frame))
            except Exception as error:
                # Whatever goes wrong in one frame, the app and the edits must survive it,
                # and the next scene may well render: report it and carry on.
                message = self.RenderFailed(request.number, f"{type(error).__name__}: {error}")
            self.post_message(message)

    def on_viewport_frame_rendered(self, message: FrameRendered) -> None:
        self._requests.done()
        self._strips = message.strips
        self._shown = message.number
        self.refresh()

    def on_viewport_render_failed(self, message: RenderFailed) -> None:
        self._requests.done()
        self._shown = message.number
        self.notify(f"The picture cannot be drawn: {message.reason}", severity="error",
                    markup=False)

    def render_line(self, y: int) -> Strip:
        width = self.size.width
        if y >= len(self._strips):
            return Strip.blank(width, self._background)
        strip = self._strips[y]
        if strip.cell_length == width:
            return strip
        # A frame of the old size, until the one for the new size arrives.
        return strip.crop_extend(0, width, self._background)

    def on_mouse_down(self, event: events.MouseDown) -> None:
        self.capture_mouse()

    def on_mouse_up(self, event: events.MouseUp) -> None:
        self.release_mouse()

    def on_mouse_move(self, event: events.MouseMove) -> None:
        rows = self.size.height
        if not event.button or not (event.delta_x or event.delta_y) or not rows:
            return
        # Shift-drag is often taken by the terminal for selecting text, so every modifier
        # and the other buttons pan too.
        pan = event.button != 1 or event.ctrl or event.shift or event.meta
        self.post_message(self.Dragged(event.delta_x / (2 * rows), event.delta_y / rows, pan))

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        event.stop()
        self.post_message(self.Zoomed(1))

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        event.stop()
        self.post_message(self.Zoomed(-1))
