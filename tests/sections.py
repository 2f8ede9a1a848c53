"""Cross-sections of meshes by planes, measured independently of how they were made: where a
plane cuts each triangle, as oriented segments (so areas follow from Green's theorem), and
what a set of muscles' sections add up to across the humerus."""

from __future__ import annotations

import numpy as np


class Sliced:
    """A closed mesh (vertices (n, 3), triangles (m, 3), wound counter-clockwise from
    outside) to be cut by planes square to the unit ``normal`` (3,) at many heights."""

    def __init__(self, vertices: np.ndarray, triangles: np.ndarray, normal: np.ndarray):
        self.corners = vertices[triangles]  # (m, 3, 3)
        self.normal = normal
        heights = self.corners @ normal
        self.low, self.high = heights.min(axis=1), heights.max(axis=1)

    def at(self, height: float) -> np.ndarray:
        """`cut` at ``height`` along the normal."""
        near = (self.low < height) & (self.high > height)
        return _cut(self.corners[near], height * self.normal, self.normal)


def cut(vertices: np.ndarray, triangles: np.ndarray, origin: np.ndarray,
        normal: np.ndarray) -> np.ndarray:
    """The segments (k, 2, 3) where the plane through ``origin`` (3,) square to the unit
    ``normal`` (3,) cuts the closed mesh, each running counter-clockwise about ``normal``
    round the section it bounds (the mesh wound counter-clockwise from outside)."""
    return _cut(vertices[triangles], origin, normal)


def _cut(corners: np.ndarray, origin: np.ndarray, normal: np.ndarray) -> np.ndarray:
    heights = (corners - origin) @ normal  # (m, 3)
    above = heights > 0.0
    crossing = above.any(axis=1) & ~above.all(axis=1)
    corners, heights, above = corners[crossing], heights[crossing], above[crossing]
    points = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        edge = above[:, a] != above[:, b]
        share = heights[:, a] / np.where(edge, heights[:, a] - heights[:, b], 1.0)
        points.append(np.where(edge[:, None], corners[:, a] + share[:, None]
                               * (corners[:, b] - corners[:, a]), np.nan))
    points = np.stack(points, axis=1)  # (k, 3 edges, 3): two are points, one NaN
    found = ~np.isnan(points[..., 0])
    order = np.argsort(~found, axis=1, kind="stable")[:, :2]
    ends = np.take_along_axis(points, order[..., None], axis=1)  # (k, 2, 3)
    faces = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    way = np.cross(normal, faces)  # the section's boundary runs this way round
    flip = np.einsum("kc,kc->k", ends[:, 1] - ends[:, 0], way) < 0.0
    ends[flip] = ends[flip][:, ::-1]
    return ends


def area(segments: np.ndarray, normal: np.ndarray) -> float:
    """The area (cm^2) the oriented ``segments`` (k, 2, 3) of a plane section enclose."""
    return 0.5 * float(np.einsum("kc,c->", np.cross(segments[:, 0], segments[:, 1]), normal))


def centroid(segments: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """(3,) the centroid of the section the oriented ``segments`` (k, 2, 3) enclose, in its
    plane (the area-weighted mean of the triangles it makes with the first point)."""
    base = segments[0, 0]
    a, b = segments[:, 0] - base, segments[:, 1] - base
    weights = np.cross(a, b) @ normal
    return base + (weights[:, None] * (a + b)).sum(axis=0) / (3.0 * weights.sum())


def thickness_along(segments: np.ndarray, origin: np.ndarray, across: np.ndarray,
                    normal: np.ndarray) -> float:
    """How much of the ray from ``origin`` (3,) along the unit ``across`` (3,), in the plane
    of unit ``normal`` (3,), lies inside the section of ``segments`` (k, 2, 3) (cm): the
    ray's crossings of the section's boundary, in pairs (in, out), from the origin out."""
    beside = np.cross(normal, across)
    first, second = (segments[:, 0] - origin) @ beside, (segments[:, 1] - origin) @ beside
    crosses = (first > 0.0) != (second > 0.0)
    share = first[crosses] / (first[crosses] - second[crosses])
    hits = segments[crosses, 0] + share[:, None] * (segments[crosses, 1] - segments[crosses, 0])
    distances = np.sort((hits - origin) @ across)
    distances = distances[distances > 0.0]
    if len(distances) % 2:  # the origin inside: the section begins there
        distances = np.concatenate([[0.0], distances])
    return float(np.sum(distances[1::2] - distances[::2]))


def _turn(o: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """The z component of (a - o) x (b - o) for 2-D points: positive for a left turn."""
    return float((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))


def hull_perimeter(points: np.ndarray) -> float:
    """The perimeter of the convex hull of 2-D ``points`` (k, 2) (Andrew's monotone chain)."""
    points = np.unique(np.round(points, 9), axis=0)
    if len(points) < 3:
        return 0.0

    def half(ordered):
        chain = []
        for p in ordered:
            while len(chain) >= 2 and _turn(chain[-2], chain[-1], p) <= 0.0:
                chain.pop()
            chain.append(p)
        return chain

    lower, upper = half(points), half(points[::-1])
    hull = np.array(lower[:-1] + upper[:-1])
    return float(np.linalg.norm(np.diff(np.vstack([hull, hull[:1]]), axis=0), axis=1).sum())
