"""The elbow's muscles laid in layers round the humerus, each section shaped to what lies
under it, each muscle's volume exact.

A muscle runs along its path (``engine/path.py``): the line through its points on the bones
and round its wrapping surfaces, as long as the muscle. Where that path runs down the upper
arm (within ``STEEPEST`` of the humerus's axis, in one run) the muscle is drawn as a stack
of slices across the humerus, each in a plane square to the humerus's axis; elsewhere
(over the humeral head, round the elbow) as round sections square to the path, centred on
it. Both keep the volume exactly:

- Square to the path and centred on it, a section sweeps ``integral A ds`` along the path
  (Pappus: the first moment of a section about its own centroid is nought), so a node
  profile of the muscle's length, laid along its path, holds the muscle's volume.
- Across the humerus the slices lie in parallel planes, so the volume is ``integral A dh``
  over their heights whatever their shapes or places (Cavalieri). The stretch of the
  muscle from the path's entry to its exit (length ``ds``) is spread evenly over the drop
  in height (``dh``): each slice's area is its section's ``pi r^2`` times ``ds / dh``, so
  the slices hold that stretch's volume.

Each slice is a shell laid on what is already there round the humerus at its height (the
bones, and the muscles laid before it, deepest first): over a window of angles round the
humerus centred on the muscle's side, its inner face follows what lies under it and its
outer face rises by ``T sqrt(1 - u^2)`` (u from -1 to 1 across the window), so it lies on
the bone or its neighbours and is round outside; ``T`` is solved so that the slice has its
area exactly. The window is as wide as the muscle's flatness asks (`Lie.aspect`, width over
thickness), up to its `Lie.spread`; a bone further out (the forearm, bent up in front) caps
the thickness and the slice spreads sideways instead. Near the ends of the stretch the
slices turn into circles on the path, so the slices meet the round sections, and the
tendons end, on the path's points.

Each section is a polygon of ``segments`` vertices with the section's area exactly, so the
mesh holds the muscle's volume to its facets along it and over its end caps.

Angles round the humerus (``phi``, radians) start at its front and turn towards its outside:
0 is the front, pi / 2 the outside (lateral), pi the back. Arrays of a muscle's sections
run from its origin to its insertion; a section's vertex ``j`` is at ``theta = 2 pi j /
segments``, counter-clockwise about the way the muscle runs, from the side facing away from
the humerus (``theta = 0``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from biceps.engine.jit import helper, ngjit
from biceps.engine.lies import Lie
from biceps.engine.mesh import Mesh, _closed_tube
from biceps.engine.muscle import Muscle
from biceps.engine.stations import distances_along, section_radii, shares

STEEPEST = math.radians(60.0)
"""How far from the humerus's axis the path may lean where the muscle is sliced across it."""
ANGLES = 120
"""Angles round the humerus at which what lies there is kept (3 degrees apart)."""
GAP = 0.05  # cm left between a slice and what it lies on
BRIDGE = 0.4  # cm: what lies this close outside the humerus's own layers counts as under
BLEND = 2.0  # cm of height over which the slices turn to the path at either end
END = 0.8  # cm of a muscle's path at either end drawn round on it, where its tendon holds on
MERGE = 4.0  # cm of height over which two heads come to share one belly
BAND = 2.5  # how many times as wide as thick heads' tendons are where they make one
SQUARENESS = 4.0  # the exponent of the superellipse of a tendon made of heads' parts
NEAREST = 0.8  # cm: the least radius a slice's width is measured at
ROUND = 3.0  # cm^2: a slice this large or larger is as flat as its muscle's aspect
STAND = (0.4, 1.2)  # cm: from this thick to this, a muscle comes to be one to lie beside
TAPER = 0.5  # cm past a muscle's end slices over which its window thins to nothing
SOLVED = 64  # vertices of the polygon a slice's thickness and width are solved on
TOLERANCE = 4e-10  # cm or radians: how closely a slice's thickness or width is solved
CLOSE = 1e-13  # of a slice's area: near enough to stop solving
SECTIONS = 97
"""Sections of a muscle from origin to insertion, the same at every pose, so that its mesh
keeps its shape of arrays (about every 4 mm of the biceps)."""
CAP_RINGS = 6  # rings of each end cap, the end section's excluded
OPEN = 1e3  # cm: as far out as nothing lies
HINGE = np.array([0.0, 0.0, 1.0])  # the elbow's axis, world space


