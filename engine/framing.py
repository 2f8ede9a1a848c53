"""How the camera frames the arm.

The camera frames the arm as it is posed and turned: it looks at the middle of the turned
arm's extent, from as close as keeps every vertex within ``FILL`` of the picture's edges
(`fit_points`), so the arm is as large as the picture allows, centred, in every
pose. The view turns the model about the centre of its bounding box, moves it by its offset,
then scales it about the point the camera looks at: zooming grows the picture about its
own centre, wherever the model was moved, and never pushes the middle of the arm out. The
light, which stays put as the model turns, scales with it, so zooming does not relight it.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from biceps.engine.jit import exact, ngjit
from biceps.engine.settings import View
from biceps.engine.transforms import (Camera, Light, model_matrix, scale_matrix,
                                      transform_points, translation_matrix)

FILL = 0.9
"""The share of the picture's half-width or half-height the arm reaches, whichever is less."""


def outline(vertices: np.ndarray, directions: int = 256, stride: int = 4) -> np.ndarray:
    """The vertices (k, 3), k <= ``directions``, farthest out along directions spread evenly
    over the sphere (a Fibonacci lattice), among every ``stride``-th of ``vertices`` (n, 3):
    all that framing needs of them.

    Neighbouring directions are at most about 13 degrees apart, so no vertex stands out of
    the outline's hull by more than 1 - cos(6.5 degrees), 0.7 %, of the arm's reach; and
    every 4th vertex of a ring of 48 misses the ring's outermost point by at most
    1 - cos(15 degrees) of the ring's radius, a few tenths of a millimetre: both far inside
    the margin `FILL` leaves. Framing a few hundred points instead of every vertex takes a
    fraction of a millisecond instead of several, and the outline itself 2 ms.
    """
    index = np.arange(directions) + 0.5
    height = 1.0 - 2.0 * index / directions
    turn = np.pi * (1.0 + 5.0**0.5) * index
    ring = np.sqrt(1.0 - height**2)
    lattice = np.array([ring * np.cos(turn), height, ring * np.sin(turn)])  # (3, k)
    some = vertices[::stride]
    # Reduced along rows of one coordinate each: numpy reduces the columns of rows of three
    # far more slowly (the same extremes: min and max do not round).
    coordinates = some.T.copy()
    centre = (coordinates.min(axis=1) + coordinates.max(axis=1)) / 2.0
    farthest, best = np.empty(directions, np.int64), np.empty(directions)
    _farthest_along(lattice, np.ascontiguousarray(some - centre), farthest, best)
    return some[np.unique(farthest)]


@ngjit
def _farthest_along(directions, points, farthest, best):
    """For each of ``directions`` (3, k), by component, the index into ``points`` (m, 3) of
    the first one farthest along it, into ``farthest`` (k,) int64; ``best`` (k,) float64 is
    working space. A kernel, not numpy: einsum holds the GIL for all its run, 45 ms at 5,000
    nodes, and the app's keys wait that long; BLAS's threads took tens of milliseconds to
    start on a busy machine. The directions are the inner loop, each component a contiguous
    row, so that LLVM runs it on several directions at once (SIMD): 2.1 -> 0.36 ms for the
    six muscles' 8,100 points, the same indices."""
    best[:] = -np.inf
    farthest[:] = 0
    for i in range(points.shape[0]):
        x, y, z = points[i, 0], points[i, 1], points[i, 2]
        for k in range(directions.shape[1]):
            reach = directions[0, k] * x + directions[1, k] * y + directions[2, k] * z
            if reach > best[k]:
                best[k], farthest[k] = reach, i


