"""Triangle meshes of the muscle and the bones, built as surfaces of revolution.

Every shape here is one profile revolved about an axis: a column of points ``(x, r)``
(distance along the axis, distance from it) with the outward normal ``(nx, nr)`` of the
profile at each point. The first and last points lie on the axis and become single pole
vertices; every other point becomes a ring of ``segments`` vertices. Revolving such a
profile gives one closed, watertight, consistently wound surface (`_assemble` joins the
rings and the poles), which makes the muscle, the bones' parts, rods and spheres. The
muscle's rings may also be moved sideways within their planes, to lie clear of the bones.

Vertices are ordered from the start pole, ring by ring along the profile, to the end pole.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from biceps.engine.stations import distances_along, section_radii

DEFAULT_SEGMENTS = 48
"""Vertices around the axis: a 48-gon keeps 99.7 % of its circle's area (k sin(2 pi/k) / 2 pi)."""


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle mesh as structure-of-arrays.

    vertices: (n, 3) float64 points.
    normals: (n, 3) float64 unit vertex normals.
    triangles: (m, 3) int32 vertex indices, counter-clockwise seen from outside.

    The arrays are read-only views, so a mesh can share its topology with others.
    """

    vertices: np.ndarray
    normals: np.ndarray
    triangles: np.ndarray

    def __post_init__(self):
        dtypes = {"vertices": np.float64, "normals": np.float64, "triangles": np.int32}
        for name, dtype in dtypes.items():
            array = np.asarray(getattr(self, name), dtype=dtype).view()
            if array.ndim != 2 or array.shape[1] != 3:
                raise ValueError(f"{name} must have shape (k, 3), got {array.shape}")
            array.flags.writeable = False
            object.__setattr__(self, name, array)
        if self.normals.shape != self.vertices.shape:
            raise ValueError(
                f"normals {self.normals.shape} must match vertices {self.vertices.shape}"
            )

    @staticmethod
    def concatenate(meshes) -> "Mesh":
        """One mesh holding all of ``meshes`` (an iterable of Mesh), indices offset to match."""
        meshes = list(meshes)
        if not meshes:
            return Mesh(np.empty((0, 3)), np.empty((0, 3)), np.empty((0, 3), np.int32))
        # int32 offsets keep the sums int32: no int64 copy of every index to convert back;
        # each part's sums written straight into the whole, not into a copy of each part
        # joined after (a second pass over every index)
        offsets = np.cumsum([0] + [len(mesh.vertices) for mesh in meshes[:-1]], dtype=np.int32)
        triangles = np.empty((sum(len(mesh.triangles) for mesh in meshes), 3), np.int32)
        at = 0
        for mesh, offset in zip(meshes, offsets):
            np.add(mesh.triangles, offset, out=triangles[at:at + len(mesh.triangles)])
            at += len(mesh.triangles)
        return Mesh(np.concatenate([mesh.vertices for mesh in meshes]),
                    np.concatenate([mesh.normals for mesh in meshes]), triangles)


def muscle_mesh(
    radii,
    length: float,
    start,
    end,
    segments: int = DEFAULT_SEGMENTS,
    caps: str = "round",
    cap_rings: int | None = None,
    offsets=None,
) -> Mesh:
    """The muscle's surface: frusta through the node rings, closed at both ends.

    radii: (n,) float64, n >= 2, the node radii, all positive; node 0 sits on ``start``,
        node n-1 at ``length`` from it in the direction of ``end``, nodes equally spaced.
    start, end: (3,) float64, the muscle's origin and insertion.
    caps: "round" closes each end with a hemisphere of the end node's radius (the solid
        whose volume the model conserves); "flat" with a disk (the frusta alone).
    cap_rings: latitude rings per hemisphere, counting the end node's ring, so also the
        number of bands from that ring to the pole; default ``segments / 4`` (at least 2),
        which makes the caps' facets about as wide as they are tall.
    offsets: (m, 3) float64, or None for the straight muscle: how far each of m body rings,
        equally spaced from start to end, is moved sideways, within its own plane (the part
        along the axis is dropped). ``m - 1`` must be a multiple of ``n - 1``: the rings
        between two nodes take radii on the straight line between theirs, so the profile is
        the nodes' own. The caps move with the end rings. Moving circular sections within
        their planes keeps the solid's volume (Cavalieri's principle), and the mesh's too:
        every band still lies between two parallel polygons, and moving either only
        translates the band's middle section, so its volume (the prismatoid formula,
        ``h (A0 + 4 Am + A1) / 6``) stays the same.

    Rings: ``m`` (flat) or ``m + 2 (cap_rings - 1)`` (round); triangles: twice ``segments``
    times the number of rings.
    """
    radii = _positive_radii(radii)
    if len(radii) < 2:
        raise ValueError(f"a muscle needs at least 2 nodes, got {len(radii)}")
    _check_segments(segments)
    if caps not in ("round", "flat"):
        raise ValueError(f'caps must be "round" or "flat", got {caps!r}')
    length = float(length)
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length must be positive, got {length}")
    axis = _unit_axis(start, end)
    start = np.asarray(start, dtype=np.float64)
    offsets = _ring_offsets(offsets, len(radii), axis)
    spokes = _spokes(axis, segments)  # one axis for the body and both caps
    body, normals = _muscle_body(radii, length, offsets, axis, spokes, caps)
    body += start
    if caps == "flat":
        poles = start + offsets[[0, -1]] + np.outer([0.0, length], axis)
        return _assemble(poles, [body], [normals], np.array([-1.0, 1.0]), axis)
    sin, cos = _quarter_circle(_cap_rings(segments, cap_rings))
    # Elevations from the equator (excluded: it is the end node's ring) to the pole.
    first = _arc(0.0, radii[0], -sin[:0:-1], cos[:0:-1])
    last = _arc(length, radii[-1], sin[1:], cos[1:])
    rings = [_rings(first[1:], start + offsets[0], axis, spokes), (body, normals),
             _rings(last[:-1], start + offsets[-1], axis, spokes)]
    poles = np.array([start + offsets[0] + first[0, 0] * axis,
                      start + offsets[-1] + last[-1, 0] * axis])
    return _assemble(poles, [v for v, _ in rings], [n for _, n in rings],
                     np.array([-1.0, 1.0]), axis)


def bent_muscle_mesh(radii, points, axes, segments: int = DEFAULT_SEGMENTS) -> Mesh:
    """A muscle along a bent path (round a wrapping cylinder), closed by hemispheres.

    radii: (n,) float64 node radii, all positive. points: (m, 3) float64 the centres of m
    rings equally spaced along the path, the first on the origin and the last on the
    insertion, m - 1 a multiple of n - 1 (as in `muscle_mesh`); axes: (m, 3) the path's
    unit direction at each. Each ring lies across its own axis, so the solid is a tube
    whose sections are centred on its path: its volume is the integral of their areas
    along it (Pappus), the straight muscle's, while the bend is wider than the tube.
    """
    radii = _positive_radii(radii)
    points, axes = np.asarray(points, dtype=np.float64), np.asarray(axes, dtype=np.float64)
    _check_segments(segments)
    # The rings take the radii of equal steps along the profile, wherever they were moved.
    r = section_radii(radii, len(points))
    along = distances_along(points)
    slopes = np.gradient(r, along)
    spokes = _spokes_along(axes, segments)  # (m, segments, 3)
    vertices = points[:, None, :] + r[:, None, None] * spokes
    normals = spokes - slopes[:, None, None] * axes[:, None, :]
    normals /= _lengths(normals)
    sin, cos = _quarter_circle(_cap_rings(segments, None))
    first = _arc(0.0, r[0], -sin[:0:-1], cos[:0:-1])
    last = _arc(0.0, r[-1], sin[1:], cos[1:])
    before = _rings(first[1:], points[0], axes[0], spokes[0])
    after = _rings(last[:-1], points[-1], axes[-1], spokes[-1])
    poles = np.array([points[0] + first[0, 0] * axes[0], points[-1] + last[-1, 0] * axes[-1]])
    mesh = _assemble(poles, [before[0], vertices, after[0]], [before[1], normals, after[1]],
                     np.array([-1.0, 1.0]), axes[0])
    pole_normals = mesh.normals.copy()
    pole_normals[-1] = axes[-1]  # the end pole faces along the path's last direction
    return Mesh(mesh.vertices, pole_normals, mesh.triangles)


def cylinder_mesh(
    start, end, radius: float, segments: int = DEFAULT_SEGMENTS, caps: str = "round"
) -> Mesh:
    """A closed rod of ``radius`` from ``start`` to ``end`` ((3,) float64 each).

    With round caps the rod ends in hemispheres centred on ``start`` and ``end``.
    """
    length = np.linalg.norm(np.subtract(end, start, dtype=np.float64))
    return muscle_mesh(np.full(2, float(radius)), length, start, end, segments, caps)


def sphere_mesh(center, radius: float, segments: int = DEFAULT_SEGMENTS) -> Mesh:
    """A UV sphere: ``segments`` meridians, ``segments / 2`` bands (at least 2), poles on y.

    center: (3,) float64. Every normal is exactly radial.
    """
    _check_segments(segments)
    (radius,) = _positive_radii([radius])
    bands = max(2, segments // 2)
    elevations = np.linspace(-np.pi / 2, np.pi / 2, bands + 1)
    profile = _arc(0.0, radius, np.sin(elevations), np.cos(elevations))
    center = np.asarray(center, dtype=np.float64)
    return _revolve(profile, center, np.array([0.0, 1.0, 0.0]), segments)


def revolved_mesh(profile, start, axis, segments: int = DEFAULT_SEGMENTS) -> Mesh:
    """The closed surface of revolution of ``profile`` about the line from ``start`` along
    ``axis`` ((3,) each, the axis need not be unit).

    profile: (k, 2) float64, k >= 3, rows (distance along the axis, radius), from one pole
    (radius 0) to the other, the radii between positive. Each point's normal is the mean of
    the normals of the two profile segments that meet there, so a smooth profile shades
    smoothly and a corner shows.
    """
    profile = np.asarray(profile, dtype=np.float64)
    if profile.ndim != 2 or profile.shape[1] != 2 or len(profile) < 3:
        raise ValueError(f"a profile is (k, 2) with k >= 3, got shape {profile.shape}")
    x, r = profile.T
    if r[0] != 0.0 or r[-1] != 0.0 or not np.all(r[1:-1] > 0):
        raise ValueError("a profile runs from a pole (radius 0) to a pole, radii between > 0")
    _check_segments(segments)
    steps = np.diff(profile, axis=0)
    sides = np.column_stack([-steps[:, 1], steps[:, 0]])  # (dx, dr) turned a quarter: outward
    sides /= np.hypot(sides[:, :1], sides[:, 1:])
    normals = sides[:-1] + sides[1:]
    normals /= np.hypot(normals[:, :1], normals[:, 1:])
    rows = np.column_stack([x, r, np.concatenate([[-1.0], normals[:, 0], [1.0]]),
                            np.concatenate([[0.0], normals[:, 1], [0.0]])])
    axis = _unit_axis(np.zeros(3), axis)
    return _revolve(rows, np.asarray(start, dtype=np.float64), axis, segments)


def _ring_offsets(offsets, nodes: int, axis: np.ndarray) -> np.ndarray:
    """The body rings' sideways offsets (m, 3), within their planes: zeros, one per node, if
    ``offsets`` is None."""
    if offsets is None:
        return np.zeros((nodes, 3))
    offsets = np.array(offsets, dtype=np.float64)
    if offsets.ndim != 2 or offsets.shape[1] != 3 or (len(offsets) - 1) % (nodes - 1):
        raise ValueError(
            f"offsets must be (m, 3) with m - 1 a multiple of the {nodes - 1} segments, "
            f"got shape {offsets.shape}"
        )
    if not np.all(np.isfinite(offsets)):
        raise ValueError("offsets must be finite")
    return offsets - np.outer(offsets @ axis, axis)


def _muscle_body(radii: np.ndarray, length: float, offsets: np.ndarray, axis: np.ndarray,
                 spokes: np.ndarray, caps: str) -> tuple[np.ndarray, np.ndarray]:
    """The body's rings about the unit ``axis`` (3,), vertex ``j`` of each out along
    ``spokes[j]`` (``spokes``: (segments, 3), see `_spokes`): vertices and unit normals, each
    (m, segments, 3).

    A frustum's side tilts its normal back by atan(dr/dx); a ring moved sideways tilts the
    side by as much again where its spoke points along the move, so along spoke ``s`` a
    band's slope is ``(dr + do.s) / dx``. A ring's normal is the normalised mean of the two
    sides that meet there, so shading is smooth across it.
    """
    m = len(offsets)
    x = np.linspace(0.0, length, m)  # exact at both ends
    r = np.interp(x, np.linspace(0.0, length, len(radii)), radii)
    segments = len(spokes)
    slopes = (np.diff(r)[:, None] + np.diff(offsets, axis=0) @ spokes.T) / np.diff(x)[:, None]
    sides = np.empty((m + 1, segments, 3))  # each band's normals, and the caps' at the ends
    sides[1:-1] = spokes[None] - slopes[..., None] * axis
    if caps == "round":
        # A hemisphere meets the frustum along its equator, where its normal is radial:
        # averaging that with the side normal is the interior nodes' rule applied to a
        # neighbour of slope zero, so the shading runs on smoothly into the cap.
        sides[[0, -1]] = spokes
    else:
        # The rim of a flat cap is a real right-angle edge: its ring keeps the side's exact
        # normal (the disk then shades like a shallow dome, which only the test mode shows).
        sides[[0, -1]] = sides[[1, -2]]
    sides /= _lengths(sides)
    normals = sides[:-1] + sides[1:]
    normals /= _lengths(normals)
    vertices = (x[:, None] * axis + offsets)[:, None, :] + r[:, None, None] * spokes
    return vertices, normals


def _lengths(vectors: np.ndarray) -> np.ndarray:
    """The lengths (..., 1) of ``vectors`` (..., 3): ``np.linalg.norm``'s sums, written out
    over whole arrays, as three times as fast as its reduction over rows of three (the same
    operations in the same order, so the same values)."""
    x, y, z = vectors[..., 0], vectors[..., 1], vectors[..., 2]
    return np.sqrt(x * x + y * y + z * z)[..., None]


def _arc(x: float, radius: float, sin: np.ndarray, cos: np.ndarray) -> np.ndarray:
    """The profile (k, 4) of a sphere of ``radius`` centred at ``x`` on the axis, at the
    elevations whose sines and cosines are ``sin``, ``cos`` (k,) (positive towards +x)."""
    return np.column_stack([x + radius * sin, radius * cos, sin, cos])


@lru_cache(maxsize=64)
def _quarter_circle(bands: int) -> tuple[np.ndarray, np.ndarray]:
    """sin and cos (bands + 1,) float64, read-only, of ``bands`` equal steps from 0 to pi/2."""
    elevations = np.linspace(0.0, np.pi / 2, bands + 1)
    sin, cos = np.sin(elevations), np.cos(elevations)
    sin.flags.writeable = cos.flags.writeable = False
    return sin, cos


def _revolve(profile: np.ndarray, start: np.ndarray, axis: np.ndarray, segments: int) -> Mesh:
    """Revolve ``profile`` (k, 4) of rows ``(x, r, nx, nr)`` about the line through
    ``start`` (3,) along the unit ``axis`` (3,).

    The first and last rows are the poles (only their ``x`` and the sign of ``nx`` count);
    the k - 2 rows between them become rings, vertex ``j`` at angle ``2 pi j / segments``
    counter-clockwise about the axis.
    """
    vertices, normals = _rings(profile[1:-1], start, axis, _spokes(axis, segments))
    poles = start + np.outer(profile[[0, -1], 0], axis)
    return _assemble(poles, [vertices], [normals], np.sign(profile[[0, -1], 2]), axis)


def _rings(profile: np.ndarray, centre: np.ndarray, axis: np.ndarray,
           spokes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and normals (k, segments, 3) of the rings of ``profile`` (k, 4) rows
    ``(x, r, nx, nr)``, revolved about the line through ``centre`` along ``axis``, whose
    ``spokes`` (segments, 3) they take."""
    x, r, nx, nr = profile.T
    vertices = (centre + x[:, None] * axis)[:, None, :] + r[:, None, None] * spokes
    normals = nr[:, None, None] * spokes + (nx[:, None] * axis)[:, None, :]
    return vertices, normals