class Humerus:
    """The humerus's axis, from the elbow's centre (the world's origin) up through the
    head's centre ``top`` (3,); with ``front`` and ``outside`` it makes a right-handed frame
    (front, up, outside), nearly world x, y, z."""

    def __init__(self, top: np.ndarray):
        self.up = top / np.linalg.norm(top)
        front = np.array([1.0, 0.0, 0.0]) - self.up[0] * self.up
        self.front = front / np.linalg.norm(front)
        self.outside = np.cross(self.front, self.up)

    def ray(self, phi) -> np.ndarray:
        """(..., 3) the unit directions across the humerus at angles ``phi`` (...)."""
        phi = np.asarray(phi)[..., None]
        return np.cos(phi) * self.front + np.sin(phi) * self.outside

    def polar(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Heights (k,), distances from the axis (k,) and angles (k,) of ``points`` (k, 3)."""
        heights = points @ self.up
        front, outside = points @ self.front, points @ self.outside
        return heights, np.hypot(front, outside), np.arctan2(outside, front)


@dataclass(frozen=True)
class Laid:
    """A muscle laid: its sections' vertices (m, segments, 3) from origin to insertion and
    each one's place along the muscle (m,) in cm from its origin; and, for the muscles laid
    after it, its slices across the humerus: their heights (k,), the inner and outer radii
    round the humerus (k, ANGLES; NaN where it is not) and each one's middle angle and
    half-width (radians), and its thickness (k, 3)."""

    rings: np.ndarray
    places: np.ndarray
    heights: np.ndarray
    inner: np.ndarray
    outer: np.ndarray
    windows: np.ndarray


class Ground:
    """What lies round the humerus as the muscles are laid on it: the bones, as spheres
    (centres (n, 3), radii (n,), world space), and each of up to ``muscles`` muscles'
    slices."""

    def __init__(self, humerus: Humerus, centres: np.ndarray, radii: np.ndarray,
                 muscles: int):
        self.humerus = humerus
        self.radii = radii
        # The spheres' centres as height up the humerus, and distance towards its front and
        # its outside (n,) each, the frame `under` works in.
        self._spheres = np.ascontiguousarray(
            np.stack([centres @ humerus.up, centres @ humerus.front, centres @ humerus.outside]))
        self.laid: dict[str, Laid] = {}
        self._phi = np.linspace(-np.pi, np.pi, ANGLES, endpoint=False)
        self._cos, self._sin = np.cos(self._phi), np.sin(self._phi)
        # The laid muscles with two slices or more, packed for `_sweep`: their names, where
        # each one's slices start (m + 1,), and the slices by height: heights, inner and
        # outer radii (room for ``muscles`` muscles' slices, rows up to ``_starts[-1]`` used).
        self._names: list[str] = []
        self._starts = [0]
        self._heights = np.empty(muscles * SECTIONS)
        self._inner = np.empty((muscles * SECTIONS, ANGLES))
        self._outer = np.empty((muscles * SECTIONS, ANGLES))

    def add(self, name: str, laid: Laid) -> None:
        self.laid[name] = laid
        if len(laid.heights) < 2:
            return
        order = np.argsort(laid.heights)
        start, end = self._starts[-1], self._starts[-1] + len(order)
        self._names.append(name)
        self._starts.append(end)
        self._heights[start:end] = laid.heights[order]
        self._inner[start:end] = laid.inner[order]
        self._outer[start:end] = laid.outer[order]

    def under(self, levels: np.ndarray, besides: str | None = None,
              middles: np.ndarray | None = None, reach: float = math.pi
              ) -> tuple[np.ndarray, np.ndarray]:
        """At each of ``levels`` (k,) heights and each of the ANGLES angles round the
        humerus: how far from its axis what lies on it reaches (the bone and the layers on
        it, joined across gaps under ``BRIDGE``; the muscle ``besides`` left out, which a
        slice stands beside), and where the next thing out begins (``OPEN`` if nothing
        does): (k, ANGLES) each. Only the angles within ``reach`` (radians) either side of
        the level's of ``middles`` (k,), if given, and the grid's next either side; NaN at
        the others."""
        levels = np.ascontiguousarray(levels, dtype=np.float64)
        used = np.array([name != besides for name in self._names], dtype=np.bool_)
        step = 2.0 * np.pi / ANGLES
        if middles is None or reach >= np.pi:
            first = np.zeros(len(levels), dtype=np.int64)
            count = ANGLES
        else:
            first = np.floor((middles - reach - self._phi[0]) / step).astype(np.int64) % ANGLES
            count = min(ANGLES, int(math.ceil(2.0 * reach / step)) + 2)
        reach_out = np.full((len(levels), ANGLES), np.nan)
        ceiling = np.full((len(levels), ANGLES), np.nan)
        things = len(self.radii) + len(self._names)
        _sweep(levels, first, count, self._spheres, self.radii, np.array(self._starts), used,
               self._heights, self._inner, self._outer, self._cos, self._sin, BRIDGE, OPEN,
               reach_out, ceiling, np.empty((3, things)), np.empty((2, things)),
               np.empty(len(self._names), dtype=np.int64), np.empty(len(self._names)))
        return reach_out, ceiling

    def window(self, name: str, levels: np.ndarray) -> np.ndarray:
        """Muscle ``name``'s slices' windows at ``levels`` (k, 3), as `Laid` keeps them (NaN
        where it has none)."""
        laid = self.laid.get(name)
        if laid is None or len(laid.heights) < 2:
            return np.full((len(levels), 3), np.nan)
        order = np.argsort(laid.heights)
        heights = laid.heights[order]
        windows = laid.windows[order].copy()
        windows[:, 0] = np.unwrap(windows[:, 0])
        values = np.column_stack([np.interp(levels, heights, column) for column in windows.T])
        # Past its end slices it thins to nothing over TAPER, so that what lies beside it
        # does not jump as its ends move.
        beyond = np.maximum(heights[0] - levels, levels - heights[-1])
        values[:, 2] *= np.clip(1.0 - beyond / TAPER, 0.0, 1.0)
        return np.where((beyond < TAPER)[:, None], values, np.nan)


@ngjit
def _sweep(levels, opening, count, spheres, radii, starts, used, heights, inner, outer, cos, sin,
           bridge, empty, reach, ceiling, circles, intervals, brackets, shares):
    """For each level k and the ``count`` angles a round the humerus from ``opening[k]`` on
    (round the grid): ``reach[k, a]``, how far out what
    lies on the humerus reaches, and ``ceiling[k, a]``, where the next thing out begins
    (``empty`` if nothing does). What lies there: the circles in which the bones' spheres
    (heights up the humerus's axis, distances towards its front and its outside (3, n);
    ``radii`` (n,)) cut the plane at height ``levels[k]``, met by the ray at the angle whose
    cosine and sine are ``cos[a]`` and ``sin[a]``; and the muscles m that are ``used``,
    whose slices, from ``starts[m]`` to ``starts[m + 1]``, lie at ``heights`` (s,) from
    ``inner`` to ``outer`` (s, A) (NaN where there is none), taken between the slices either
    side of the level. The reach grows from the axis by everything that begins near it:
    wholly if it begins within ``bridge / 2`` of it, less and less as the gap grows to
    ``bridge`` (so that the reach changes smoothly as things move), not at all beyond; the
    first thing further out than that is the ceiling. ``circles`` (3, n + m),
    ``intervals`` (2, n + m), ``brackets`` (m,) int64 and ``shares`` (m,): room to work
    in."""
    angles = reach.shape[1]
    for k in range(reach.shape[0]):
        level = levels[k]
        cut = 0  # the bones' circles at this level
        for j in range(radii.shape[0]):
            above = spheres[0, j] - level
            if abs(above) < radii[j]:
                circles[0, cut] = spheres[1, j]
                circles[1, cut] = spheres[2, j]
                circles[2, cut] = np.sqrt(radii[j] * radii[j] - above * above)
                cut += 1
        # A circle inside another adds nothing along any ray from the axis: most of the
        # humerus's, which overlap along it.
        kept = 0
        for i in range(cut):
            inside = False
            for j in range(cut):
                if j != i:
                    apart = np.hypot(circles[0, i] - circles[0, j], circles[1, i] - circles[1, j])
                    if apart + circles[2, i] < circles[2, j] or (
                            apart + circles[2, i] == circles[2, j] and j < i):
                        inside = True
                        break
            if not inside:
                circles[0, kept], circles[1, kept] = circles[0, i], circles[1, i]
                circles[2, kept] = circles[2, i]
                kept += 1
        cut = kept
        # Each muscle's slices either side of the level (-1: it has none there).
        for m in range(used.shape[0]):
            first, last = starts[m], starts[m + 1] - 1
            brackets[m] = -1
            if used[m] and heights[first] <= level <= heights[last]:
                below = first + np.searchsorted(heights[first:last + 1], level) - 1
                below = min(max(below, first), last - 1)
                brackets[m] = below
                shares[m] = (level - heights[below]) / (heights[below + 1] - heights[below])
        for turn in range(count):
            a = (opening[k] + turn) % angles
            things = 0
            for i in range(cut):
                front, outside, radius = circles[0, i], circles[1, i], circles[2, i]
                facing = front * cos[a] + outside * sin[a]
                spread = facing * facing - front * front - outside * outside + radius * radius
                if spread > 0.0 and facing + np.sqrt(spread) > 0.0:
                    intervals[0, things] = max(facing - np.sqrt(spread), 0.0)
                    intervals[1, things] = facing + np.sqrt(spread)
                    things += 1
            for m in range(used.shape[0]):
                below = brackets[m]
                if below < 0:
                    continue
                share = shares[m]
                start = (1.0 - share) * inner[below, a] + share * inner[below + 1, a]
                if start == start:
                    intervals[0, things] = start
                    intervals[1, things] = (1.0 - share) * outer[below, a] \
                        + share * outer[below + 1, a]
                    things += 1
            # Nearest first, so that the reach grows in one pass or two.
            for i in range(1, things):
                start, end = intervals[0, i], intervals[1, i]
                j = i
                while j > 0 and intervals[0, j - 1] > start:
                    intervals[0, j], intervals[1, j] = intervals[0, j - 1], intervals[1, j - 1]
                    j -= 1
                intervals[0, j], intervals[1, j] = start, end
            out = 0.0
            grew = True
            while grew:
                grew = False
                for i in range(things):
                    start, end = intervals[0, i], intervals[1, i]
                    if end > out:
                        share = min(max(2.0 * (bridge - (start - out)) / bridge, 0.0), 1.0)
                        grown = out + share * (end - out)
                        if grown > out + 1e-12:
                            out = grown
                            grew = True
            above = empty
            for i in range(things):
                start = intervals[0, i]
                if start > out + bridge and start < above:
                    above = start
            reach[k, a] = out
            ceiling[k, a] = above


def prepare() -> None:
    """Compile, or load from numba's cache, this module's kernels, on arrays of the kinds
    a pose passes them (``engine/coldstart.py``)."""
    levels, angles, vertices = 1, ANGLES, SOLVED
    reach, ceiling = np.zeros((levels, angles)), np.zeros((levels, angles))
    one = np.zeros(1)
    _sweep(np.zeros(levels), np.zeros(levels, dtype=np.int64), angles, np.zeros((3, 1)), one,
           np.zeros(2, dtype=np.int64),
           np.ones(1, dtype=np.bool_), np.zeros(2), np.zeros((2, angles)),
           np.zeros((2, angles)), np.zeros(angles), np.zeros(angles), BRIDGE, OPEN, reach,
           ceiling, np.empty((3, 2)), np.empty((2, 2)), np.empty(1, dtype=np.int64),
           np.empty(1))
    _solve(reach, ceiling, 0.0, 1.0, GAP, np.full(1, np.nan), one, one,
           np.zeros((1, vertices)), np.zeros(vertices), np.zeros(1), np.ones(1), np.zeros(1),
           1.0, np.ones(1), np.empty((3, vertices)))
    unit = np.array([[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, -1.0, 0.0]]])
    axis = np.array([0.0, 0.0, 1.0])
    _scaled(unit, np.ones(1), axis, axis, axis, np.empty_like(unit))
    _polygons(np.zeros((1, 3)), np.zeros((1, 3)), np.zeros((1, 3)), one, np.ones(vertices),
              np.zeros(vertices), np.empty((1, vertices, 3)))
    _grid_normals(np.zeros((2, vertices, 3)), np.zeros(3), np.ones(3),
                  np.empty((2, vertices, 3)))
    axis = np.array([0.0, 1.0, 0.0])
    _place(reach, ceiling, 0.0, 1.0, GAP, one, one, np.ones(1), one, one, np.zeros(vertices),
           np.ones(vertices, dtype=np.bool_), axis, axis, axis, np.empty((1, vertices, 3)),
           np.empty((1, angles)), np.empty((1, angles)))


def fill(segments: int) -> float:
    """The share of a circle's area that the regular polygon of ``segments`` vertices on it
    covers."""
    return segments * math.sin(2.0 * math.pi / segments) / (2.0 * math.pi)


def lay(name: str, muscle: Muscle, route: np.ndarray, lie: Lie, ground: Ground,
        segments: int, round_ends: tuple[bool, bool] = (True, True)) -> Laid:
    """The muscle ``name`` laid along ``route`` (m, 3), the line of its path from origin to
    insertion, on ``ground``, lying as ``lie`` says, with ``segments`` vertices a section;
    the ground then holds it too. An end of ``round_ends`` (origin, insertion) that is
    True ends in ``END`` cm of round sections on the path (a tendon held on a point of a
    bone off the humerus); else it may end on the ground round the humerus."""
    humerus = ground.humerus
    along = distances_along(route)
    places = shares(SECTIONS) * muscle.length
    areas = np.pi * section_radii(muscle.radii, SECTIONS) ** 2
    # A wrap's arc is drawn as chords, a hair short of the path's length: each place is the
    # same share of either.
    on_route = places * (along[-1] / muscle.length)
    points, ahead = _on_line(route, along, on_route)
    first, last = _stretch(route, along, humerus.up, on_route, areas, lie.lowest)
    # The tendons' last centimetre either end keeps to the path, so that each ends on its
    # point of the bone.
    first = max(first, END) if round_ends[0] else first
    last = min(last, along[-1] - END) if round_ends[1] else last
    sliced = (on_route >= first) & (on_route <= last) if last > first else \
        np.zeros(SECTIONS, dtype=bool)
    rings = np.empty((SECTIONS, segments, 3))
    middle = math.radians(0.5 * (lie.side[0] + lie.side[1]))
    outward = humerus.ray(middle)
    round_ = ~sliced
    # Past the stretch, towards the insertion, the tendon keeps to its lane across the
    # elbow (along the hinge, square to the bends round it, so its volume is kept).
    lane = np.where(on_route > last, lie.lane, 0.0)[:, None] * HINGE
    banded = round_ & (on_route > last) if lie.band is not None else np.zeros_like(round_)
    circled = round_ & ~banded
    rings[circled] = _circles((points + lane)[circled], ahead[circled], outward,
                              np.sqrt(areas[circled] / (np.pi * fill(segments))), segments)
    if banded.any():
        rings[banded] = _band(points[banded], ahead[banded], outward, areas[banded],
                              on_route[banded] - last, lie, segments)
    heights = np.empty(0)
    inner = outer = np.empty((0, ANGLES))
    windows = np.empty((0, 3))
    if sliced.any():
        ends, _ = _on_line(route, along, np.array([first, last]))
        top, bottom = ends @ humerus.up
        share = (on_route[sliced] - first) / (last - first)
        heights = top + share * (bottom - top)
        slice_areas = areas[sliced] * (last - first) / (top - bottom)
        # Each slice lies on its muscle's side; near either end of the stretch it turns to
        # the side the path is on there and into a circle about the path, so that the
        # slices meet the sections on the path.
        sides = np.radians(lie.side[0] + share * (lie.side[1] - lie.side[0]))
        _, _, entry = humerus.polar(ends)
        nearness = np.zeros(len(heights))
        joins = (on_route[0] < first, on_route[-1] > last)  # round sections beyond the end
        for end, distance, joined in ((entry[0], top - heights, joins[0]),
                                      (entry[1], heights - bottom, joins[1])):
            weight = np.clip(distance / BLEND, 0.0, 1.0)
            weight = weight * weight * (3.0 - 2.0 * weight)  # 0 at the end, 1 from BLEND on
            sides = sides + (1.0 - weight) * _wrapped(end - sides)
            if joined:
                nearness = np.maximum(nearness, 1.0 - weight)
        merged = np.clip((lie.merge_below - heights) / MERGE, 0.0, 1.0)
        peaks = lie.wall * merged * merged * (3.0 - 2.0 * merged)
        shells, inner, outer, windows = _shells(heights, slice_areas, sides, peaks, lie,
                                                ground, segments)
        lanes = np.where(share > 0.5, lie.lane, 0.0)[:, None] * HINGE
        on_path = points[sliced] + lanes
        on_path = on_path + (heights - on_path @ humerus.up)[:, None] * humerus.up
        near = nearness > 0.0
        circles = _circles(on_path[near], np.tile(-humerus.up, (near.sum(), 1)),
                           humerus.ray(sides[near]),
                           np.sqrt(slice_areas[near] / (np.pi * fill(segments))), segments)
        shells[near] += nearness[near, None, None] * (circles - shells[near])
        rings[sliced] = _with_area(shells, slice_areas, humerus.up)
        # The muscles laid after lie on its slices, not on the ends that turn to the path.
        inner = np.where(nearness[:, None] < 0.5, inner, np.nan)
        outer = np.where(nearness[:, None] < 0.5, outer, np.nan)
    laid = Laid(rings, places, heights, inner, outer, windows)
    ground.add(name, laid)
    return laid


def _stretch(route: np.ndarray, along: np.ndarray, up: np.ndarray, on_route: np.ndarray,
             areas: np.ndarray, lowest: float) -> tuple[float, float]:
    """Where along ``route`` (m, 3) (its distances ``along`` (m,)) the run of its segments
    that lean less than ``STEEPEST`` from straight down the humerus begins and ends, down
    to the height ``lowest`` at most: the run that holds the muscle's thickest section (at
    ``on_route`` (k,) with ``areas`` (k,)), or the longest run; (0, 0) if there is none."""
    steps = np.diff(route, axis=0)
    lengths = np.diff(along)
    drop = -(steps @ up)
    steep = (lengths > 0.0) & (drop >= lengths * math.cos(STEEPEST))
    runs, begin = [], None
    for index, flag in enumerate(np.append(steep, False)):
        if flag and begin is None:
            begin = index
        elif not flag and begin is not None:
            runs.append((float(along[begin]), float(along[index])))
            begin = None
    # A run descends, so it crosses the lowest height once at most.
    heights = route @ up
    runs = [(first, min(last, float(np.interp(-lowest, -heights[(along >= first) & (along <= last)],
                                                along[(along >= first) & (along <= last)]))))
            for first, last in runs]
    runs = [(first, last) for first, last in runs if last > first]
    if not runs:
        return 0.0, 0.0
    thickest = on_route[int(np.argmax(areas))]
    for first, last in runs:
        if first <= thickest <= last:
            return first, last
    return max(runs, key=lambda run: run[1] - run[0])


def _on_line(points: np.ndarray, along: np.ndarray, wanted: np.ndarray):
    """The places (k, 3) at distances ``wanted`` (k,) along the line through ``points``
    (m, 3), whose distances are ``along`` (m,), and the line's unit direction there."""
    steps = np.diff(points, axis=0)
    lengths = np.diff(along)
    keep = np.flatnonzero(lengths > 0.0)
    segment = keep[np.clip(np.searchsorted(along[keep], wanted, side="right") - 1, 0,
                           len(keep) - 1)]
    share = np.clip((wanted - along[segment]) / lengths[segment], 0.0, 1.0)
    places = points[segment] + share[:, None] * steps[segment]
    return places, steps[segment] / lengths[segment, None]


