"""A muscle's path over the elbow: straight from origin to insertion, or wrapped around a
cylinder about the elbow's axis where the straight line would cut through the joint; or,
as OpenSim's models lead their muscles, through points fixed to the bones and round
wrapping surfaces (`ViaPath`).

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
from functools import cached_property, lru_cache
from typing import Literal

import numpy as np

from biceps.engine.skeleton import Attachment, forearm_frame, place
from biceps.engine.stations import distances_along, shares
from biceps.engine.wrapping import Surface, Wrapped

WrapSide = Literal["front", "back"]
SIDES: dict[str, int] = {"front": 1, "back": -1}
RECENT = 32
"""Poses a path keeps what it worked out for (see `ViaPath._at`)."""


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

    def points_at(self, flexion: float) -> np.ndarray:
        """(k, 3) the points the path runs through at ``flexion`` degrees, origin to
        insertion: its two ends, and round the cylinder points along it (every 2 mm)."""
        start, end = self.ends(flexion)
        if not self.wraps(flexion):
            return np.stack([start, end])
        length = self.length_at(flexion)
        return self.centreline(flexion, max(3, math.ceil(length / 0.2) + 1))[0]

    def moment_arm_at(self, flexion: float) -> float:
        """The moment arm about the elbow (cm) at ``flexion`` degrees: ``-dL/dtheta``, the
        length lost per radian of flexion, positive for a flexor."""
        start, end = self.ends(flexion)
        wrapped = self._wrapped(start, end)
        if wrapped is None:
            return moment_arm_of(end, end - start)
        planar, _, _, (touch, _, last) = wrapped
        # The climb along z is shared in proportion to the planar lengths (a helix).
        height = end[2] - (end[2] - start[2]) * last / planar
        return moment_arm_of(end, end - np.array([touch[0], touch[1], height]))

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


def _turn(flexion: float) -> np.ndarray:
    """(3, 3) the turn of the forearm about the hinge (z) from the straight arm to
    ``flexion`` degrees."""
    frame = forearm_frame(flexion)
    return frame @ STRAIGHT_FOREARM.T


STRAIGHT_FOREARM = forearm_frame(0.0)


def moment_arm_of(point: np.ndarray, arriving: np.ndarray) -> float:
    """The moment arm about the elbow (cm) of a path that ends at the forearm's ``point``
    (3,), reaching it along ``arriving`` (3,): ``-dL/dtheta``, as the point turns about the
    hinge (z) and the path's length changes by its motion along the path's last line (the
    rest of a shortest path round fixed surfaces does not change its length to first
    order: its tangent points slide along it). The motion is ``z x point``, written out."""
    (px, py, _), (ax, ay, az) = point.tolist(), arriving.tolist()
    return (py * ax - px * ay) / math.sqrt(ax * ax + ay * ay + az * az)


HINGE = np.array([0.0, 0.0, 1.0])
"""The elbow's axis in world space (see ``engine/skeleton.py``)."""


@dataclass(frozen=True)
class PathWrap:
    """A wrapping surface fixed to the upper arm, which the path's segments between its
    points ``first`` and ``last`` (indices, both included) may pass round."""

    surface: Surface
    first: int
    last: int


