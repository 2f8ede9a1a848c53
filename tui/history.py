"""Undo and redo for the model: the arms that edits replaced, and those that undoing replaced.

Arms are immutable, so the history holds them as they are, sharing what they share (every
length of one muscle shares its reference shape). A run of length changes, a key held down
or tapped quickly, is one step: undo takes the muscle back to where the run began, as an
editor undoes a burst of typing at once.
"""

from __future__ import annotations

from collections import deque
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
        # The oldest undo step goes first when there are too many nodes: a deque drops it
        # at no cost, and the count of the nodes kept is kept up to date, not summed again
        # at each edit, so that an edit costs the same however long the history is.
        self._undo: deque[Step] = deque()
        self._redo: list[Step] = []
        self._kept = 0  # the nodes of every arm in self._undo

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
        self._push(Step(before, what, run, at))
        while len(self._undo) > 1 and self._kept > KEPT_NODES:
            self._kept -= _nodes(self._undo.popleft())

    def undo(self, current: Arm) -> Step | None:
        """The step to go back to (its arm, and what is undone), or None if there is none."""
        if not self._undo:
            return None
        step = self._undo.pop()
        self._kept -= _nodes(step)
        self._redo.append(Step(current, step.what))
        return step

    def redo(self, current: Arm) -> Step | None:
        """The step undone last, to do again, or None if there is none."""
        if not self._redo:
            return None
        step = self._redo.pop()
        self._push(Step(current, step.what))
        return step

    def clear(self) -> None:
        self._undo.clear()
        self._redo.clear()
        self._kept = 0

    def _push(self, step: Step) -> None:
        self._undo.append(step)
        self._kept += _nodes(step)


def _nodes(step: Step) -> int:
    # Every muscle's nodes: an arm of several muscles keeps each one's arrays.
    return sum(muscle.node_count for muscle in step.arm.muscles)