def _assemble(poles: np.ndarray, vertices: list, normals: list, pole_sides: np.ndarray,
              axis: np.ndarray) -> Mesh:
    """One closed mesh: a pole (3,) at each end of ``poles`` (2, 3), and between them the
    rings of ``vertices`` and ``normals`` (lists of (k, segments, 3)), in order; each pole's
    normal is the axis times its entry of ``pole_sides`` (2,) (-1 or 1)."""
    rings = np.concatenate(vertices)
    segments = rings.shape[1]
    return Mesh(
        np.concatenate([poles[:1], rings.reshape(-1, 3), poles[1:]]),
        np.concatenate([pole_sides[:1, None] * axis, np.concatenate(normals).reshape(-1, 3),
                        pole_sides[1:, None] * axis]),
        _closed_tube(len(rings), segments),
    )


def _spokes(axis: np.ndarray, segments: int) -> np.ndarray:
    """(segments, 3) unit radial directions about ``axis``, vertex ``j`` at angle
    ``2 pi j / segments`` counter-clockwise."""
    u, w = _ring_frame(axis)
    cos, sin = _unit_circle(segments)
    return cos[:, None] * u + sin[:, None] * w


def _spokes_along(axes: np.ndarray, segments: int) -> np.ndarray:
    """(m, segments, 3) the `_spokes` about each of ``axes`` (m, 3). A path wrapped round
    the elbow is straight before and after its arc, where its axes repeat: each run's are
    worked out once, not once a ring (0.51 -> 0.25 ms a wrapped muscle of the six), and
    copied to the rest of the run in one gather, not ring by ring (41 rings of 5 runs
    46 -> 42 us; 1,024 rings of 60, a subdivided muscle, 779 -> 398 us)."""
    bits = np.ascontiguousarray(axes).view(np.uint64)  # the same bits, as before: -0.0 is not 0.0
    first = np.ones(len(axes), dtype=bool)
    first[1:] = np.any(bits[1:] != bits[:-1], axis=1)
    runs = np.stack([_spokes(axis, segments) for axis in axes[first]])
    return np.take(runs, np.cumsum(first) - 1, axis=0)


