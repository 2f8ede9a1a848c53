"""Wrapping surfaces: the shortest way for a muscle's path round a cylinder or an ellipsoid
fixed to a bone, as OpenSim's wrap objects (``WrapCylinder``, ``WrapEllipsoid``) have it.

A surface lives in a frame of its own: its ``centre`` (3,) and ``rotation`` (3, 3), whose
columns are its local x, y and z axes in world space (cm). A cylinder's axis is its local
z; an ellipsoid's semi-axes are ``radii`` along its local x, y and z. An optional
``quadrant`` keeps the path to one half of the surface: (axis, sign), the half where that
local coordinate has that sign (OpenSim's ``quadrant = "-y"`` is (1, -1)).

A straight segment from ``p`` to ``q`` wraps a surface when it passes through it (and
neither end lies inside it); it then goes round on the active side, the short way unless
the quadrant asks otherwise: a straight line to a tangent point, along the surface, and a
straight line from the second tangent point. OpenSim also wraps a constrained cylinder
that the segment misses when its ends lie either side of the quadrant's plane; no path of
arm26 at the shoulder's rest angle meets that case, and it is not done here.

- Round a cylinder the path is the exact geodesic of an unbounded cylinder: unrolled, the
  tangent lines and the helix between them are one straight line (Garner and Pandy 2000,
  "The obstacle-set method"). OpenSim approximates the same path (its tangent points are
  slid along the axis until the path is tangent to a degree); the two agree on arm26's
  lengths to 0.03 mm.
- Round an ellipsoid the path is the shortest of those that lie in one plane through both
  ends (OpenSim's paths over an ellipsoid are such plane sections too; it picks the plane
  by its own rule, which this minimum matches on arm26's BIClong to 0.01 mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np

Quadrant = tuple[int, int] | None

ELLIPSE_SAMPLES = 720
"""Points round the plane section of an ellipsoid that a wrap is measured on: its length to
a few parts in a million (the inscribed polygon's shortfall is about (2 pi / 720)^2 / 24 of
the arc)."""
SEARCH_SAMPLES = 180
"""Points round a section while the best plane is sought, sixteen times as coarse a length
but the same for every plane, so the least is found in the same place."""
PLANE_SAMPLES = 24
"""Planes through the segment tried for an ellipsoid's shortest wrap, before the best is
refined by golden section."""
HELIX_STEP = 0.2  # cm between the points a wrap's arc is drawn through


class Wrapped:
    """A segment's way round a surface: its tangent points ``first`` and ``last`` (3,) in
    world space, the length along the surface between them (cm), and the points (k, 3) on
    the surface from one to the other, first to last (`points`, made by ``sample`` when
    first asked for: only a picture needs them). The segment's whole length adds the
    straight lines from its start to the first point and from the last to its end."""

    def __init__(self, first: np.ndarray, last: np.ndarray, length: float,
                 sample: Callable[[], np.ndarray]):
        self.first, self.last, self.length = first, last, length
        self._sample = sample

    @cached_property
    def points(self) -> np.ndarray:
        return self._sample()

    def total(self, start: np.ndarray, end: np.ndarray) -> float:
        """The whole segment's length (cm) from ``start`` to ``end`` (3,) round the surface."""
        return math.dist(start, self.first) + self.length + math.dist(self.last, end)


@dataclass(frozen=True, eq=False, kw_only=True)
class Surface:
    """The frame shared by every wrapping surface: see the module's docstring."""

    centre: np.ndarray
    rotation: np.ndarray
    quadrant: Quadrant = None

    def local(self, point: np.ndarray) -> np.ndarray:
        """(3,) ``point`` (3,) in the surface's own frame."""
        return self.rotation.T @ (point - self.centre)

    def world(self, points: np.ndarray) -> np.ndarray:
        """(k, 3) ``points`` (k, 3) of the surface's frame in world space."""
        return points @ self.rotation.T + self.centre

    def active(self, point) -> bool:
        """Whether a local ``point`` (3,) lies on the quadrant's half (always, with none)."""
        return self.quadrant is None or self.quadrant[1] * point[self.quadrant[0]] > 0.0


