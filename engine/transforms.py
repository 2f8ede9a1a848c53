"""Transforms and camera: 4x4 matrices as plain functions on numpy arrays.

Conventions (those of ``engine/__init__.py``, and OpenGL's):

- Right-handed world, ``y`` up, angles in radians (the :class:`Camera` keeps its field of
  view in degrees, as the configuration does).
- Matrices act on column vectors; points are rows, so ``points @ M[:3, :3].T + M[:3, 3]``
  moves them, and ``A @ B`` applies ``B`` first.
- Eye space: the camera at the origin looking down ``-z``, ``y`` up.
- Clip space: ``perspective`` is OpenGL's (``gluPerspective``): a point is visible when
  ``-w <= x, y, z <= w``; dividing by ``w`` gives normalised device coordinates (NDC) in
  ``[-1, 1]``, ``z = -1`` on the near plane and ``+1`` on the far one.
- Screen space (``viewport``): ``x`` to the right and ``y`` down in pixels, the top-left
  pixel covering ``[0, 1) x [0, 1)`` (so its centre is at ``(0.5, 0.5)``), and a reversed
  depth, 1 on the near plane and 0 on the far one (``engine/raster`` says why). The
  rasterizer applies exactly this mapping.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Annotated

import numpy as np

from biceps.engine.settings import Limits, Point, number, setting


def rotation_x(angle: float) -> np.ndarray:
    """(4, 4) float64: rotate by ``angle`` radians about ``x`` (pitch), ``y`` towards ``z``."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]], dtype=np.float64)


def rotation_y(angle: float) -> np.ndarray:
    """(4, 4) float64: rotate by ``angle`` radians about ``y`` (yaw), ``z`` towards ``x``."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]], dtype=np.float64)


def rotation_z(angle: float) -> np.ndarray:
    """(4, 4) float64: rotate by ``angle`` radians about ``z`` (roll), ``x`` towards ``y``."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=np.float64)


def translation_matrix(offset) -> np.ndarray:
    """(4, 4) float64: move by ``offset`` (3,)."""
    matrix = np.eye(4)
    matrix[:3, 3] = offset
    return matrix


def scale_matrix(factor) -> np.ndarray:
    """(4, 4) float64: scale by ``factor``, a number or (3,) per axis."""
    return np.diag(np.append(np.broadcast_to(np.asarray(factor, dtype=np.float64), 3), 1.0))


