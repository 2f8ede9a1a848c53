"""The record key: the flex cycle of the current view written in the background."""

import threading

import numpy as np
import pytest
from textual.widgets import Input

from biceps.engine import movie
from biceps.engine.config import load_config
from biceps.engine.sweep import flexion_range
from biceps.tui.screens.record import RecordPrompt
from biceps.tui.widgets.recorder import Recorder
from decode import decoded
from waiting import until


async def _record(session, path, *, size="96x54", frames="8", motion="bounce") -> None:
    """Press v, fill the dialog (file, size, from, to, frames, rate, motion) and accept."""
    await session.pilot.press("v")
    await session.pilot.pause()
    assert isinstance(session.app.screen, RecordPrompt)
    values = [str(path), size, "0", "130", frames, "25", motion]
    for box, value in zip(session.app.screen.query(Input), values):
        box.value = value
    await session.pilot.press("enter")
    await session.pilot.pause()


async def _recorded(session) -> None:
    """Wait until the recording in progress, if any, is written."""
    workers = [worker for worker in session.app.workers if worker.group == "record"]
    if workers:  # an empty list would mean every worker, the render loop among them
        await session.app.workers.wait_for_complete(workers)
    await session.pilot.pause()


class Held:
    """A recording held once every pose is rendered, before it is encoded."""

    def __init__(self) -> None:
        self.rendered = threading.Event()  # set when a recording is held
        self.release = threading.Event()  # set by the test: encode it

    def write_when_released(self, *args, **kwargs) -> None:
        self.rendered.set()
        assert self.release.wait(timeout=60), "the test never released the recording"
        movie.write_animation(*args, **kwargs)


@pytest.fixture
def held(monkeypatch) -> Held:
    """Holds every recording before it is encoded until the test releases it."""
    held = Held()
    monkeypatch.setattr("biceps.tui.widgets.recorder.write_animation", held.write_when_released)
    return held


async def test_v_records_the_flex_cycle_while_the_app_keeps_answering(biceps, tmp_path, held):
    out = tmp_path / "cycle.gif"
    async with biceps() as session:
        app = session.app
        await _record(session, out)
        recorder = app.screen.query_one(Recorder)
        assert recorder.busy is not None and recorder.display
        await until(session.pilot, held.rendered.is_set)
        length, yaw = app.scene.arm.length, app.scene.view.yaw
        await session.pilot.press("C", "right", "p")
        await session.settle()  # the picture caught up with the keys
        assert app.scene.arm.length == pytest.approx(length - 1.0)
        assert app.scene.view.yaw == yaw + 5.0
        assert not out.exists()  # all while the recording was still being written
        held.release.set()
        await _recorded(session)
        assert recorder.busy is None and not recorder.display
        assert any(note.message.startswith(f"Recorded {out}") for note in session.notes)
    frames = decoded(out)
    assert len(frames) == 8 and frames[0].shape == (54, 96, 3)
    assert np.array_equal(frames[1], frames[7])  # a bounce: out and back


async def test_the_cycle_is_of_the_view_when_it_was_asked_for(biceps, tmp_path):
    async with biceps() as session:
        await session.pilot.press("right", "right")
        await _record(session, tmp_path / "turned.apng", frames="2", motion="loop")
        await _recorded(session)
        turned = decoded(tmp_path / "turned.apng")[0]
        await session.pilot.press("r")  # back to the file's view
        await _record(session, tmp_path / "plain.apng", frames="2", motion="loop")
        await _recorded(session)
    assert not np.array_equal(turned, decoded(tmp_path / "plain.apng")[0])


@pytest.mark.parametrize(("field", "value", "message"), [
    (4, "7", "needs an even number of frames, not 7"),
    (5, "60", "a GIF plays at most 50 frames a second"),
    (3, "150", "outside the joint's range"),
    (4, "many", "'many' is not a whole number"),
    (6, "sideways", "write bounce or loop"),
    (0, "cycle.avi", "must end in .gif, .apng, .webp, .mp4"),
])
async def test_a_refused_option_keeps_the_dialog_open_and_writes_nothing(
        biceps, tmp_path, field, value, message):
    folder = tmp_path / "out"
    folder.mkdir()
    async with biceps() as session:
        await session.pilot.press("v")
        await session.pilot.pause()
        boxes = list(session.app.screen.query(Input))
        boxes[0].value = str(folder / "cycle.gif")
        boxes[field].value = value if field else str(folder / value)
        await session.pilot.press("enter")
        await session.pilot.pause()
        assert isinstance(session.app.screen, RecordPrompt)
        assert message in session.app.screen.error
        assert session.app.screen_stack[0].query_one(Recorder).busy is None
    assert list(folder.iterdir()) == []


async def test_a_second_recording_waits_for_the_first(biceps, tmp_path, held):
    async with biceps() as session:
        await _record(session, tmp_path / "first.gif")
        await session.pilot.press("v")
        await session.pilot.pause()
        assert not isinstance(session.app.screen, RecordPrompt)
        assert any("Still recording" in warning for warning in session.warnings)
        held.release.set()
        await _recorded(session)
    assert (tmp_path / "first.gif").exists()


async def test_the_dialog_remembers_the_last_recording(biceps, tmp_path):
    async with biceps() as session:
        await _record(session, tmp_path / "cycle.webp", size="64x36", frames="4", motion="loop")
        await _recorded(session)
        await session.pilot.press("v")
        await session.pilot.pause()
        values = [box.value for box in session.app.screen.query(Input)]
        assert values == [str(tmp_path / "cycle.webp"), "64x36", "0", "130", "4", "25", "loop"]


async def test_a_range_limited_by_the_config_is_offered_whole_and_accepted(biceps, config_path,
                                                                        tmp_path):
    text = config_path.read_text()
    config_path.write_text(text.replace("# min_length = 28.0", "min_length = 28.0")
                           .replace("# max_length = 35.0", "max_length = 35.0"))
    async with biceps(on=load_config(config_path)) as session:
        await session.pilot.press("v")
        await session.pilot.pause()
        boxes = list(session.app.screen.query(Input))
        least, most = flexion_range(session.app.scene.arm)
        assert (float(boxes[2].value), float(boxes[3].value)) == (least, most)
        boxes[0].value, boxes[1].value = str(tmp_path / "limited.apng"), "64x36"
        await session.pilot.press("enter")
        await session.pilot.pause()
        await _recorded(session)
        assert session.warnings == []
    assert len(decoded(tmp_path / "limited.apng")) == 60


async def test_recording_over_a_file_asks_every_time_and_escape_goes_back(biceps, tmp_path):
    from biceps.tui.screens.choice import Choice

    path = tmp_path / "cycle.gif"
    path.write_bytes(b"keep me")
    async with biceps() as session:
        await _record(session, path, size="64x36", frames="4")
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("escape")
        assert isinstance(session.app.screen, RecordPrompt)  # back, with what was typed
        assert session.app.screen.query(Input).first().value == str(path)
        await session.pilot.press("escape")
        assert path.read_bytes() == b"keep me"
        await _record(session, path, size="64x36", frames="4")
        await session.pilot.press("y")
        await _recorded(session)
        await _record(session, path, size="64x36", frames="4")  # the same file again
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("escape", "escape")
    assert path.read_bytes() != b"keep me"
