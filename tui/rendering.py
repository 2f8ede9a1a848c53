"""The viewport's frames, apart from Textual: requested on the UI thread, drawn and encoded on
a render thread, handed over newest only, and paced by the terminal.

The UI asks for a frame of a scene at a size (:meth:`Frames.request`) as often as keys
repeat or the mouse drags. One render thread (:meth:`Frames.serve`) owns a
:class:`~engine.scene_renderer.SceneRenderer` and serves the requests through a
:class:`~tui.latest_only.LatestOnly` hand-over: it renders only the newest scene, and has
the encoder (``tui/encoder.py``) turn the frame into what the terminal is sent.

A frame is handed over only when the :class:`~tui.pacing.Pacer` says the terminal has
taken the last one (:meth:`Frames.written`); meanwhile the worker draws the next (the
newest request), so that only its encoding is left to do once the terminal has answered
(see `STALE_AFTER`).
"""

from __future__ import annotations

from dataclasses import dataclass
from time import monotonic
from typing import Any, Callable, Generic, Protocol, TypeVar

import numpy as np

from biceps.engine.config import rgb
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal.palette import Palette256
from biceps.tui.latest_only import LatestOnly
from biceps.tui.pacing import Pacer

BUSY_AFTER = 0.3
"""Seconds without a new frame, while one is wanted, before the picture is said to be
being drawn: a first Phong frame compiles its kernels, a muscle of many nodes takes long."""

STALE_AFTER = 2 / 60
"""Seconds after which a frame drawn ahead is drawn again if a newer scene is waiting by
the time the terminal has taken the last frame. A frame waits up to one of Textual's
updates (a 60th of a second) to be written, and a local terminal answers within a
millisecond or two: its frames drawn ahead are shown as drawn. Over a slow link the answer
takes as long as the frame takes to cross it (75 ms for 47 KB at 5 Mbit/s), and a frame
drawn that long ago would show the keys that late."""

P = TypeVar("P")  # what the encoder makes of a frame (tui/encoder.py's Picture)


class Encoder(Protocol[P]):
    """What the render thread needs of a :class:`~tui.encoder.PictureEncoder`."""

    def encode(self, frame: np.ndarray) -> P: ...

    def reset(self) -> None: ...


@dataclass(frozen=True)
class Request:
    number: int
    scene: Scene
    width: int  # pixels
    height: int  # pixels
    aspect: float  # a pixel's width over its height on the screen


@dataclass(frozen=True)
class Rendered(Generic[P]):
    """Request ``number``'s frame, of ``scene``, ``height`` pixels tall, as ``picture``."""

    number: int
    scene: Scene
    picture: P
    height: int  # pixels


@dataclass(frozen=True)
class Failed:
    """Request ``number`` could not be drawn or encoded, for ``reason``."""

    number: int
    reason: str


@dataclass(frozen=True)
class _Drawn:
    request: Request
    frame: np.ndarray | Exception  # (h, w, 3) uint8, or what stopped it being drawn
    at: float  # seconds, on the frames' clock