def _circles(centres: np.ndarray, ahead: np.ndarray, outward: np.ndarray,
             radii: np.ndarray, segments: int) -> np.ndarray:
    """(k, segments, 3) the regular polygons of ``radii`` (k,) about ``centres`` (k, 3),
    square to the unit ``ahead`` (k, 3), vertex 0 towards ``outward`` ((3,) or (k, 3))."""
    theta = 2.0 * np.pi * np.arange(segments) / segments
    polygons = np.empty((len(centres), segments, 3))
    _polygons(np.ascontiguousarray(centres), np.ascontiguousarray(ahead),
              np.broadcast_to(outward, ahead.shape).copy(), radii,
              np.cos(theta), np.sin(theta), polygons)
    return polygons


@ngjit
def _polygons(centres, ahead, outward, radii, cos, sin, polygons):
    """Into ``polygons`` (k, s, 3): `_circles`' polygons, their vertices at the angles whose
    cosines and sines are ``cos`` and ``sin`` (s,) each."""
    for k in range(polygons.shape[0]):
        facing = outward[k, 0] * ahead[k, 0] + outward[k, 1] * ahead[k, 1] \
            + outward[k, 2] * ahead[k, 2]
        first0 = outward[k, 0] - facing * ahead[k, 0]
        first1 = outward[k, 1] - facing * ahead[k, 1]
        first2 = outward[k, 2] - facing * ahead[k, 2]
        size = np.sqrt(first0 * first0 + first1 * first1 + first2 * first2)
        first0, first1, first2 = first0 / size, first1 / size, first2 / size
        second0 = ahead[k, 1] * first2 - ahead[k, 2] * first1
        second1 = ahead[k, 2] * first0 - ahead[k, 0] * first2
        second2 = ahead[k, 0] * first1 - ahead[k, 1] * first0
        for j in range(polygons.shape[1]):
            along, across = radii[k] * cos[j], radii[k] * sin[j]
            polygons[k, j, 0] = centres[k, 0] + along * first0 + across * second0
            polygons[k, j, 1] = centres[k, 1] + along * first1 + across * second1
            polygons[k, j, 2] = centres[k, 2] + along * first2 + across * second2


