"""A muscle's path over the elbow: straight from origin to insertion, or wrapped around a
cylinder about the elbow's axis where the straight line would cut through the joint.

The cylinder is OpenSim's wrapping cylinder (arm26's "TRI", radius 1.6 cm, about the
elbow's axis): the triceps runs over the olecranon and, as the elbow bends, around the back
of the humerus's condyles; the brachialis around their front. The path is the shortest one
that keeps to the cylinder's given side: in the plane of the bend (across the elbow's axis
``z``) two tangents and the arc between them, and along ``z`` a steady climb, so that
unrolled the whole path is one straight line and its length is the hypotenuse of the
planar length and the attachments' sideways separation (a helix on the cylinder, Garner
and Pandy 2000, "The obstacle-set method").

Conventions as in ``engine/skeleton.py``: world space in cm, the elbow's centre at the
origin, its axis ``z``. ``side`` is +1 when the muscle passes in front of the elbow (a
flexor) and -1 behind it (an extensor), seen going from origin to insertion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from biceps.engine.skeleton import Attachment, forearm_frame, place
from biceps.engine.stations import shares

WrapSide = Literal["front", "back"]
SIDES: dict[str, int] = {"front": 1, "back": -1}


@dataclass(frozen=True)
class Wrap:
    """A cylinder of ``radius`` cm about the elbow's axis, passed on its ``side``."""

    radius: float
    side: WrapSide


@dataclass(frozen=True)
class MusclePath:
    """Where a muscle holds on (origin on the upper arm, insertion on the forearm) and how it
    gets from one to the other."""

    origin: Attachment
    insertion: Attachment
    wrap: Wrap | None = None

    def ends(self, flexion: float) -> tuple[np.ndarray, np.ndarray]:
        """The origin and the insertion (3,) float64 in world space at ``flexion`` degrees."""
        frame = forearm_frame(flexion)
        return place(self.origin, frame), place(self.insertion, frame)

    def length_at(self, flexion: float) -> float:
        """The path's length (cm) with the elbow at ``flexion`` degrees."""
        start, end = self.ends(flexion)
        wrapped = self._wrapped(start, end)
        if wrapped is None:
            return float(np.linalg.norm(end - start))
        return math.hypot(wrapped[0], end[2] - start[2])

    def wraps(self, flexion: float) -> bool:
        """Whether the path bends round the cylinder at ``flexion`` degrees."""
        return self._wrapped(*self.ends(flexion)) is not None

    def centreline(self, flexion: float, count: int) -> tuple[np.ndarray, np.ndarray]:
        """``count`` points (count, 3) equally spaced along the path from origin to insertion,
        and the path's unit direction (count, 3) at each, at ``flexion`` degrees."""
        start, end = self.ends(flexion)
        wrapped = self._wrapped(start, end)
        share = shares(count)
        if wrapped is None:
            direction = (end - start) / np.linalg.norm(end - start)
            return start + np.outer(share, end - start), np.tile(direction, (count, 1))
        planar, first, arc, second = wrapped
        # Equal steps of the whole path are equal steps of its planar part (the climb along
        # z is steady), so the stations are spaced evenly in the plane.
        u = share * planar
        flat, heading = np.empty((count, 2)), np.empty((count, 2))
        on_first = u <= first[2]
        on_arc = ~on_first & (u <= first[2] + arc[2])
        on_second = ~(on_first | on_arc)
        for mask, (begin, stop, _), before in ((on_first, first, 0.0),
                                               (on_second, second, first[2] + arc[2])):
            way = (stop - begin) / np.linalg.norm(stop - begin)
            flat[mask] = begin + np.outer(u[mask] - before, way)
            heading[mask] = way
        start_angle, step = arc[0], arc[1]
        angle = start_angle + step * (u[on_arc] - first[2]) / arc[2]
        radius = self.wrap.radius
        flat[on_arc] = radius * np.column_stack([np.cos(angle), np.sin(angle)])
        heading[on_arc] = np.sign(step) * np.column_stack([-np.sin(angle), np.cos(angle)])
        rise = (end[2] - start[2]) / planar
        points = np.column_stack([flat, start[2] + u * rise])
        tangents = np.column_stack([heading, np.full(count, rise)])
        return points, tangents / np.linalg.norm(tangents, axis=1, keepdims=True)

    def _wrapped(self, start: np.ndarray, end: np.ndarray):
        """None if the straight line keeps clear of the cylinder on its side; otherwise the
        planar length, the first tangent (from, to, length), the arc (start angle, signed
        turn, length) and the second tangent, all in the plane of the bend."""
        if self.wrap is None:
            return None
        radius, side = self.wrap.radius, SIDES[self.wrap.side]
        p, q = start[:2], end[:2]
        chord = q - p
        reach = float(np.linalg.norm(chord))
        ahead = chord / reach
        along = -float(p @ ahead)  # where the line comes nearest the axis
        passing = side * float(ahead[0] * p[1] - ahead[1] * p[0])  # > 0: on its side
        if not 0.0 < along < reach or passing >= radius:
            return None
        a, b = float(np.linalg.norm(p)), float(np.linalg.norm(q))
        if a <= radius or b <= radius:
            return None  # an attachment inside the cylinder: nothing to wrap around
        # Each tangent point is acos(R / distance) round from its attachment's direction,
        # towards the side the path passes on; the path turns the other way round the axis.
        into = math.atan2(p[1], p[0]) - side * math.acos(radius / a)
        out = math.atan2(q[1], q[0]) + side * math.acos(radius / b)
        turn = (side * (into - out)) % (2.0 * math.pi)
        touch_in = radius * np.array([math.cos(into), math.sin(into)])
        touch_out = radius * np.array([math.cos(out), math.sin(out)])
        first = (p, touch_in, math.sqrt(a * a - radius * radius))
        second = (touch_out, q, math.sqrt(b * b - radius * radius))
        arc = (into, -side * turn, radius * turn)
        return first[2] + arc[2] + second[2], first, arc, second