class Frames(Generic[P]):
    """The frames of one viewport: its requests, its render thread and their pacing.

    :meth:`serve` runs on the render thread; every other method on the UI thread.
    """

    def __init__(self, encoder: Encoder[P], pacer: Pacer, palette: Palette256 | None = None,
                 clock: Callable[[], float] = monotonic,
                 renderer: Callable[[], SceneRenderer] | None = None) -> None:
        """``encoder`` turns frames into pictures, on the render thread only; ``pacer`` says
        when the next may be handed over; ``palette``: the colours a frame is mapped onto
        as a whole (a 256-colour terminal), or None for 24-bit colour; ``clock``: seconds,
        read on both threads, for when a frame is late (:meth:`busy`) or stale;
        ``renderer`` makes the render thread's renderer, closed when it is done (a
        :class:`SceneRenderer` of its own if None)."""
        self._encoder, self._pacer, self._palette, self._clock = encoder, pacer, palette, clock
        self._renderer = renderer
        self._requests: LatestOnly[Request] = LatestOnly()
        self.requested = 0  # the number of the newest request
        self.shown = 0  # the number of the request whose frame (or failure) came last
        self._progress_at = 0.0  # when the last frame came, or the wait for one began

    @property
    def up_to_date(self) -> bool:
        """Whether the frame shown is that of the latest request."""
        return self.shown == self.requested

    def request(self, scene: Scene, width: int, height: int, aspect: float) -> None:
        """Ask for a frame of ``scene``, ``width x height`` pixels, each ``aspect`` times as
        wide as tall on the screen; it replaces any request not yet taken."""
        if self.up_to_date:
            self._progress_at = self._clock()
        self.requested += 1
        self._requests.put(Request(self.requested, scene, width, height, aspect))

    def busy(self) -> bool:
        """Whether a frame has been wanted for :data:`BUSY_AFTER` seconds without one
        coming."""
        return not self.up_to_date and self._clock() - self._progress_at >= BUSY_AFTER

    def arrived(self, result: Rendered[P] | Failed) -> None:
        """``result``, handed over by :meth:`serve`, is on its way to the screen. A
        failure is done with at once; a frame once :meth:`written`."""
        self.shown = result.number
        self._progress_at = self._clock()
        if isinstance(result, Failed):
            self._requests.done()

    def written(self) -> None:
        """The last frame is written: the next is handed over once the terminal has taken
        it (the pacer)."""
        self._pacer.after_frame(self._requests.done)

    def close(self) -> None:
        """Release the render thread: :meth:`serve` returns."""
        self._requests.close()

    def serve(self, deliver: Callable[[Rendered[P] | Failed], Any]) -> None:
        """Draw and encode the requests, newest only, and ``deliver`` each result, one at a
        time, until :meth:`close`. Run on the render thread."""
        # Both keep what they need from one frame to the next (buffers, the lines on
        # screen), so they are this thread's own (see PictureEncoder for the exceptions).
        renderer, requests = (self._renderer or SceneRenderer)(), self._requests
        try:
            request = requests.take()
            while request is not None:
                # Drawn ahead, while the UI waits for the terminal to take the last frame:
                # once it has, the next is only encoded (every encoded frame is shown, in
                # order: the encoder sends the rows that changed since the last), not drawn
                # too.
                drawn = self._drawn(renderer, request)
                if not requests.hand_over():
                    return
                if (self._clock() - drawn.at > STALE_AFTER
                        and (newer := requests.newer()) is not None):
                    drawn = self._drawn(renderer, newer)
                deliver(self._encoded(drawn))
                request = requests.take()
        finally:
            renderer.close()

    def _drawn(self, renderer: SceneRenderer, request: Request) -> _Drawn:
        """The frame of ``request``, valid until ``renderer`` draws again, or the error
        that stopped it."""
        try:
            frame = renderer.render(request.scene, request.width, request.height,
                                    pixel_aspect=request.aspect)
            if self._palette is not None:
                frame = self._palette.mapped(frame, rgb(request.scene.render.background))
        except Exception as error:
            return _Drawn(request, error, self._clock())
        return _Drawn(request, frame, self._clock())

    def _encoded(self, drawn: _Drawn) -> Rendered[P] | Failed:
        request, frame = drawn.request, drawn.frame
        try:
            if isinstance(frame, Exception):
                raise frame
            return Rendered(request.number, request.scene, self._encoder.encode(frame),
                            request.height)
        except Exception as error:
            # Whatever goes wrong in one frame, the app and the edits must survive it,
            # and the next scene may well render: report it and carry on. The encoder
            # may have failed halfway, so what it kept no longer matches the screen.
            self._encoder.reset()
            return Failed(request.number, f"{type(error).__name__}: {error}")