def fit_points(points, aspect: float, fov_y_deg: float = 35.0, fill: float = 0.9,
               scale: float = 1.0) -> Camera:
    """The tightest centred framing of ``points`` (n, 3) (world space): a camera on their
    ``+z`` side looking down ``-z``, as close as it can be with every point within ``fill``
    of the view's half-width and half-height, aimed so that their picture is centred.

    aspect: width / height of the view. ``scale`` (the model's zoom about the target) only
    pushes the far plane out so a scaled-up model is not cut off.

    From an eye at ``(cx, cy, e)``, a point ``(x, y, z)`` is in view when
    ``|x - cx| <= (e - z) tan_x`` and ``|y - cy| <= (e - z) tan_y``: for a given aim the
    least ``e`` is the largest of ``z + |x - cx| / tan_x`` and ``z + |y - cy| / tan_y`` over
    the points, exact in perspective. Aimed first at the middle of the points' extents, the
    picture of a deep model is off centre (its near end looks larger), so the aim then moves
    by the picture's own offset, a few times over.
    """
    points = np.asarray(points, dtype=np.float64)
    low, high = points.min(axis=0), points.max(axis=0)
    aim = (low + high) / 2.0
    tan_y = math.tan(math.radians(fov_y_deg) / 2.0) * fill
    eye_z = _aim(np.ascontiguousarray(points), tan_y * aspect, tan_y, aim)
    distance = eye_z - aim[2]
    reach = float(np.linalg.norm(high - low)) / 2.0
    return Camera(
        eye=(float(aim[0]), float(aim[1]), eye_z),
        target=tuple(float(c) for c in aim), fov_y_deg=fov_y_deg,
        near=0.05 * distance, far=distance + 8.0 * reach * max(scale, 1.0),
    )


@exact
def _aim(points, tan_x, tan_y, aim):
    """Move ``aim`` (3,) float64, the middle of ``points``' (n, 3) extents, by the picture's
    own offset four times over (see :func:`fit_points`); the least eye ``z`` for that aim.
    A kernel: numpy took 0.1 ms a frame (at 60 a second) on the outline's hundred-odd
    points, in thirty calls on arrays of two columns."""
    for _ in range(4):
        eye_z = _least_eye_z(points, tan_x, tan_y, aim)
        low_x = low_y = np.inf
        high_x = high_y = -np.inf
        for i in range(points.shape[0]):
            depth = eye_z - points[i, 2]
            # each point's place in the picture, in tan
            seen_x, seen_y = (points[i, 0] - aim[0]) / depth, (points[i, 1] - aim[1]) / depth
            # (numpy's minimum and maximum, which keep a NaN, as its reductions do)
            low_x, high_x = np.minimum(low_x, seen_x), np.maximum(high_x, seen_x)
            low_y, high_y = np.minimum(low_y, seen_y), np.maximum(high_y, seen_y)
        aim[0] += (low_x + high_x) / 2.0 * (eye_z - aim[2])
        aim[1] += (low_y + high_y) / 2.0 * (eye_z - aim[2])
    return _least_eye_z(points, tan_x, tan_y, aim)


@exact
def _least_eye_z(points, tan_x, tan_y, aim):
    """The least eye ``z`` from which every one of ``points`` is in view, aimed at ``aim``."""
    eye_z = -np.inf
    for i in range(points.shape[0]):
        reach = np.maximum(abs(points[i, 0] - aim[0]) / tan_x,
                           abs(points[i, 1] - aim[1]) / tan_y)
        eye_z = np.maximum(eye_z, points[i, 2] + reach)
    return eye_z


def view_camera(view: View, vertices: np.ndarray, aspect: float) -> tuple[Camera, np.ndarray]:
    """The camera framing ``vertices`` (n, 3), world space at rest, turned by ``view``, at
    this width / height; and the model matrix (4, 4) that turns, moves and scales them.
    (Pass the `outline` of a mesh's vertices: it frames them as well, and faster.)"""
    pivot = (vertices.min(axis=0) + vertices.max(axis=0)) / 2.0
    turn = model_matrix(np.radians(view.yaw), np.radians(view.pitch), np.radians(view.roll),
                        pivot=pivot)
    camera = fit_points(transform_points(turn, vertices), aspect, view.fov, FILL, view.scale)
    target = np.array(camera.target)
    model = (translation_matrix((1.0 - view.scale) * target) @ scale_matrix(view.scale)
             @ translation_matrix(view.offset) @ turn)
    return camera, model


def zoomed_light(light: Light, scale: float, camera: Camera) -> Light:
    """``light`` scaled with the model about the point the camera looks at, so that zooming
    magnifies the picture without relighting it (a light left where it was would end up
    inside a model zoomed eight times)."""
    target = np.array(camera.target)
    position = target + scale * (np.array(light.position) - target)
    return replace(light, position=tuple(position.tolist()))