@dataclass(frozen=True, eq=False, kw_only=True)
class Cylinder(Surface):
    """A cylinder of ``radius`` about its local z axis, ``length`` long (cm), centred.

    Worked out in plain floats, not numpy: a muscle's length is asked for at each of the
    driver's steps and each pose, where numpy's calls on three numbers cost more than the
    arithmetic."""

    radius: float
    length: float

    def wrap(self, start: np.ndarray, end: np.ndarray) -> Wrapped | None:
        """The segment from ``start`` to ``end`` (3,) round the cylinder, or None if it
        keeps clear of it (or an end lies inside it)."""
        ax, ay, az = self._local(start)
        bx, by, bz = self._local(end)
        radius = self.radius
        cx, cy = bx - ax, by - ay
        across = cx * cx + cy * cy
        reach_a, reach_b = math.hypot(ax, ay), math.hypot(bx, by)
        if across == 0.0 or reach_a <= radius or reach_b <= radius:
            return None
        nearest = -(ax * cx + ay * cy) / across
        px, py = ax + nearest * cx, ay + nearest * cy
        if not (0.0 < nearest < 1.0 and px * px + py * py < radius * radius):
            return None
        # The short way round turns as the line from a to b does about the axis; a
        # quadrant may ask for the long way instead.
        short = 1.0 if ax * by - ay * bx >= 0.0 else -1.0
        ways = [self._round((ax, ay, az), (bx, by, bz), turning) for turning in (short, -short)]
        active = [way for way in ways if self.active(way[3])]
        into, out, length, _, turning, turn, climb, first_length = (active or ways)[0]
        half = 0.5 * self.length
        if abs(into[2]) > half and abs(out[2]) > half:
            return None  # both tangent points past the cylinder's ends, as OpenSim has it

        def sample() -> np.ndarray:
            count = max(2, math.ceil(length / HELIX_STEP) + 1)
            turns = np.linspace(0.0, turn, count)
            angles = math.atan2(into[1], into[0]) + turning * turns
            heights = az + climb * (first_length + radius * turns)
            return self.world(np.column_stack([radius * np.cos(angles),
                                               radius * np.sin(angles), heights]))

        return Wrapped(self._world(into), self._world(out), length, sample)

    def _round(self, a, b, turning: float):
        """The way round from the tangent point seen from ``a`` to that seen from ``b``
        (local, (x, y, z) each), turning ``turning`` (+1: counter-clockwise about z): the
        two tangent points, the length between them on the cylinder, the point halfway,
        the turning, the turn (radians), the climb per unit of planar length and the
        planar length from ``a`` to the first tangent point."""
        radius = self.radius
        reach_a, reach_b = math.hypot(a[0], a[1]), math.hypot(b[0], b[1])
        into = math.atan2(a[1], a[0]) + turning * math.acos(radius / reach_a)
        out = math.atan2(b[1], b[0]) - turning * math.acos(radius / reach_b)
        turn = (turning * (out - into)) % (2.0 * math.pi)
        first = math.sqrt(reach_a**2 - radius**2)
        arc = radius * turn
        planar = first + arc + math.sqrt(reach_b**2 - radius**2)
        # Unrolled, the whole path is one straight line: the climb along the axis is shared
        # in proportion to the planar lengths.
        climb = (b[2] - a[2]) / planar
        middle = into + turning * 0.5 * turn
        return ((radius * math.cos(into), radius * math.sin(into), a[2] + climb * first),
                (radius * math.cos(out), radius * math.sin(out), a[2] + climb * (first + arc)),
                math.hypot(arc, climb * arc),
                (radius * math.cos(middle), radius * math.sin(middle),
                 a[2] + climb * (first + 0.5 * arc)),
                turning, turn, climb, first)

    @cached_property
    def _frame(self):
        """The rotation's rows and columns and the centre, as plain floats."""
        return (tuple(map(tuple, self.rotation.tolist())),
                tuple(map(tuple, self.rotation.T.tolist())), tuple(self.centre.tolist()))

    def _local(self, point) -> tuple[float, float, float]:
        _, columns, centre = self._frame
        x, y, z = (p - c for p, c in zip(point.tolist(), centre))
        return tuple(u * x + v * y + w * z for u, v, w in columns)

    def _world(self, point) -> np.ndarray:
        rows, _, centre = self._frame
        return np.array([u * point[0] + v * point[1] + w * point[2] + c
                         for (u, v, w), c in zip(rows, centre)])


