"""Undo and redo for the model: the arms that edits replaced, and those that undoing replaced.

Arms are immutable, so the history holds them as they are, sharing what they share (every
length of one muscle shares its reference shape). A run of length changes, a key held down
or tapped quickly, is one step: undo takes the muscle back to where the run began, as an
editor undoes a burst of typing at once.
"""

from __future__ import annotations

from dataclasses import dataclass

from biceps.engine.arm import Arm

RUN_GAP = 1.0
"""Seconds: length changes closer together than this are one step. Longer than a
keyboard's delay before it repeats a held key (up to 0.66 s on X11's default)."""

KEPT_NODES = 2_000_000
"""The most nodes the history keeps, all steps together (a node is three float64s: about
50 MB): the oldest steps go first. At 15 nodes that is any number of steps; at 20,000,
a hundred."""


@dataclass(frozen=True)
class Step:
    """The arm before an edit, and what the edit was, in words: ``node 8 deleted``."""

    arm: Arm
    what: str
    run: bool = False  # a length change, which later ones close in time join
    at: float = 0.0  # when it was last joined (seconds, monotonic)


class History:
    def __init__(self) -> None:
        self._undo: list[Step] = []
        self._redo: list[Step] = []

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

    def record(self, before: Arm, what: str, *, run: bool = False, at: float = 0.0) -> None:
        """An edit replaced ``before``. A length change (``run``) at ``at`` seconds joins the
        step before it if that was one too, less than :data:`RUN_GAP` earlier."""
        self._redo.clear()
        last = self._undo[-1] if self._undo else None
        if run and last is not None and last.run and at - last.at < RUN_GAP:
            self._undo[-1] = Step(last.arm, last.what, run=True, at=at)
            return
        self._undo.append(Step(before, what, run, at))
        while len(self._undo) > 1 and _nodes(self._undo) > KEPT_NODES:
            del self._undo[0]

    def undo(self, current: Arm) -> Step | None:
        """The step to go back to (its arm, and what is undone), or None if there is none."""
        return _moved(self._undo, self._redo, current)

    def redo(self, current: Arm) -> Step | None:
        """The step undone last, to do again, or None if there is none."""
        return _moved(self._redo, self._undo, current)

    def clear(self) -> None:
        self._undo.clear()
        self._redo.clear()


def _moved(source: list[Step], target: list[Step], current: Arm) -> Step | None:
    if not source:
        return None
    step = source.pop()
    target.append(Step(current, step.what))
    return step


def _nodes(steps: list[Step]) -> int:
    # Every muscle's nodes: an arm of several muscles keeps each one's arrays.
    return sum(muscle.node_count for step in steps for muscle in step.arm.muscles)
