"""A muscle that follows the elbow: its length is not chosen but set by the elbow's angle
and its own path, and it keeps its own volume with the same node law as the driver.

The biceps drives the elbow (its length sets the angle by the law of cosines, SPEC 2.3);
the other muscles of the elbow (the biceps' short head, the brachialis, the triceps' three
heads) go with it: at each angle every companion is solved, from its own rest shape, at the
length its path has there (``engine/path.py``), so each one's volume is exact at every
pose and no sequence of poses can drift.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.path import MusclePath

REACH_SAMPLES = 66
"""Flexions at which a companion's reach is checked across the joint's range (every 2
degrees over 0 to 130): a path's length is smooth in the angle, so its longest is found
to a hair."""


@dataclass(frozen=True)
class Companion:
    """A named muscle on its path, in its colour (``#rrggbb``), at the elbow's current
    flexion."""

    name: str
    muscle: Muscle
    path: MusclePath
    colour: str

    def at_flexion(self, flexion: float) -> Companion:
        """This companion with the elbow at ``flexion`` degrees."""
        return replace(self, muscle=self.muscle.at_length(self.path.length_at(flexion)))

    def with_muscle(self, muscle: Muscle) -> Companion:
        """This companion with an edited muscle, at the same length."""
        return replace(self, muscle=muscle)


def reach_problem(companion: Companion, low: float, high: float) -> str | None:
    """Why ``companion`` cannot follow the elbow from ``low`` to ``high`` degrees (stretched
    that far, a node would thin to nothing), or None if it can."""
    flexions = np.linspace(low, high, REACH_SAMPLES)
    lengths = np.array([companion.path.length_at(f) for f in flexions])
    longest = int(np.argmax(lengths))
    if lengths[longest] <= companion.muscle.longest_length:
        return None
    return (f"{companion.name} would have to stretch to {lengths[longest]:.2f} cm at "
            f"{flexions[longest]:.0f} degrees of flexion, but "
            f"{companion.muscle.thinnest_note()} at {companion.muscle.longest_length:.2f} cm: "
            f"give its belly more radius or growth")


def check_reach(companion: Companion, low: float, high: float) -> None:
    """Raise :class:`RefusedChange` unless ``companion`` can follow the elbow over the range."""
    problem = reach_problem(companion, low, high)
    if problem is not None:
        raise RefusedChange(problem)