@lru_cache(maxsize=64)
def _closed_tube(rings: int, segments: int) -> np.ndarray:
    """Triangles (2 rings segments, 3) int32, read-only, of ``rings`` rings of ``segments``
    vertices closed by a pole before and after, laid out as `_revolve` lays them out.

    The topology depends on the two counts only, so every frame reuses it.
    """
    start_pole, end_pole = 0, rings * segments + 1
    j = np.arange(segments)
    ring = 1 + np.arange(rings)[:, None] * segments  # first vertex of each ring
    a, b = ring + j, ring + (j + 1) % segments  # the ring closes by wrap-around, not a seam vertex
    c, d = b + segments, a + segments  # the same two on the next ring
    # Going from a to b turns counter-clockwise about the axis and from a to d runs along
    # it, so (a, b, c) and (a, c, d) face away from the axis (right-hand rule).
    quads = np.stack([a[:-1], b[:-1], c[:-1], a[:-1], c[:-1], d[:-1]], axis=-1).reshape(-1, 3)
    start_fan = np.stack([np.full(segments, start_pole), b[0], a[0]], axis=-1)
    end_fan = np.stack([np.full(segments, end_pole), a[-1], b[-1]], axis=-1)
    triangles = np.concatenate([start_fan, quads, end_fan]).astype(np.int32)
    triangles.flags.writeable = False
    return triangles


