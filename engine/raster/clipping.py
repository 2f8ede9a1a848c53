"""Clipping: the clip volume's planes, and the pass that cuts the triangles crossing them.

Triangles crossing the near plane are clipped in clip space (Sutherland-Hodgman), and so
are triangles reaching beyond a wide guard band around the screen, which keeps the fixed
point coordinates small enough that the edge functions cannot overflow int64. Clipping is
a separate pass, compiled the first time a frame needs it.
"""

import math

import numpy as np

from biceps.engine.jit import helper, ngjit
from biceps.engine.raster.coverage import ONE

GUARD_BAND = float(1 << 19)
"""Pixels beyond each edge of the screen within which triangles are not clipped. With
screens up to 2^16 pixels wide, fixed-point coordinates stay below 2^28, so the edge
functions' products stay below 2^59."""

# Outcode bits: which side of the clip volume's planes a vertex is outside.
NEAR, LEFT, RIGHT, BOTTOM, TOP = 1, 2, 4, 8, 16
CLIP_PLANES = (NEAR, LEFT, RIGHT, BOTTOM, TOP)
CLIP_MASK = NEAR | LEFT | RIGHT | BOTTOM | TOP
FAR = 32  # for trivial rejection only: the depth test hides the rest
INVALID = 64  # a coordinate is NaN or infinite
MAX_POLYGON = 3 + len(CLIP_PLANES)  # each plane adds at most one vertex to a convex polygon


@helper
def _guard(size):
    """How far out (in units of w) the guard band's planes are, for a screen ``size`` wide."""
    return 1.0 + 2.0 * GUARD_BAND / size


@helper
def _to_screen(x, y, z, w, width, height):
    """Clip space to screen space: (X, Y) int64 in 1/256 pixel, the reversed depth
    ``(1 - z / w) / 2`` (float64, 1 on the near plane, 0 on the far one) and ``1 / w``. The
    same arithmetic as `project_vertices`, for the vertices that clipping makes."""
    inv_w = 1.0 / w
    sx = (x * inv_w + 1.0) * (0.5 * width)
    sy = (1.0 - y * inv_w) * (0.5 * height)
    return (np.int64(math.floor(sx * ONE + 0.5)), np.int64(math.floor(sy * ONE + 0.5)),
            (w - z) * inv_w * 0.5, inv_w)


@helper
def _clip_distance(polygon, slot, i, plane, gx, gy):
    """How far vertex i of polygon[slot] (rows x, y, z, w, attributes...) is inside
    ``plane``, in clip space units: >= 0 inside. The same inequalities as the outcodes of
    `project_vertices`."""
    x, y, z, w = polygon[slot, i, 0], polygon[slot, i, 1], polygon[slot, i, 2], polygon[slot, i, 3]
    if plane == NEAR:
        return z + w
    if plane == LEFT:
        return x + gx * w
    if plane == RIGHT:
        return gx * w - x
    if plane == BOTTOM:
        return y + gy * w
    return gy * w - y


@helper
def _clip_polygon(polygon, source, slot, n, plane, gx, gy):
    """One Sutherland-Hodgman pass: cut the convex polygon of n vertices in polygon[slot]
    by ``plane`` into polygon[1 - slot], and return its vertex count.

    polygon: (2, MAX_POLYGON, 4 + a) float64, rows clip position then attributes;
    source: (2, MAX_POLYGON) int64, the mesh vertex each polygon vertex is, -1 if new.

    A new vertex is always interpolated from the inside end of its edge towards the outside
    end, so two triangles sharing an edge compute the very same point and stay watertight.
    """
    out = 1 - slot
    count = 0
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        di = _clip_distance(polygon, slot, i, plane, gx, gy)
        dj = _clip_distance(polygon, slot, j, plane, gx, gy)
        if di >= 0.0:
            for c in range(polygon.shape[2]):
                polygon[out, count, c] = polygon[slot, i, c]
            source[out, count] = source[slot, i]
            count += 1
        if (di >= 0.0) != (dj >= 0.0):
            inside, outside, d_in, d_out = (i, j, di, dj) if di >= 0.0 else (j, i, dj, di)
            t = d_in / (d_in - d_out)
            for c in range(polygon.shape[2]):
                start = polygon[slot, inside, c]
                polygon[out, count, c] = start + t * (polygon[slot, outside, c] - start)
            source[out, count] = -1
            count += 1
    return count


@ngjit
def clip_triangles(triangles, clip, screen_xy, screen_z, screen_q, outcodes, attributes, width,
                   height, out_xy, out_z, out_q, out_attributes, out_triangles, counts, polygon,
                   source):
    """Clip the triangles that cross a clipping plane (but are not wholly outside one) and
    write what is left of them as a mesh for the rasterize kernels.

    triangles: (m, 3) int32; clip: (4, n), screen_xy: (2, n), screen_z: (n,), screen_q:
    (n,), outcodes: (n,) from `project_vertices`; attributes: (a, n) float64; width, height: the
    screen. Writes out_xy: (2, k) int64, out_z: (k,) float64, out_q: (k,) float64,
    out_attributes: (a, k) float64 and out_triangles: (j, 3) int32, room enough being
    ``MAX_POLYGON`` vertices and ``MAX_POLYGON - 2`` triangles per triangle to clip, and
    counts: (2,) int64, the vertices and triangles written. Each clipped triangle leaves a
    convex polygon, drawn as a fan (the near plane alone leaves a triangle or a
    quadrilateral). polygon: (2, MAX_POLYGON, 4 + a) float64 and source: (2, MAX_POLYGON)
    int64, scratch (`_clip_polygon`), passed in as every kernel's is (``engine/jit.py``).
    """
    gx, gy = _guard(width), _guard(height)
    a = attributes.shape[0]
    vertex_count = triangle_count = 0
    for t in range(triangles.shape[0]):
        spill, inside = 0, 0xFF
        for k in range(3):
            spill |= outcodes[triangles[t, k]]
            inside &= outcodes[triangles[t, k]]
        if inside or spill & INVALID or not spill & CLIP_MASK:
            continue  # wholly outside a plane, not a number, or needs no clipping
        for k in range(3):
            v = triangles[t, k]
            for c in range(4):
                polygon[0, k, c] = clip[c, v]
            for c in range(a):
                polygon[0, k, 4 + c] = attributes[c, v]
            source[0, k] = v
        n, slot = 3, 0
        for plane in CLIP_PLANES:
            if spill & plane and n >= 3:
                n = _clip_polygon(polygon, source, slot, n, plane, gx, gy)
                slot = 1 - slot
        if n < 3:
            continue
        for k in range(n):
            v, o = source[slot, k], vertex_count + k
            if v >= 0:
                # A mesh vertex: keep its snapped position, so its neighbours agree exactly.
                out_xy[0, o], out_xy[1, o] = screen_xy[0, v], screen_xy[1, v]
                out_z[o], out_q[o] = screen_z[v], screen_q[v]
            else:
                out_xy[0, o], out_xy[1, o], out_z[o], out_q[o] = _to_screen(
                    polygon[slot, k, 0], polygon[slot, k, 1], polygon[slot, k, 2],
                    polygon[slot, k, 3], width, height)
            for c in range(a):
                out_attributes[c, o] = polygon[slot, k, 4 + c]
        for k in range(1, n - 1):
            out_triangles[triangle_count, 0] = vertex_count
            out_triangles[triangle_count, 1] = vertex_count + k
            out_triangles[triangle_count, 2] = vertex_count + k + 1
            triangle_count += 1
        vertex_count += n
    counts[0], counts[1] = vertex_count, triangle_count
