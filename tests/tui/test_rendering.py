"""The viewport's frames apart from Textual (tui/rendering.py): no app, a stand-in renderer."""

from __future__ import annotations

import queue
import subprocess
import sys
import threading
from types import SimpleNamespace

import numpy as np
import pytest

import biceps.tui.rendering
from biceps.tui.pacing import Pacer
from biceps.tui.rendering import BUSY_AFTER, Failed, Frames, Rendered

WAIT = 10.0  # seconds a test waits for the render thread at most


class Renderer:
    """Stands in for SceneRenderer: a frame filled with the scene (a number), counted."""

    drawn: list[int] = []
    started = threading.Semaphore(0)  # released as each frame is drawn

    def render(self, scene, width, height, pixel_aspect=1.0):
        if scene < 0:
            raise ValueError("no such scene")
        Renderer.drawn.append(scene)
        Renderer.started.release()
        return np.full((height, width, 3), scene, np.uint8)

    def close(self) -> None:
        pass


class Encoder:
    """The frame's value and shape as its picture; fails on a frame of 99."""

    def __init__(self) -> None:
        self.resets = 0

    def encode(self, frame: np.ndarray) -> tuple[int, tuple[int, ...]]:
        if frame[0, 0, 0] == 99:
            raise RuntimeError("cannot encode")
        return int(frame[0, 0, 0]), frame.shape

    def reset(self) -> None:
        self.resets += 1


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture(autouse=True)
def renderer(monkeypatch):
    monkeypatch.setattr(biceps.tui.rendering, "SceneRenderer", Renderer)
    monkeypatch.setattr(Renderer, "drawn", [])
    monkeypatch.setattr(Renderer, "started", threading.Semaphore(0))


def _unpaced() -> Pacer:
    """A pacer with no terminal to ask and no cap: each frame is released at once."""
    return Pacer(lambda column: False, lambda delay, release: release())


class Served:
    """``frames`` served on a thread of their own, what they deliver in ``results``."""

    def __init__(self, frames: Frames) -> None:
        self.frames = frames
        self.results: queue.Queue = queue.Queue()
        self.thread = threading.Thread(target=frames.serve, args=(self.results.put,))
        self.thread.start()

    def next(self):
        return self.results.get(timeout=WAIT)

    def drawn(self, count: int) -> None:
        """Wait until ``count`` more frames have been drawn."""
        for _ in range(count):
            assert Renderer.started.acquire(timeout=WAIT), "never drawn"

    def close(self) -> None:
        self.frames.close()
        self.thread.join(WAIT)
        assert not self.thread.is_alive()


@pytest.fixture
def served():
    made = []

    def serve(frames: Frames) -> Served:
        made.append(Served(frames))
        return made[-1]

    yield serve
    for one in made:
        one.close()


def test_a_frame_is_drawn_at_the_size_asked_and_encoded(served):
    frames = Frames(Encoder(), _unpaced())
    frames.request(7, 4, 6, 1.0)
    result = served(frames).next()
    assert result == Rendered(1, 7, (7, (6, 4, 3)), 6)
    assert not frames.up_to_date  # until it arrives
    frames.arrived(result)
    assert frames.up_to_date


def test_only_the_newest_of_requests_made_meanwhile_is_drawn(served):
    frames = Frames(Encoder(), _unpaced())
    for scene in (1, 2, 3):
        frames.request(scene, 2, 2, 1.0)
    result = served(frames).next()
    assert (result.number, result.picture[0]) == (3, 3)
    assert Renderer.drawn == [3]


def test_the_next_frame_is_drawn_ahead_but_handed_over_only_once_the_last_is_written(
        served):
    frames = Frames(Encoder(), _unpaced())
    frames.request(1, 2, 2, 1.0)
    serving = served(frames)
    frames.arrived(serving.next())
    frames.request(2, 2, 2, 1.0)
    serving.drawn(2)  # the second frame is drawn...
    assert serving.results.empty()  # ...and held: the first is not written yet
    frames.written()
    assert serving.next().picture[0] == 2


@pytest.mark.parametrize("stale_after, shown", [(60.0, 2), (0.0, 3)])
def test_a_frame_drawn_ahead_too_long_ago_is_drawn_again_from_the_newest_request(
        served, monkeypatch, stale_after, shown):
    monkeypatch.setattr(biceps.tui.rendering, "STALE_AFTER", stale_after)
    frames = Frames(Encoder(), _unpaced())
    frames.request(1, 2, 2, 1.0)
    serving = served(frames)
    frames.arrived(serving.next())
    frames.request(2, 2, 2, 1.0)
    serving.drawn(2)  # drawn ahead, waiting for the first to be written
    frames.request(3, 2, 2, 1.0)
    frames.written()
    result = serving.next()
    assert (result.number, result.picture[0]) == (shown, shown)


def test_a_frame_that_fails_is_reported_and_the_next_is_drawn(served):
    encoder = Encoder()
    frames = Frames(encoder, _unpaced())
    frames.request(-1, 2, 2, 1.0)
    serving = served(frames)
    failure = serving.next()
    assert failure == Failed(1, "ValueError: no such scene")
    assert encoder.resets == 1  # what it kept may no longer match the screen
    frames.arrived(failure)  # done with at once: nothing is written
    assert frames.up_to_date
    frames.request(99, 2, 2, 1.0)  # the encoder fails this time
    failure = serving.next()
    assert failure == Failed(2, "RuntimeError: cannot encode")
    assert encoder.resets == 2
    frames.arrived(failure)
    frames.request(5, 2, 2, 1.0)
    assert serving.next().picture[0] == 5


def test_the_frames_are_paced_by_the_terminal(served):
    asked = []

    def ask(column: int) -> bool:
        asked.append(column)
        return True

    # The wait for an answer never runs out here.
    pacer = Pacer(ask, lambda delay, release: SimpleNamespace(stop=lambda: None))
    frames = Frames(Encoder(), pacer)
    frames.request(1, 2, 2, 1.0)
    serving = served(frames)
    frames.arrived(serving.next())
    frames.written()
    assert asked == [1]  # the terminal is asked where its cursor is
    frames.request(2, 2, 2, 1.0)
    serving.drawn(2)
    assert serving.results.empty()  # no answer yet: the second is held
    pacer.answered(1, 0)
    assert serving.next().picture[0] == 2


def test_a_picture_is_busy_once_wanted_a_while_without_one_coming():
    clock = Clock()
    frames = Frames(Encoder(), _unpaced(), clock=clock)
    frames.request(1, 2, 2, 1.0)
    clock.now = BUSY_AFTER / 2
    assert not frames.busy()
    frames.request(2, 2, 2, 1.0)  # still waiting since the first: the wait goes on
    clock.now = BUSY_AFTER
    assert frames.busy()
    frames.arrived(Rendered(2, 2, None, 2))
    assert not frames.busy()


def test_closing_releases_the_render_thread(served):
    frames = Frames(Encoder(), _unpaced())
    serving = served(frames)
    serving.close()  # (asserts the thread ended)


def test_the_frames_import_no_textual():
    code = ("import sys, biceps.tui.rendering; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'textual'))")
    process = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             timeout=120, check=True)
    assert process.stdout.strip() == "[]"