@lru_cache(maxsize=64)
def _unit_circle(segments: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin (segments,) float64, read-only, of ``2 pi j / segments``."""
    angles = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    cos, sin = np.cos(angles), np.sin(angles)
    cos.flags.writeable = sin.flags.writeable = False
    return cos, sin


def _ring_frame(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors u, w (3,) with (axis, u, w) a right-handed orthonormal frame.

    They are the images of +y and +z under the shortest rotation taking +x onto the axis,
    which varies smoothly with the axis everywhere except at -x. The arm lies in the x-y
    plane and its muscle runs from the shoulder down to the forearm, never along -x, and
    for any axis in that plane the rotation is about z: w stays +z, so the rings do not
    twist at all as the elbow bends.
    """
    ax, ay, az = axis.tolist()
    k = 1.0 + ax
    if k > 1e-6:
        u = np.array([-ay, 1.0 - ay * ay / k, -ay * az / k])
    else:
        u = np.array([0.0, 1.0, 0.0])  # near -x the rotation is undefined: any normal will do
    u -= (u @ axis) * axis  # Gram-Schmidt removes the rounding left by the division
    u /= math.sqrt(u @ u)
    ux, uy, uz = u.tolist()
    return u, np.array([ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux])  # axis x u


def _unit_axis(start, end) -> np.ndarray:
    axis = np.subtract(end, start, dtype=np.float64)
    if axis.shape != (3,):
        raise ValueError(f"start and end must be points (3,), got shape {axis.shape}")
    norm = np.linalg.norm(axis)
    if not (np.isfinite(norm) and norm > 0):
        raise ValueError(f"start and end must be distinct finite points, got {start} and {end}")
    return axis / norm


def _positive_radii(radii) -> np.ndarray:
    radii = np.asarray(radii, dtype=np.float64)
    if radii.ndim != 1 or len(radii) < 1:
        raise ValueError(f"radii must be a non-empty 1-D array, got shape {radii.shape}")
    if not np.all(np.isfinite(radii) & (radii > 0)):
        raise ValueError(f"radii must be positive and finite, got {radii}")
    return radii


def _check_segments(segments: int) -> None:
    if segments < 3:
        raise ValueError(f"segments must be at least 3 (a ring needs 3 vertices), got {segments}")


def _cap_rings(segments: int, cap_rings: int | None) -> int:
    if cap_rings is None:
        return max(2, round(segments / 4))
    if cap_rings < 1:
        raise ValueError(f"cap_rings must be at least 1, got {cap_rings}")
    return cap_rings