def _band(centres: np.ndarray, ahead: np.ndarray, outward: np.ndarray, areas: np.ndarray,
          past: np.ndarray, lie: Lie, segments: int) -> np.ndarray:
    """(k, segments, 3) a tendon's sections as its part of one flat tendon (`Lie.band`):
    at ``centres`` (k, 3) on its path, square to the unit ``ahead`` (k, 3), of ``areas``
    (k,), ``past`` (k,) cm past the end of its slices, from which they turn, over
    ``BLEND``, from the round sections on its lane into flat ones, ``BAND`` times as wide
    along the hinge as thick, side by side with its neighbours' (a side part's inner edge
    ``lie.seam`` from the path; the middle part as wide as the seam allows). Each polygon
    has its area exactly, its centroid off the path only along the hinge, square to the
    bends round it, so the volume is kept. Vertex 0 towards ``outward`` (3,), as
    `_circles` has it, so that the rings join untwisted."""
    weight = np.clip(past / BLEND, 0.0, 1.0)
    weight = weight * weight * (3.0 - 2.0 * weight)
    # The section's own frame: along the hinge (its width) and across it (its thickness).
    wide = HINGE - (ahead @ HINGE)[:, None] * ahead
    wide /= np.linalg.norm(wide, axis=1, keepdims=True)
    thick = _cross(ahead, wide)
    first = outward - (ahead @ outward)[:, None] * ahead
    first /= np.linalg.norm(first, axis=1, keepdims=True)
    second = _cross(ahead, first)
    theta = 2.0 * np.pi * np.arange(segments) / segments
    spokes = (np.cos(theta)[None, :, None] * first[:, None, :]
              + np.sin(theta)[None, :, None] * second[:, None, :])  # (k, segments, 3)
    u = np.einsum("ksc,kc->ks", spokes, wide)
    v = np.einsum("ksc,kc->ks", spokes, thick)
    # A superellipse (exponent SQUARENESS): blunt ends, so that the parts meet along their
    # edges rather than at points.
    power = (1.0 + weight * (2.0 / SQUARENESS - 1.0))[:, None]  # 1: the round section
    shape_u = np.sign(u) * np.abs(u) ** power
    shape_v = np.sign(v) * np.abs(v) ** power
    unit = _plane_polygon_areas(shape_u, shape_v)  # of half-widths 1 by 1, (k,)
    aspect = 1.0 + weight * (BAND - 1.0)
    if lie.band == 0:  # the middle: as wide as the seam, unless a round section is wider
        round_half = np.sqrt(areas / (unit * BAND)) * BAND
        half_width = (1.0 - weight) * np.sqrt(areas / unit) + weight * np.minimum(
            lie.seam, round_half)
        half_thick = areas / (unit * half_width)
        offset = np.zeros(len(areas))
    else:
        half_thick = np.sqrt(areas / (unit * aspect))
        half_width = aspect * half_thick
        offset = (1.0 - weight) * lie.lane + weight * lie.band * (lie.seam + half_width)
    centre = centres + offset[:, None] * HINGE
    return (centre[:, None, :] + (half_width[:, None] * shape_u)[..., None] * wide[:, None, :]
            + (half_thick[:, None] * shape_v)[..., None] * thick[:, None, :])