def model_matrix(yaw: float = 0.0, pitch: float = 0.0, roll: float = 0.0, scale=1.0,
                 translation=(0.0, 0.0, 0.0), pivot=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(4, 4) float64: scale and rotate about ``pivot`` (3,), then move by ``translation`` (3,).

    ``p' = R S (p - pivot) + pivot + translation`` with ``R = R_y(yaw) R_x(pitch) R_z(roll)``
    (roll first, yaw last: the yaw turns the model about the world's vertical, whatever the
    pitch). Angles in radians; ``scale`` a number or (3,).
    """
    pivot = np.asarray(pivot, dtype=np.float64)
    rotate = rotation_y(yaw) @ rotation_x(pitch) @ rotation_z(roll)
    return (translation_matrix(pivot + np.asarray(translation, dtype=np.float64)) @ rotate
            @ scale_matrix(scale) @ translation_matrix(-pivot))


def normal_matrix(matrix) -> np.ndarray:
    """(3, 3) float64: the inverse transpose of ``matrix``'s linear part, which keeps
    normals perpendicular to the surface under any invertible affine ``matrix`` (4, 4)."""
    return np.linalg.inv(np.asarray(matrix, dtype=np.float64)[:3, :3]).T


def look_at(eye, target, up=(0.0, 1.0, 0.0)) -> np.ndarray:
    """(4, 4) float64 view matrix (``gluLookAt``): world to eye space.

    eye, target, up: (3,). ``eye`` goes to the origin, ``target`` onto the ``-z`` axis and
    ``up`` into the upper half of the ``y``-``z`` plane. ``up`` must not be parallel to the
    line of sight.
    """
    eye = np.asarray(eye, dtype=np.float64)
    forward = _unit(np.asarray(target, dtype=np.float64) - eye)
    right = _unit(_cross(forward, np.asarray(up, dtype=np.float64)))
    true_up = _cross(right, forward)
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = right, true_up, -forward
    view[:3, 3] = -view[:3, :3] @ eye
    return view


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for (3,) vectors (``np.cross`` costs more than the arithmetic, per call, by
    far: its checks and broadcasting are made for large arrays)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / math.sqrt(float(v @ v))


def perspective(fov_y: float, aspect: float, near: float, far: float) -> np.ndarray:
    """(4, 4) float64 projection (``gluPerspective``): eye space to clip space.

    fov_y: the vertical field of view in radians; aspect: width / height;
    0 < near < far: the distances to the clipping planes.
    """
    f = 1.0 / math.tan(fov_y / 2.0)
    return np.array([
        [f / aspect, 0.0, 0.0, 0.0],
        [0.0, f, 0.0, 0.0],
        [0.0, 0.0, (far + near) / (near - far), 2.0 * far * near / (near - far)],
        [0.0, 0.0, -1.0, 0.0],
    ])


def viewport(width: int, height: int) -> np.ndarray:
    """(4, 4) float64: NDC to screen space, ``[-1, 1]^3`` onto
    ``[0, width] x [height, 0] x [1, 0]`` (y down, depth reversed)."""
    return np.array([
        [width / 2.0, 0.0, 0.0, width / 2.0],
        [0.0, -height / 2.0, 0.0, height / 2.0],
        [0.0, 0.0, -0.5, 0.5],
        [0.0, 0.0, 0.0, 1.0],
    ])


def transform_points(matrix, points) -> np.ndarray:
    """(n, 3) float64: ``points`` (n, 3) through ``matrix`` (4, 4), divided by ``w``."""
    matrix = np.asarray(matrix, dtype=np.float64)
    homogeneous = np.asarray(points, dtype=np.float64) @ matrix[:, :3].T + matrix[:, 3]
    return homogeneous[:, :3] / homogeneous[:, 3:]


@dataclass(frozen=True)
class Camera:
    """A perspective camera: where it is, what it looks at, how wide it sees.

    eye, target, up: (3,) world space, cm. fov_y_deg: vertical field of view, degrees.
    near, far: distances (cm) to the clipping planes, ``0 < near < far``.
    """

    eye: tuple[float, float, float] = (0.0, 0.0, 100.0)
    target: tuple[float, float, float] = (0.0, 0.0, 0.0)
    up: tuple[float, float, float] = (0.0, 1.0, 0.0)
    fov_y_deg: float = 35.0
    near: float = 1.0
    far: float = 1000.0

    def view_matrix(self) -> np.ndarray:
        """(4, 4) float64: world to eye space."""
        return look_at(self.eye, self.target, self.up)

    def projection_matrix(self, aspect: float) -> np.ndarray:
        """(4, 4) float64: eye to clip space for a view ``aspect`` = width / height."""
        return perspective(math.radians(self.fov_y_deg), aspect, self.near, self.far)


FRACTION = Limits(0, 1)
SHININESS = Limits(1, 512)


@setting("light")
class Light:
    """A white point light fixed in world space (it does not turn with the model).

    position: (3,) world space, cm. ambient, diffuse, specular: the weights of the three
    terms of the lighting model; shininess: the Blinn-Phong exponent. A light outside these
    rules cannot be made (:class:`~engine.errors.SettingError`, see ``engine/settings.py``).
    """

    position: Point = (60.0, 80.0, 120.0)
    ambient: Annotated[float, number(FRACTION)] = 0.2
    diffuse: Annotated[float, number(FRACTION)] = 0.8
    specular: Annotated[float, number(FRACTION)] = 0.3
    shininess: Annotated[float, number(SHININESS)] = 24.0


def frame_camera(bounds_min, bounds_max, aspect: float, fov_y_deg: float = 35.0,
                 fill: float = 0.9) -> Camera:
    """A camera on the ``+z`` side of a box, looking down ``-z`` at its centre, as close as
    it can be with the whole box in view; the box then spans ``fill`` of the view's height
    or width, whichever is tighter.

    bounds_min, bounds_max: (3,) opposite corners of the box, world space.
    aspect: width / height of the view.

    Every point of the box is at most the half-extents ``(hx, hy)`` off the line of sight and
    no nearer than the box's front face, so fitting the front face fits the whole box.
    """
    low = np.asarray(bounds_min, dtype=np.float64)
    high = np.asarray(bounds_max, dtype=np.float64)
    centre, half = (low + high) / 2.0, np.maximum((high - low) / 2.0, 1e-9)
    tan_y = math.tan(math.radians(fov_y_deg) / 2.0) * fill
    tan_x = tan_y * aspect
    to_front = max(half[1] / tan_y, half[0] / tan_x)
    distance = to_front + half[2]
    eye = (float(centre[0]), float(centre[1]), float(centre[2] + distance))
    # The near plane a quarter of the way to the box, so that turning the model about its
    # centre does not cut it; the far plane well behind it.
    near = max(float(to_front) * 0.25, 1e-6)
    far = float(distance + 4.0 * np.linalg.norm(half) + 10.0 * near)
    return Camera(eye=eye, target=tuple(float(c) for c in centre), fov_y_deg=fov_y_deg,
                  near=near, far=far)
