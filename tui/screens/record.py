"""The record dialog: the options of ``biceps animate``, one compact line each.

Seven fields in the usual form would not fit a 24-row terminal, so each is a label and a
one-line input side by side. The values are read and checked as in any :class:`Prompt`: a
refusal (an odd frame count for a bounce, an angle the arm cannot reach) is said while the
dialog is still open.
"""

from __future__ import annotations

from pathlib import Path
from typing import Awaitable, Callable

from textual.app import ComposeResult
from textual.containers import Grid
from textual.widgets import Input, Label

from biceps.engine.animate import FlexCycle, check_cycle
from biceps.engine.bounds import exactly
from biceps.engine.errors import shown
from biceps.engine.export import parse_size
from biceps.engine.movie import ANIMATION_FORMATS, check_animation
from biceps.engine.names import printable
from biceps.engine.scene import Scene
from biceps.engine.sweep import flexion_range
from biceps.tui.parse import parse_number, parse_path
from biceps.tui.screens.prompt import LONGEST, PRINTABLE, Field, Prompt
from biceps.tui.suggest import PathSuggester
from biceps.tui.widgets.recorder import Recording

MOTIONS = {"bounce": True, "loop": False}


def parse_frames(text: str) -> int:
    """A whole number of frames, 2 or more."""
    try:
        frames = int(text)
    except ValueError:
        raise ValueError(f"{shown(text)} is not a whole number") from None
    if frames < 2:
        raise ValueError(f"a cycle needs at least 2 frames, not {frames}")
    return frames


def parse_motion(text: str) -> bool:
    """``bounce`` (there and back: True) or ``loop`` (there, then from the start: False)."""
    motion = text.strip().lower()
    if motion not in MOTIONS:
        raise ValueError(f"{shown(text)}: write bounce or loop")
    return MOTIONS[motion]


def as_recording(path: Path, size: tuple[int, int], start: float, end: float, frames: int,
                 fps: float, bounce: bool) -> Recording:
    """The dialog's values as a :class:`Recording`; raises :class:`BicepsError` if the cycle
    cannot be played."""
    return Recording(path, *size, FlexCycle(start, end, frames, bounce), fps)


class RecordPrompt(Prompt):
    """Asks where and how to record the flex cycle of ``scene``; dismisses with the values
    for :func:`as_recording`, or None when cancelled. ``last`` fills the fields as they were
    the last time; ``read`` is the model's file, which a recording may not replace;
    ``replace`` asks whether to replace a file that exists (True to)."""

    def __init__(self, scene: Scene, default_path: Path, last: Recording | None = None, *,
                 read: Path | None = None,
                 replace: Callable[[Path], Awaitable[bool]]) -> None:
        least, most = flexion_range(scene.arm)
        if last is None:
            last = Recording(default_path, 640, 360, FlexCycle(least, most, 60), 25.0)
        cycle = last.cycle
        fields = [
            Field("File", printable(last.path), parse_path, PathSuggester(ANIMATION_FORMATS)),
            Field("Size in pixels", f"{last.width}x{last.height}", parse_size),
            # Every digit of an end worked back from a length limit, which rounded to six
            # digits could fall outside the range and be refused.
            Field("From, degrees", exactly(cycle.start), parse_number),
            Field("To, degrees", exactly(cycle.end), parse_number),
            Field("Frames", str(cycle.frames), parse_frames),
            Field("Frames a second", f"{last.fps:g}", parse_number),
            Field("Bounce or loop", "bounce" if cycle.bounce else "loop", parse_motion),
        ]
        self._scene, self._read = scene, read
        self._replace = replace
        super().__init__("Record the flex cycle", fields, accept="Record", check=self._check)

    def compose_fields(self) -> ComposeResult:
        with Grid(classes="record-fields"):
            for field in self._fields:
                yield Label(field.label)
                yield Input(field.text, suggester=field.suggester, compact=True,
                            restrict=PRINTABLE, max_length=LONGEST)
        yield Label(f"As {', '.join(ANIMATION_FORMATS)}; MP4 needs biceps[video].",
                    classes="record-note", markup=False)

    async def _check(self, *values) -> bool:
        recording = as_recording(*values)
        check_animation(recording.path, recording.width, recording.height, recording.fps,
                        self._read)
        check_cycle(self._scene, recording.cycle, recording.width, recording.height)
        return not recording.path.exists() or await self._replace(recording.path)