def _plane_polygon_areas(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The areas (k,) of the polygons of vertices ``x``, ``y`` (k, s) (counter-clockwise)."""
    return 0.5 * np.sum(x * _following(y) - _following(x) * y, axis=1)


def _profile(across: np.ndarray, peaks: np.ndarray) -> np.ndarray:
    """How thick a slice is across its window, as a share of its thickness: at ``across``
    ((s,) for every slice, or (k, s)) from -1 to 1, for slices (k,) thickest at ``peaks``
    (k,) (0: the middle, a half ellipse; 1 or -1: that edge, a quarter ellipse standing on
    it): (k, s)."""
    offset = np.atleast_2d(across) - peaks[:, None]
    reach = np.where(offset > 0.0, 1.0 - peaks[:, None], 1.0 + peaks[:, None])
    ratio = np.divide(offset, reach, out=np.zeros_like(offset), where=reach > 0.0)
    return np.sqrt(np.clip(1.0 - ratio**2, 0.0, 1.0))


def _shells(heights, areas, sides, peaks, lie: Lie, ground: Ground, segments: int):
    """The slices at ``heights`` (k,) of ``areas`` (k,) cm^2, laid on ``ground`` about the
    angles ``sides`` (k,), thickest at ``peaks`` (k,) across them (see `_profile`): their
    vertices (k, segments, 3), their inner and outer radii round the humerus (k, ANGLES)
    and windows (k, 3), as `Laid` keeps them.

    A slice's window is as wide as the muscle's flatness asks for its area (a half-ellipse
    of width w and thickness T has area pi w T / 4), up to its spread, and its thickness
    is solved for the area. A muscle that makes one belly with the one it lies beside
    takes that one's thickness at the edge they share, and its width is solved instead.
    """
    grid = ground._phi
    step = 2.0 * np.pi / ANGLES
    # How far round either way a slice may reach from the middle of its window (twice its
    # spread; the widest solved are 1.3 times it): the ground is swept only so far.
    widest = min(np.pi - 0.05, 2.0 * math.radians(lie.spread))
    under, _ = ground.under(heights, middles=sides, reach=step)
    # Solved at a fixed number of vertices, so that where a slice lies does not depend on
    # how finely it is drawn (nor, then, where the muscles laid on it lie).
    theta = 2.0 * np.pi * np.arange(SOLVED) / SOLVED
    across = np.sin(theta)
    rise = np.where(np.cos(theta) >= 0.0, _profile(across, peaks), 0.0)  # (k, SOLVED)
    # A slice thickest at an edge is half of a belly it shares: half as wide for its area;
    # a tendon's is round (a belly's flatness comes in as its sections grow to ROUND).
    aspect = ((1.0 + (lie.aspect - 1.0) * np.minimum(areas / ROUND, 1.0))
              * (1.0 - 0.5 * np.abs(peaks)))
    natural = np.sqrt(4.0 * areas / (math.pi * aspect))
    base = np.maximum(_at_angles(under, grid, sides[:, None])[:, 0], NEAREST)
    # Its width measured halfway up the slice: a slice widens outwards round the humerus.
    half = np.minimum(aspect * natural / (2.0 * base + natural), math.radians(lie.spread))
    sides = sides - peaks * half  # a wall stands at the side

    fixed = np.full(len(areas), np.nan)  # where a slice's edge stands against another's
    way = np.zeros(len(areas))
    thickness = np.zeros(len(areas))
    if lie.beside is not None:
        neighbour = ground.window(lie.beside, heights)
        way = np.sign(_wrapped(sides - np.nan_to_num(neighbour[:, 0])))
        edge = neighbour[:, 0] + way * neighbour[:, 1]
        # Beside a neighbour thick enough to stand against, on the ground without it: its
        # edge is this slice's. Where it thins (towards its ends) the slice turns back to
        # its own side, gradually, so that no section jumps as the muscles slide.
        standing = np.clip((np.nan_to_num(neighbour[:, 2]) - STAND[0]) / (STAND[1] - STAND[0]),
                           0.0, 1.0)
        own_edge = sides - way * half
        edge = own_edge + standing * _wrapped(np.nan_to_num(edge) - own_edge)
        sides = edge + way * half
        # Where the two make one belly: this one as thick as that one at the edge they
        # share, its width solved.
        merging = np.abs(peaks) * standing
        thickness = merging * np.nan_to_num(neighbour[:, 2]) + (1.0 - merging) * natural
        fixed = np.where(peaks != 0.0, edge, np.nan)
    # The ground under each slice's widest window: from its edge on, where that stands.
    middles = np.where(np.isnan(fixed), sides, fixed + way * widest)
    reach = widest + 2.0 * step
    under, ceiling = ground.under(heights, middles=middles, reach=reach)
    if lie.beside is not None:  # beside its neighbour: on the ground without it
        beside = standing > 0.0
        under[beside], ceiling[beside] = ground.under(heights[beside], lie.beside,
                                                      middles[beside], reach)
    _solve(np.ascontiguousarray(under), np.ascontiguousarray(ceiling), grid[0],
           step, GAP, fixed, way, areas, rise, across, sides, half, thickness, widest,
           np.maximum(reach - step - np.abs(_wrapped(sides - middles)), half),
           np.empty((3, SOLVED)))
    theta = 2.0 * np.pi * np.arange(segments) / segments
    humerus = ground.humerus
    vertices = np.empty((len(heights), segments, 3))
    inner = np.empty((len(heights), ANGLES))
    outer = np.empty((len(heights), ANGLES))
    _place(under, ceiling, grid[0], step, GAP, heights, sides, half, thickness, peaks,
           np.sin(theta), np.cos(theta) >= 0.0, humerus.up, humerus.front, humerus.outside,
           vertices, inner, outer)
    return vertices, inner, outer, np.column_stack([sides, half, thickness])


@ngjit
def _place(under, ceiling, start, step, gap, heights, sides, half, thickness, peaks, across,
           outward, up, front, outside, vertices, inner, outer):
    """The solved slices laid out: slice k's polygon ``vertices[k]`` (segments, 3), its
    vertex j at the angle ``sides[k] + half[k] across[j]`` round the humerus, on the
    ground (``under``, (k, A) on angles from ``start`` by ``step``) and, where
    ``outward[j]``, up by ``thickness[k]`` times its profile (`_profile`, thickest at
    ``peaks[k]``) but no nearer than ``gap`` to ``ceiling``; in the humerus's frame
    (``up``, ``front``, ``outside`` (3,) each) at height ``heights[k]``. And what it covers
    round the humerus, for the muscles laid after: its inner and outer radii at each of
    the A angles within its window, NaN at the others (k, A) each."""
    count, segments = vertices.shape[0], vertices.shape[1]
    angles = inner.shape[1]
    for k in range(count):
        for j in range(segments):
            phi = sides[k] + half[k] * across[j]
            floor = _interpolated(under[k], start, step, phi) + gap
            radius = floor
            if outward[j]:
                room = max(_interpolated(ceiling[k], start, step, phi) - gap - floor, 0.0)
                radius += min(thickness[k] * _rise(across[j], peaks[k]), room)
            ray_front, ray_outside = radius * np.cos(phi), radius * np.sin(phi)
            for c in range(3):
                vertices[k, j, c] = heights[k] * up[c] + ray_front * front[c] \
                    + ray_outside * outside[c]
        for a in range(angles):
            offset = (start + a * step - sides[k] + np.pi) % (2.0 * np.pi) - np.pi
            offset /= half[k]
            if abs(offset) <= 1.0:
                bottom = under[k, a] + gap
                inner[k, a] = bottom
                outer[k, a] = bottom + min(thickness[k] * _rise(offset, peaks[k]),
                                           max(ceiling[k, a] - gap - bottom, 0.0))
            else:
                inner[k, a] = np.nan
                outer[k, a] = np.nan


@helper
def _rise(across, peak):
    """`_profile` of one slice at one place: at ``across`` from -1 to 1, thickest at
    ``peak``."""
    offset = across - peak
    reach = 1.0 - peak if offset > 0.0 else 1.0 + peak
    ratio = offset / reach if reach > 0.0 else 0.0
    return np.sqrt(min(max(1.0 - ratio * ratio, 0.0), 1.0))


@ngjit
def _solve(under, ceiling, start, step, gap, fixed, way, areas, rise, across, sides, half,
           thickness, widest, caps, scratch):
    """Each slice k's window and thickness, solved for its area ``areas[k]``, in place in
    ``sides``, ``half`` and ``thickness`` (k,). Its polygon's vertex j is at the angle
    ``sides[k] + half[k] across[j]`` round the humerus, ``gap`` out from ``under`` and up
    by ``thickness[k] rise[k, j]`` but no nearer than ``gap`` to ``ceiling`` ((k, A) each,
    on angles from ``start`` by ``step``). Where ``fixed[k]`` is a number, the slice's
    edge stands there (its side then ``fixed + way half``) and its thickness is given: its
    half-width is solved, between 0.01 and ``widest``. Otherwise, or if no width is
    enough, its thickness is, between 0 and 30 cm, its window widened by 1.4 while even
    that is too little (eight times at most, and to half-widths of ``caps[k]`` at most,
    as far as the ground was swept). ``scratch``: (3, s) room to work in."""
    count, vertices = rise.shape
    floor, room, turn = scratch[0], scratch[1], scratch[2]
    for k in range(count):
        if fixed[k] == fixed[k]:
            low, high = 0.01, widest
            over_high = _area(under[k], ceiling[k], start, step, gap, fixed[k] + way[k] * high,
                              high, thickness[k], rise[k], across) - areas[k]
            if over_high >= 0.0:
                over_low = _area(under[k], ceiling[k], start, step, gap,
                                 fixed[k] + way[k] * low, low, thickness[k], rise[k],
                                 across) - areas[k]
                stale = 0
                while over_low < 0.0 and high - low > TOLERANCE:
                    middle = _false_position(low, over_low, high, over_high)
                    over = _area(under[k], ceiling[k], start, step, gap,
                                 fixed[k] + way[k] * middle, middle, thickness[k], rise[k],
                                 across) - areas[k]
                    low, over_low, high, over_high, stale = _narrowed(
                        low, over_low, high, over_high, middle, over, stale)
                    if 0.0 <= over_high <= CLOSE * areas[k]:
                        break
                half[k] = high if over_low < 0.0 else low
                sides[k] = fixed[k] + way[k] * half[k]
                continue
        for _ in range(8):
            for j in range(vertices):  # the polygon's angles stay while its thickness is sought
                phi = sides[k] + half[k] * across[j]
                floor[j] = _interpolated(under[k], start, step, phi) + gap
                room[j] = max(_interpolated(ceiling[k], start, step, phi) - gap - floor[j], 0.0)
                turn[j] = np.sin(half[k] * (across[(j + 1) % vertices] - across[j]))
            low, high = 0.0, 30.0
            over_high = _fixed_area(floor, room, turn, rise[k], high) - areas[k]
            if over_high >= 0.0:
                over_low = _fixed_area(floor, room, turn, rise[k], low) - areas[k]
                stale = 0
                while over_low < 0.0 and high - low > TOLERANCE:
                    middle = _false_position(low, over_low, high, over_high)
                    over = _fixed_area(floor, room, turn, rise[k], middle) - areas[k]
                    low, over_low, high, over_high, stale = _narrowed(
                        low, over_low, high, over_high, middle, over, stale)
                    if 0.0 <= over_high <= CLOSE * areas[k]:
                        break
                thickness[k] = high if over_low < 0.0 else low
                break
            half[k] = min(half[k] * 1.4, caps[k])


@helper
def _false_position(low, over_low, high, over_high):
    """Where the line through (``low``, ``over_low`` < 0) and (``high``, ``over_high`` >= 0)
    crosses nought: the next guess of a root between them (their middle if it falls
    outside, as rounding can make it)."""
    guess = low - over_low * (high - low) / (over_high - over_low)
    if not low < guess < high:
        guess = 0.5 * (low + high)
    return guess


@helper
def _narrowed(low, over_low, high, over_high, guess, over, stale):
    """The bracket (``low``, ``over_low``, ``high``, ``over_high``) narrowed by ``guess``,
    where the function is ``over``; the Illinois rule halves the value at an end kept
    twice running (``stale``: -1 the low end was, 1 the high end), so that false position
    closes in from both sides instead of creeping from one (Dowell and Jarratt 1971)."""
    if over >= 0.0:
        if stale == -1:
            over_low *= 0.5
        return low, over_low, guess, over, -1
    if stale == 1:
        over_high *= 0.5
    return guess, over, high, over_high, 1


@helper
def _fixed_area(floor, room, turn, rise, thickness):
    """The area of a slice's polygon whose vertices' angles are set: radii ``floor`` up by
    ``thickness rise`` but no more than ``room``, each turning by the sine ``turn`` to the
    next (all (s,))."""
    vertices = floor.shape[0]
    total = 0.0
    for j in range(vertices):
        following = (j + 1) % vertices
        total += ((floor[j] + min(thickness * rise[j], room[j]))
                  * (floor[following] + min(thickness * rise[following], room[following]))
                  * turn[j])
    return 0.5 * total


@helper
def _area(under, ceiling, start, step, gap, side, half, thickness, rise, across):
    """The area of a slice's polygon (see `_solve`): the shoelace of its vertices given in
    angles and radii round the humerus."""
    vertices = rise.shape[0]
    total = 0.0
    first_phi = first_radius = last_phi = last_radius = 0.0
    for j in range(vertices):
        phi = side + half * across[j]
        floor = _interpolated(under, start, step, phi) + gap
        room = max(_interpolated(ceiling, start, step, phi) - gap - floor, 0.0)
        radius = floor + min(thickness * rise[j], room)
        if j == 0:
            first_phi, first_radius = phi, radius
        else:
            total += last_radius * radius * np.sin(phi - last_phi)
        last_phi, last_radius = phi, radius
    total += last_radius * first_radius * np.sin(first_phi - last_phi)
    return 0.5 * total


@helper
def _interpolated(values, start, step, phi):
    """``values`` (A,) on the periodic angles from ``start`` by ``step``, at ``phi``."""
    count = values.shape[0]
    position = (phi - start) / step
    below = np.floor(position)
    share = position - below
    index = int(below) % count
    return (1.0 - share) * values[index] + share * values[(index + 1) % count]


def _wrapped(angles: np.ndarray) -> np.ndarray:
    """``angles`` (radians, any shape) brought within -pi to pi."""
    return np.mod(angles + np.pi, 2.0 * np.pi) - np.pi


def _at_angles(values: np.ndarray, grid: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``values`` (k, ANGLES) on the periodic ``grid`` of angles, at angles ``phi`` (k, s)."""
    step = 2.0 * np.pi / ANGLES
    position = (phi - grid[0]) / step
    below = np.floor(position).astype(int)
    share = position - below
    rows = np.arange(len(values))[:, None]
    left = values[rows, below % ANGLES]
    right = values[rows, (below + 1) % ANGLES]
    return (1.0 - share) * left + share * right


def _with_area(rings: np.ndarray, areas: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """``rings`` (k, segments, 3), each a polygon in a plane square to ``normal`` (3,),
    scaled about its centroid to have its area of ``areas`` (k,)."""
    first = np.array([normal[1], -normal[0], 0.0])  # normal x (0, 0, 1)
    first /= np.linalg.norm(first)
    scaled = np.empty_like(rings)
    _scaled(np.ascontiguousarray(rings), areas, first, _cross(normal, first), normal, scaled)
    return scaled


@ngjit
def _scaled(rings, areas, first, second, normal, scaled):
    """Into ``scaled``: `_with_area`'s polygons, ``first``, ``second`` and ``normal`` (3,)
    each the right-handed frame of their planes. The centroid and area by the shoelace."""
    segments = rings.shape[1]
    for k in range(rings.shape[0]):
        twice = moment_x = moment_y = level = 0.0
        for j in range(segments):
            following = (j + 1) % segments
            x = rings[k, j, 0] * first[0] + rings[k, j, 1] * first[1] + rings[k, j, 2] * first[2]
            y = rings[k, j, 0] * second[0] + rings[k, j, 1] * second[1] \
                + rings[k, j, 2] * second[2]
            x1 = rings[k, following, 0] * first[0] + rings[k, following, 1] * first[1] \
                + rings[k, following, 2] * first[2]
            y1 = rings[k, following, 0] * second[0] + rings[k, following, 1] * second[1] \
                + rings[k, following, 2] * second[2]
            cross = x * y1 - x1 * y
            twice += cross
            moment_x += (x + x1) * cross
            moment_y += (y + y1) * cross
            level += rings[k, j, 0] * normal[0] + rings[k, j, 1] * normal[1] \
                + rings[k, j, 2] * normal[2]
        cx, cy, level = moment_x / (3.0 * twice), moment_y / (3.0 * twice), level / segments
        scale = np.sqrt(areas[k] / (0.5 * abs(twice)))
        for c in range(3):
            centroid = cx * first[c] + cy * second[c] + level * normal[c]
            for j in range(segments):
                scaled[k, j, c] = centroid + scale * (rings[k, j, c] - centroid)


def muscle_mesh(laid: Laid, closed: bool) -> Mesh:
    """The laid muscle's closed surface: its sections joined, closed at each end by a
    dome of the end section (a hemisphere on a round end, ``closed``) or a flat cap."""
    rings = laid.rings
    segments = rings.shape[1]
    ends = []
    for index, inward in ((0, 1), (-1, -2)):
        ring = rings[index]
        centre = ring.mean(axis=0)
        outward = centre - rings[inward].mean(axis=0)
        outward /= np.linalg.norm(outward)
        # A dome as high as a circle of the end section's area is wide, so a round end's
        # holds the cap's (2/3) pi r^3.
        radius = np.sqrt(_plane_area(ring) / np.pi)
        if closed:
            lat = np.linspace(0.0, 0.5 * np.pi, CAP_RINGS + 1)[1:-1]
            dome = (centre + np.cos(lat)[:, None, None] * (ring - centre)
                    + (radius * np.sin(lat))[:, None, None] * outward)
            pole = centre + radius * outward
        else:
            dome = np.empty((0, segments, 3))
            pole = centre
        ends.append((dome, pole, outward))
    (start_dome, start_pole, start_out), (end_dome, end_pole, end_out) = ends
    grid = np.concatenate([start_dome[::-1], rings, end_dome])
    vertices = np.concatenate([start_pole[None], grid.reshape(-1, 3), end_pole[None]])
    normals = np.empty_like(vertices)
    normals[0], normals[-1] = start_out, end_out
    _grid_normals(grid, start_pole, end_pole, normals[1:-1].reshape(grid.shape))
    return Mesh(vertices, normals, _closed_tube(len(grid), segments))


@ngjit
def _grid_normals(grid, start_pole, end_pole, normals):
    """The unit normals (r, s, 3) of a tube's ``grid`` of r rings of s vertices (r, s, 3),
    closed by ``start_pole`` and ``end_pole`` (3,): across each ring (counter-clockwise
    about the way the tube runs) crossed with along it, pointing out."""
    rings, segments = grid.shape[0], grid.shape[1]
    for i in range(rings):
        for j in range(segments):
            after, before = (j + 1) % segments, (j - 1) % segments
            around0 = grid[i, after, 0] - grid[i, before, 0]
            around1 = grid[i, after, 1] - grid[i, before, 1]
            around2 = grid[i, after, 2] - grid[i, before, 2]
            ahead = grid[i + 1, j] if i + 1 < rings else end_pole
            behind = grid[i - 1, j] if i > 0 else start_pole
            along0, along1, along2 = ahead[0] - behind[0], ahead[1] - behind[1], \
                ahead[2] - behind[2]
            x = around1 * along2 - around2 * along1
            y = around2 * along0 - around0 * along2
            z = around0 * along1 - around1 * along0
            size = max(np.sqrt(x * x + y * y + z * z), 1e-300)
            normals[i, j, 0], normals[i, j, 1], normals[i, j, 2] = x / size, y / size, z / size


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross`` of (..., 3) arrays, written out: numpy's own moves the axes about."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _plane_area(ring: np.ndarray) -> float:
    """The area of the plane polygon ``ring`` (s, 3): half the length of the sum of its
    edges' cross products (the shoelace in 3D)."""
    return 0.5 * float(np.linalg.norm(_cross(ring, _following(ring.T).T).sum(axis=0)))


def _following(values: np.ndarray) -> np.ndarray:
    """``values`` (..., s) moved one place back along their last axis: the next vertex's."""
    return np.concatenate([values[..., 1:], values[..., :1]], axis=-1)


def ring_places(muscle: Muscle, vertices: int) -> np.ndarray:
    """Each of the ``vertices`` of the laid muscle's mesh (`muscle_mesh`) placed along the
    muscle, in nodes: (n,) float64, 0 at the first node, ``node_count - 1`` at the last, a
    dome's rings and pole at their end section's. Its sections are at the same shares of
    its length at every pose, so this is the same at every pose."""
    rings = shares(SECTIONS) * (muscle.node_count - 1)
    caps = CAP_RINGS - 1 if muscle.volume_mode == "closed" else 0
    segments = (vertices - 2) // (SECTIONS + 2 * caps)
    per_ring = np.concatenate([np.full(caps, rings[0]), rings, np.full(caps, rings[-1])])
    return np.concatenate([[rings[0]], np.repeat(per_ring, segments), [rings[-1]]])

