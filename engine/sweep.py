"""The muscle across the elbow's range: one row of numbers per angle, for tables and plots.

``biceps sweep`` prints these rows and the app's plot panel draws them, so both show the
same numbers. Each row is the arm put at its angle from the config's arm, exactly as ``info
--flexion`` puts it, so the two agree to the last bit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from biceps.engine.arm import Arm
from biceps.engine.errors import RefusedChange

MOST_ANGLES = 100_000
"""More rows than any table or plot needs; a step so fine it asks for more is a mistake."""


@dataclass(frozen=True)
class Row:
    """The arm's numbers at one elbow angle (cm, cm^3, degrees)."""

    flexion: float
    length: float
    moment_arm: float
    volume: float
    volume_error: float  # relative to the conserved volume
    max_radius: float
    girth: float
    radii: np.ndarray  # (n,) float64, origin to insertion

    @classmethod
    def of(cls, arm: Arm, flexion: float) -> Row:
        """The row of ``arm`` put at ``flexion`` degrees, which it keeps as asked (the
        angle worked back from the length may differ in the last bit)."""
        muscle = arm.muscle
        return cls(flexion, muscle.length, arm.moment_arm, muscle.volume,
                   muscle.volume_error, muscle.max_radius, muscle.girth, muscle.radii)

    def record(self) -> dict[str, Any]:
        """The row as plain data, named as ``info --json`` names the same numbers."""
        return {
            "flexion_deg": self.flexion,
            "length_cm": self.length,
            "moment_arm_cm": self.moment_arm,
            "volume_cm3": self.volume,
            "volume_relative_error": self.volume_error,
            "max_radius_cm": self.max_radius,
            "girth_cm": self.girth,
            "radii_cm": self.radii.tolist(),
        }


def flexion_range(arm: Arm) -> tuple[float, float]:
    """The least and the most elbow flexion (degrees) the arm allows: the joint's range, or
    less where the config limits the muscle's length.

    An angle worked back from a length limit can land a rounding error beyond it, where
    :meth:`Arm.at_flexion` refuses it; such an end is moved in until it is accepted.
    """
    skeleton, drive = arm.skeleton, arm.drive
    shortest, longest = arm.length_range()
    joint_shortest, joint_longest = drive.length_range()
    least = skeleton.min_flexion if longest == joint_longest else drive.flexion(longest)
    most = skeleton.max_flexion if shortest == joint_shortest else drive.flexion(shortest)
    while drive.length_at(least) > longest:
        least = float(np.nextafter(least, most))
    while drive.length_at(most) < shortest:
        most = float(np.nextafter(most, least))
    return least, most


def angles(start: float, stop: float, step: float) -> list[float]:
    """``start``, ``start + step``, ... up to ``stop`` (degrees), downwards if ``stop`` is
    below ``start``; ``stop`` itself ends the list when a step lands on it.

    Each angle is ``start + k * step``, not a running sum, so no rounding builds up and a
    row's angle can be typed back into ``info --flexion`` as printed. A last step that
    lands within a rounding error of ``stop`` gives ``stop`` itself (``3 * 0.1`` is
    ``0.30000000000000004``), which may be the end of the joint's range.
    """
    if not (math.isfinite(step) and step > 0):
        raise RefusedChange(f"the step must be above 0 degrees, got {step:g}")
    span = abs(stop - start)
    # A hair of tolerance, so that 0 to 1 by 0.1 ends on 1 despite 10 * 0.1 rounding. A
    # step of 1e-308 makes a count too large for a float (inf): compared as one, not made
    # an int first.
    steps = span / step * (1 + 1e-12)
    if not steps < MOST_ANGLES:
        rows = f"{math.floor(steps) + 1:,}" if steps < 1e9 else "more than a billion"
        raise RefusedChange(
            f"a step of {step:g} degrees from {start:g} to {stop:g} makes {rows} rows; "
            f"at most {MOST_ANGLES:,} are allowed, so take a larger step"
        )
    count = math.floor(steps) + 1
    direction = 1.0 if stop >= start else -1.0
    out = [start + direction * k * step for k in range(count)]
    if abs(out[-1] - stop) <= 1e-9 * step:
        out[-1] = stop
    return out


def sweep(arm: Arm, flexions: list[float],
          progress: Callable[[int, int], None] | None = None) -> list[Row]:
    """The arm's numbers at each of ``flexions`` (degrees); raises :class:`RefusedChange`,
    before any row is made, if one is outside what the arm allows. ``progress`` is told
    ``(done, total)`` as the arm is put at each angle."""
    for flexion in flexions[:1] + flexions[-1:]:  # an end out of reach, refused at once
        arm.at_flexion(flexion)
    arms = []
    for flexion in flexions:
        arms.append(arm.at_flexion(flexion))
        if progress is not None and len(arms) % 100 == 0:
            progress(len(arms), len(flexions))
    return [Row.of(posed, flexion) for posed, flexion in zip(arms, flexions)]