@dataclass(frozen=True, eq=False, kw_only=True)
class Ellipsoid(Surface):
    """An ellipsoid of semi-axes ``radii`` (3,) along its local axes (cm)."""

    radii: np.ndarray

    def wrap(self, start: np.ndarray, end: np.ndarray) -> Wrapped | None:
        """The segment from ``start`` to ``end`` (3,) round the ellipsoid, or None if it
        keeps clear of it (or an end lies inside it): the shortest path in a plane through
        both ends that goes round the ellipsoid on its active side."""
        a, b = self.local(start), self.local(end)
        if not self._passes_through(a, b):
            return None
        ahead = (b - a) / np.linalg.norm(b - a)
        first = np.cross(ahead, [0.0, 0.0, 1.0])
        if np.linalg.norm(first) < 1e-6:
            first = np.cross(ahead, [1.0, 0.0, 0.0])
        first /= np.linalg.norm(first)
        second = np.cross(ahead, first)
        planes = np.linspace(0.0, 2.0 * np.pi, PLANE_SAMPLES, endpoint=False)

        def length(angle: float, samples: int = SEARCH_SAMPLES) -> float:
            way = self._in_plane(a, b, ahead, first, second, angle, samples)
            return np.inf if way is None else way[1]

        lengths = np.array([length(angle) for angle in planes])
        best = int(np.argmin(lengths))
        if not np.isfinite(lengths[best]):
            return None
        step = planes[1] - planes[0]
        angle = _golden_minimum(length, planes[best] - step, planes[best] + step)
        way = (self._in_plane(a, b, ahead, first, second, angle, ELLIPSE_SAMPLES)
               or self._in_plane(a, b, ahead, first, second, planes[best], ELLIPSE_SAMPLES))
        if way is None:
            return None
        points, _, along = way
        placed = self.world(points)
        # The arc drawn through a point every HELIX_STEP or so, as a cylinder's is.
        count = max(2, math.ceil(along / HELIX_STEP) + 1)
        drawn = placed[np.round(np.linspace(0, len(placed) - 1, count)).astype(int)]
        return Wrapped(placed[0], placed[-1], along, lambda: drawn)

    def _passes_through(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether the segment from ``a`` to ``b`` (local) enters and leaves the ellipsoid
        (both crossings strictly between its ends, as OpenSim asks)."""
        scaled_a, scaled_step = a / self.radii, (b - a) / self.radii
        qa = float(scaled_step @ scaled_step)
        qb = 2.0 * float(scaled_a @ scaled_step)
        qc = float(scaled_a @ scaled_a) - 1.0
        spread = qb * qb - 4.0 * qa * qc
        if spread <= 0.0 or qc <= 0.0 or float((b / self.radii) @ (b / self.radii)) <= 1.0:
            return False
        near, far = ((-qb - math.sqrt(spread)) / (2.0 * qa), (-qb + math.sqrt(spread)) / (2.0 * qa))
        return 0.0 < near and far < 1.0

    def _in_plane(self, a, b, ahead, first, second, angle, samples: int):
        """The way round in the plane through ``a`` and ``b`` (local) that holds the unit
        ``ahead`` (from a to b) and the side ``cos(angle) first + sin(angle) second``,
        going round that side: (local points (k, 3), the whole length, the length on the
        surface), or None if it is not on the active half; the section is taken as a
        polygon of ``samples`` points."""
        side = math.cos(angle) * first + math.sin(angle) * second
        weights = 1.0 / self.radii**2
        basis = np.stack([ahead, side])  # (2, 3): in-plane coordinates u (ahead), v (side)
        form = (basis * weights) @ basis.T
        linear = (basis * weights) @ a
        centre = -np.linalg.solve(form, linear)
        level = float(centre @ form @ centre - (a * weights) @ a + 1.0)
        if level <= 0.0:
            return None
        values, vectors = np.linalg.eigh(form)
        turns = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)
        ring = centre + (np.sqrt(level / values) * np.column_stack([np.cos(turns), np.sin(turns)])) @ vectors.T
        reach = float(np.linalg.norm(b - a))
        # The tangent points: the points of the ring seen furthest round towards the side,
        # from each end; the path goes between them over the side (v > 0).
        touch_a = int(np.argmax(np.arctan2(ring[:, 1], ring[:, 0])))
        touch_b = int(np.argmax(np.arctan2(ring[:, 1], reach - ring[:, 0])))
        forward = np.arange(touch_a, touch_a + samples + 1) % samples
        upto = int(np.flatnonzero(forward == touch_b)[0])
        onward, backward = forward[:upto + 1], forward[upto:][::-1]
        arc = max((onward, backward), key=lambda run: float(ring[run, 1].min()))
        flat = ring[arc]
        points = a + flat @ basis
        if not self.active(points[len(points) // 2]):
            return None
        along = float(np.linalg.norm(np.diff(flat, axis=0), axis=1).sum())
        whole = float(np.linalg.norm(flat[0]) + along + np.linalg.norm(flat[-1] - [reach, 0.0]))
        return points, whole, along


def _golden_minimum(function, low: float, high: float, iterations: int = 30) -> float:
    """Where ``function`` of one variable is least between ``low`` and ``high``, by golden
    section (to (0.618)^iterations of the interval)."""
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    left, right = high - ratio * (high - low), low + ratio * (high - low)
    at_left, at_right = function(left), function(right)
    for _ in range(iterations):
        if at_left <= at_right:
            high, right, at_right = right, left, at_left
            left = high - ratio * (high - low)
            at_left = function(left)
        else:
            low, left, at_left = left, right, at_right
            right = low + ratio * (high - low)
            at_right = function(right)
    return 0.5 * (low + high)
