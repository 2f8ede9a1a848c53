"""Recording the flex cycle to a file in the background, with a line of progress meanwhile.

The frames are rendered and encoded in a worker thread (the kernels release the GIL, and so
does most of Pillow's encoding), so the picture and the keys go on answering. The worker
reports by message; quitting cancels it between two frames, and then no file is written.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from textual import work
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.content import Content
from textual.message import Message
from textual.widgets import Label, ProgressBar
from textual.worker import get_current_worker

from biceps.engine.animate import FlexCycle, render_cycle
from biceps.engine.errors import BicepsError
from biceps.engine.movie import Progress, write_animation
from biceps.engine.names import printable
from biceps.engine.scene import Scene


@dataclass(frozen=True)
class Recording:
    """What to record: the cycle, into which file, at what size and frame rate."""

    path: Path
    width: int
    height: int
    cycle: FlexCycle
    fps: float

    def __str__(self) -> str:
        return (f"{printable(self.path)} ({self.width}x{self.height}, {self.cycle.frames} frames at "
                f"{self.fps:g} a second)")


class _Cancelled(Exception):
    """The app is closing: stop between two frames."""


class Recorder(Horizontal):
    """Hidden until :meth:`record` starts; then a label and a bar until the file is written."""

    class Progressed(Message, bubble=False):
        def __init__(self, stage: str, done: int, total: int) -> None:
            super().__init__()
            self.stage, self.done, self.total = stage, done, total

    class Ended(Message, bubble=False):
        def __init__(self, note: str, failed: bool) -> None:
            super().__init__()
            self.note, self.failed = note, failed

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._recording: Recording | None = None

    @property
    def busy(self) -> Recording | None:
        """The recording being written, if any."""
        return self._recording

    def compose(self) -> ComposeResult:
        yield Label()
        yield ProgressBar(show_eta=False)

    def record(self, scene: Scene, recording: Recording) -> None:
        """Start writing ``recording`` of ``scene`` (not while another is being written)."""
        if self._recording is not None:
            raise BicepsError(f"still recording {printable(self._recording.path)}; wait for it to finish")
        self._recording = recording
        self.add_class("-busy")
        self._show("rendering", 0, len(recording.cycle.poses()))
        self._write(scene, recording)

    @work(thread=True, exclusive=True, group="record")
    def _write(self, scene: Scene, recording: Recording) -> None:
        worker = get_current_worker()

        def progress(stage: str) -> Progress:
            def tell(done: int, total: int) -> None:
                if worker.is_cancelled:
                    raise _Cancelled
                self.post_message(self.Progressed(stage, done, total))
            return tell

        try:
            frames = render_cycle(scene, recording.cycle, recording.width, recording.height,
                                  progress("rendering"))
            write_animation(recording.path, frames, recording.fps, progress("encoding"))
        except _Cancelled:
            return
        except BicepsError as error:
            reason = str(error)
        except MemoryError:
            reason = f"not enough memory for {recording}"
        except Exception as error:
            # Whatever breaks in a recording, the app and the edits in it must survive.
            reason = f"{type(error).__name__}: {error}"
        else:
            self.post_message(self.Ended(f"Recorded {recording}", failed=False))
            return
        self.post_message(self.Ended(reason, failed=True))

    def on_recorder_progressed(self, message: Progressed) -> None:
        self._show(message.stage, message.done, message.total)

    def on_recorder_ended(self, message: Ended) -> None:
        path, self._recording = self._recording.path, None
        self.remove_class("-busy")
        if message.failed:
            self.notify(message.note, title="Not recorded", severity="error", markup=False)
        else:
            if self.app.is_web:  # under biceps serve: to the browser, as a download
                self.app.deliver_binary(path)
            self.notify(message.note, markup=False)

    def _show(self, stage: str, done: int, total: int) -> None:
        # Content, not a str, which a Label reads as markup: a file may be named [b]x.gif.
        name = printable(self._recording.path.name)
        self.query_one(Label).update(Content(f"Recording {name}: {stage}"))
        self.query_one(ProgressBar).update(total=total, progress=done)