@dataclass(frozen=True, eq=False)
class ViaPath:
    """A path through ``points`` fixed to the bones (origin first, insertion last), each
    straight segment between them passing round a wrapping surface where it would cut
    through one, as OpenSim's ``GeometryPath`` leads a muscle.

    The ``wrapping`` surfaces are tried in their order, each on the segments of its range
    from the first: the first segment a surface's straight line passes through goes round
    it (a segment goes round one surface at most). The segments between two upper-arm
    points do not change with the elbow, so theirs are worked out once.
    """

    points: tuple[Attachment, ...]
    wrapping: tuple[PathWrap, ...] = ()

    @property
    def origin(self) -> Attachment:
        return self.points[0]

    @property
    def insertion(self) -> Attachment:
        return self.points[-1]

    def places(self, flexion: float) -> np.ndarray:
        """(k, 3) every point of the path in world space at ``flexion`` degrees."""
        return self._at(flexion)[0].copy()

    @cached_property
    def _straight(self) -> np.ndarray:
        """(k, 3) every point in world space with the arm straight."""
        return np.array([point.in_frame() for point in self.points])

    @cached_property
    def _moving(self) -> np.ndarray:
        """(k,) bool: the points on the forearm, which turn with the elbow."""
        return np.array([point.bone == "forearm" for point in self.points])

    def ends(self, flexion: float) -> tuple[np.ndarray, np.ndarray]:
        """The origin and the insertion (3,) float64 in world space at ``flexion`` degrees."""
        places = self._at(flexion)[0]
        return places[0].copy(), places[-1].copy()

    def segments(self, flexion: float) -> tuple[np.ndarray, list[Wrapped | None]]:
        """The points (k, 3) at ``flexion`` degrees and, for each of the k - 1 segments
        between them, its way round a surface, or None where it is straight."""
        places, ways, _ = self._at(flexion)
        return places.copy(), list(ways)

    def _at(self, flexion: float):
        """The points (k, 3), each segment's way round a surface (or None) and its length,
        at ``flexion`` degrees. The last few poses asked for are kept: a pose's picture,
        its numbers and the driver's search ask for the same ones again and again."""
        known = self._recent.get(flexion)
        if known is not None:
            return known
        places = self._straight.copy()
        moving = self._moving
        places[moving] = self._straight[moving] @ _turn(flexion).T
        ways: list[Wrapped | None] = [None] * (len(places) - 1)
        for index, wrap in enumerate(self.wrapping):
            for segment in range(wrap.first, wrap.last):
                if ways[segment] is not None:
                    continue
                if moving[segment] or moving[segment + 1]:
                    way = wrap.surface.wrap(places[segment], places[segment + 1])
                else:
                    way = self._fixed_way(index, segment, places)
                if way is not None:
                    ways[segment] = way
                    break
        steps = np.diff(places, axis=0)
        lengths = np.sqrt(np.einsum("kc,kc->k", steps, steps))
        for segment, way in enumerate(ways):
            if way is not None:
                lengths[segment] = way.total(places[segment], places[segment + 1])
        places.flags.writeable = lengths.flags.writeable = False
        known = (places, tuple(ways), lengths)
        if len(self._recent) >= RECENT:
            self._recent.pop(next(iter(self._recent)))
        self._recent[flexion] = known
        return known

    @cached_property
    def _recent(self) -> dict:
        """The poses last worked out (see `_at`), oldest first."""
        return {}

    def _fixed_way(self, wrap: int, segment: int, places: np.ndarray) -> Wrapped | None:
        key = (wrap, segment)
        if key not in self._fixed:
            surface = self.wrapping[wrap].surface
            self._fixed[key] = surface.wrap(places[segment], places[segment + 1])
        return self._fixed[key]

    @cached_property
    def _fixed(self) -> dict:
        """The ways round surfaces of the segments that do not move with the elbow, by
        (wrap, segment), filled as they are first asked for."""
        return {}

    def length_at(self, flexion: float) -> float:
        """The path's length (cm) with the elbow at ``flexion`` degrees."""
        plain = self._plain
        if plain is None:
            return float(self._at(flexion)[2].sum())
        fixed, segments = plain
        c, s = math.cos(math.radians(flexion)), math.sin(math.radians(flexion))
        total = fixed
        for (ax, ay, az, a_moves), (bx, by, bz, b_moves) in segments:
            if a_moves:
                ax, ay = c * ax - s * ay, s * ax + c * ay
            if b_moves:
                bx, by = c * bx - s * by, s * bx + c * by
            total += math.sqrt((bx - ax) ** 2 + (by - ay) ** 2 + (bz - az) ** 2)
        return total

    @cached_property
    def _plain(self):
        """Where no surface may wrap a segment that moves with the elbow (the biceps'
        paths: their wraps are all on the upper arm): the length of the segments that do
        not move, and the moving segments' ends as the straight arm holds them (each with
        whether it turns), from which the length at any flexion is a few square roots.
        None for a path whose moving segments may wrap."""
        moving = self._moving
        spans = [segment for segment in range(len(self.points) - 1)
                 if moving[segment] or moving[segment + 1]]
        if any(wrap.first <= segment < wrap.last for wrap in self.wrapping for segment in spans):
            return None
        lengths = self._at(0.0)[2]
        fixed = float(sum(length for segment, length in enumerate(lengths) if segment not in spans))
        straight = self._straight
        ends = [tuple((*straight[index].tolist(), bool(moving[index])) for index in (segment, segment + 1))
                for segment in spans]
        return fixed, ends

    def wraps(self, flexion: float) -> bool:
        """Whether any segment goes round a surface at ``flexion`` degrees."""
        return any(way is not None for way in self._at(flexion)[1])

    def moment_arm_at(self, flexion: float) -> float:
        """The moment arm about the elbow (cm) at ``flexion`` degrees: ``-dL/dtheta``, the
        length lost per radian of flexion, positive for a flexor. Each forearm point moves
        with the hinge and lengthens the path by its motion along the line arriving at it,
        shortens it by that along the line leaving it (from or to the next point, or the
        tangent point of a surface between)."""
        plain = self._plain
        if plain is not None:
            c, s = math.cos(math.radians(flexion)), math.sin(math.radians(flexion))
            arms = 0.0
            for (ax, ay, az, a_moves), (bx, by, bz, b_moves) in plain[1]:
                if a_moves:
                    ax, ay = c * ax - s * ay, s * ax + c * ay
                if b_moves:
                    bx, by = c * bx - s * by, s * bx + c * by
                span = math.sqrt((bx - ax) ** 2 + (by - ay) ** 2 + (bz - az) ** 2)
                if b_moves:  # the line arriving at b: z x b along it
                    arms += (by * (bx - ax) - bx * (by - ay)) / span
                if a_moves:  # and leaving a
                    arms += (ay * (ax - bx) - ax * (ay - by)) / span
            return arms
        places, ways, _ = self._at(flexion)
        arms = 0.0
        for index in np.flatnonzero(self._moving):
            place = places[index]
            if index > 0:
                way = ways[index - 1]
                before = places[index - 1] if way is None else way.last
                arms += moment_arm_of(place, place - before)
            if index < len(places) - 1:
                way = ways[index]
                after = places[index + 1] if way is None else way.first
                arms += moment_arm_of(place, place - after)
        return arms

    def points_at(self, flexion: float) -> np.ndarray:
        """(k, 3) the points the path runs through at ``flexion`` degrees, origin to
        insertion: its own, and round each surface it wraps points along it (every 2 mm)."""
        return self.route(flexion).points

    def route(self, flexion: float) -> Route:
        """The path at ``flexion`` degrees as one line of points through every point of the
        path and round every surface it wraps."""
        places, ways, _ = self._at(flexion)
        points, at = [places[:1]], [0]
        for index, way in enumerate(ways):
            if way is not None:
                points.append(way.points)
            points.append(places[index + 1:index + 2])
            at.append(at[-1] + 1 + (0 if way is None else len(way.points)))
        return Route(places, np.concatenate(points), np.array(at))

    def centreline(self, flexion: float, count: int) -> tuple[np.ndarray, np.ndarray]:
        """``count`` points (count, 3) equally spaced along the path from origin to insertion,
        and the path's unit direction (count, 3) at each, at ``flexion`` degrees (on a
        surface, the direction of the line between the route's points it lies between)."""
        return along_line(self.route(flexion).points, count)


@dataclass(frozen=True)
class Route:
    """A path at one pose: its own points (k, 3), the line (m, 3) through them and round
    the surfaces it wraps, and where each of its own points is on that line (k,)."""

    places: np.ndarray
    points: np.ndarray
    at: np.ndarray


def along_line(points: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """``count`` points (count, 3) equally spaced along the line through ``points`` (m, 3),
    both ends included, and the line's unit direction (count, 3) at each."""
    along = distances_along(points)
    steps = np.diff(points, axis=0)
    lengths = np.diff(along)
    keep = lengths > 0.0
    steps, starts, lengths = steps[keep], along[:-1][keep], lengths[keep]
    wanted = shares(count) * along[-1]
    segment = np.clip(np.searchsorted(starts, wanted, side="right") - 1, 0, len(starts) - 1)
    share = (wanted - starts[segment]) / lengths[segment]
    kept = points[:-1][keep]
    placed = kept[segment] + share[:, None] * steps[segment]
    placed[-1] = points[-1]
    return placed, steps[segment] / lengths[segment, None]


ROOT_TOLERANCE = 1e-12
"""Degrees: a root-find for the flexion stops once a step moves it by less than this."""


@dataclass(frozen=True)
class PathDrive:
    """The elbow driven by a muscle on ``path``: the flexion (degrees) is the one at which
    the path has the muscle's length. The path must shorten all the way as the elbow bends
    (a positive moment arm), so there is one flexion per length; outside the range the
    nearer end is taken. The same four answers as :class:`Skeleton`'s law of cosines."""

    path: ViaPath | MusclePath
    min_flexion: float
    max_flexion: float

    def length_at(self, flexion: float) -> float:
        """The muscle length (cm) that puts the elbow at ``flexion`` degrees."""
        return self.path.length_at(flexion)

    def moment_arm(self, flexion: float) -> float:
        """The muscle's moment arm about the elbow (cm) at ``flexion`` degrees."""
        return self.path.moment_arm_at(flexion)

    def length_range(self) -> tuple[float, float]:
        """The shortest and longest length (cm): at the most and the least flexion."""
        return self.length_at(self.max_flexion), self.length_at(self.min_flexion)

    def flexion(self, length: float) -> float:
        """The flexion (degrees) at which the path is ``length`` cm long (see `_flexion`;
        the last lengths asked for are kept, since an arm's flexion is asked for often)."""
        return _flexion(self, length)

    def _search(self, length: float) -> float:
        """The flexion (degrees) at which the path is ``length`` cm long.

        Newton's method on the length, whose slope is the moment arm (``-dL/dtheta``),
        kept inside a bracket that shrinks with every step: a step that would leave it
        bisects it instead, so the search cannot fail on a monotonic path. It starts from
        the straight line between the bracket's ends and stops once a step moves the angle
        by less than :data:`ROOT_TOLERANCE` degrees (4 to 6 steps on arm26's biceps).
        """
        low, high = self.min_flexion, self.max_flexion
        longest, shortest = self.length_at(low), self.length_at(high)
        if length >= longest:
            return low
        if length <= shortest:
            return high
        flexion = low + (high - low) * (longest - length) / (longest - shortest)
        for _ in range(200):
            excess = self.length_at(flexion) - length
            if excess == 0.0:
                return flexion
            if excess > 0.0:
                low = flexion
            else:
                high = flexion
            slope = -math.radians(self.moment_arm(flexion))  # cm per degree
            step = -excess / slope if slope < 0.0 else math.inf
            guess = flexion + step
            if not low < guess < high:
                guess = 0.5 * (low + high)
            if abs(guess - flexion) < ROOT_TOLERANCE or high - low < ROOT_TOLERANCE:
                return guess
            flexion = guess
        return flexion


@lru_cache(maxsize=64)
def _flexion(drive: PathDrive, length: float) -> float:
    return drive._search(length)
