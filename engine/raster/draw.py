"""The draw loop: each triangle rejected, culled, covered and shaded.

Every quantity is set up per triangle as a plane equation in screen space through the three
snapped vertices. Depth (``z / w``) is linear in screen space, so its plane is exact. An
attribute (colour, normal, position) is linear across the triangle in space, not on the
screen: perspective makes ``a / w`` and ``1 / w`` linear on the screen instead, so those
are the planes, and the shader divides one by the other at each pixel, as a GPU does
(Heckbert and Moreton, "Interpolation for Polygon Texture Mapping and Shading", 1991).
Interpolating ``a`` itself on the screen, Gouraud's shortcut, drifts by tens of colour
levels in a close-up, where a triangle's near corner is much nearer than its far one.

Most triangles are far shallower than that, and the division costs Gouraud's cheap loop half
as much again, so a triangle whose drift is bounded below ``AFFINE_BELOW`` levels keeps
Gouraud's shortcut. Along a line from ``q_a`` to ``q_b`` the perspective-correct weight of
the far end is ``t q_b / ((1 - t) q_a + t q_b)``, which departs from ``t`` by at most
``(sqrt(r) - 1) / (sqrt(r) + 1)`` with ``r = q_b / q_a`` (at ``t = 1 / (1 + sqrt(r))``);
within a triangle no further than with ``r`` the ratio of its largest ``q`` to its least, so
an attribute ranging over ``d`` across the triangle drifts by at most that times ``d``. The
triangle picks its span loop once, from two written out in full: choosing inside the span
shader, for every row, ran 70 % slower, even with every triangle taking the same one. Phong's
attributes (positions, normals) sway the colour too sharply for such a bound, and the
division is a small part of its pixel: Phong always divides.
"""

import math

import numpy as np

from biceps.engine.jit import helper, inline, ngjit
from biceps.engine.raster.clipping import FAR
from biceps.engine.raster.coverage import ONE, may_cover, triangle_spans
from biceps.engine.raster.shading import (count_overdraw, shade_gouraud, shade_gouraud_on_screen,
                                          shade_phong)

AFFINE_BELOW = 0.25
"""Gouraud's colour levels below which a triangle's drift in perspective goes unseen: it is
then interpolated on the screen, with no division per pixel."""


@helper
def _set_plane(planes, row, x0, y0, e1x, e1y, e2x, e2y, inv_det, v0, v1, v2):
    """planes[row] = (c, d/dx, d/dy) of the plane ``c + x d/dx + y d/dy`` through
    (x0, y0, v0), (x0 + e1x, y0 + e1y, v1), (x0 + e2x, y0 + e2y, v2) (Cramer's rule)."""
    d1 = v1 - v0
    d2 = v2 - v0
    ddx = (d1 * e2y - d2 * e1y) * inv_det
    ddy = (d2 * e1x - d1 * e2x) * inv_det
    planes[row, 0] = v0 - ddx * x0 - ddy * y0
    planes[row, 1] = ddx
    planes[row, 2] = ddy


@helper
def _drift(q0, q1, q2, attributes, i0, i1, i2):
    """The most an attribute of the triangle can drift from its perspective-correct value
    when interpolated on the screen (see the module's docstring), in its own units."""
    low = q0 if q0 < q1 else q1
    low = low if low < q2 else q2
    high = q0 if q0 > q1 else q1
    high = high if high > q2 else q2
    root = math.sqrt(high / low)
    spread = 0.0
    for k in range(attributes.shape[0]):
        a0, a1, a2 = attributes[k, i0], attributes[k, i1], attributes[k, i2]
        least = a0 if a0 < a1 else a1
        least = least if least < a2 else a2
        most = a0 if a0 > a1 else a1
        most = most if most > a2 else a2
        spread = spread if spread > most - least else most - least
    return spread * (root - 1.0) / (root + 1.0)


@inline
def _draw_triangle(shade, shade_on_screen, perspective, i0, i1, i2, screen_xy, screen_z,
                   screen_q, attributes, lighting, pixels, depths, width, height, span_lo,
                   span_hi, planes):
    """Cover and shade the triangle of vertices i0, i1, i2 with the span shader ``shade``
    in ``perspective``, or else with ``shade_on_screen`` (the two may be the same).

    screen_xy: (2, n) int64, screen_z: (n,) float64, screen_q: (n,) float64 (1 / w),
    attributes: (a, n) float64. span_lo, span_hi: (height,) int64 and planes:
    (>= 2 + a, 3) float64: scratch, written with the planes of the depth, of q = 1 / w and of
    each attribute times q (q taken as 1 on the screen).
    """
    x0, y0 = screen_xy[0, i0], screen_xy[1, i0]
    x1, y1 = screen_xy[0, i1], screen_xy[1, i1]
    x2, y2 = screen_xy[0, i2], screen_xy[1, i2]
    first, end = triangle_spans(x0, y0, x1, y1, x2, y2, width, height, span_lo, span_hi)
    # Plane equations in pixels, through the snapped positions the coverage used.
    e1x, e1y = (x1 - x0) / ONE, (y1 - y0) / ONE
    e2x, e2y = (x2 - x0) / ONE, (y2 - y0) / ONE
    inv_det = 1.0 / (e1x * e2y - e1y * e2x)
    fx, fy = x0 / ONE, y0 / ONE
    q0, q1, q2 = (screen_q[i0], screen_q[i1], screen_q[i2]) if perspective else (1.0, 1.0, 1.0)
    _set_plane(planes, 0, fx, fy, e1x, e1y, e2x, e2y, inv_det, screen_z[i0], screen_z[i1],
               screen_z[i2])
    _set_plane(planes, 1, fx, fy, e1x, e1y, e2x, e2y, inv_det, q0, q1, q2)
    for k in range(attributes.shape[0]):
        _set_plane(planes, 2 + k, fx, fy, e1x, e1y, e2x, e2y, inv_det, attributes[k, i0] * q0,
                   attributes[k, i1] * q1, attributes[k, i2] * q2)
    if perspective:
        for y in range(first, end):
            lo, hi = span_lo[y], span_hi[y]
            if lo < hi:
                shade(pixels, depths, np.uint64(y * width + lo), np.uint64(y * width + hi),
                      lo + 0.5, y + 0.5, planes, lighting)
    else:
        for y in range(first, end):
            lo, hi = span_lo[y], span_hi[y]
            if lo < hi:
                shade_on_screen(pixels, depths, np.uint64(y * width + lo),
                                np.uint64(y * width + hi), lo + 0.5, y + 0.5, planes, lighting)


@helper
def _visible(triangles, t, screen_xy, outcodes, width, height):
    """Whether triangle t may cover a pixel: inside every clipping plane but the far one
    (a triangle crossing one is left for `clip_triangles`), front-facing, on the screen.
    A helper, for LLVM to inline: inlined by numba (``@inline``) it made Phong's kernel half
    as slow again on small pictures, 2.0 to 2.9 ms for 100k triangles at 200x120."""
    i0, i1, i2 = triangles[t, 0], triangles[t, 1], triangles[t, 2]
    c0, c1, c2 = outcodes[i0], outcodes[i1], outcodes[i2]
    if c0 & c1 & c2 or (c0 | c1 | c2) & ~FAR:
        return False
    return may_cover(screen_xy[0, i0], screen_xy[1, i0], screen_xy[0, i1], screen_xy[1, i1],
                     screen_xy[0, i2], screen_xy[1, i2], width, height)


@inline
def _rasterize(shade, triangles, screen_xy, screen_z, screen_q, outcodes, attributes, lighting,
               pixels, depths, width, spans, planes):
    """The triangle loop of the rasterize kernels, for the span shader ``shade``, in
    perspective."""
    height = depths.shape[0] // width
    span_lo, span_hi = spans[0], spans[1]  # once: each view made in the loop costs a refcount
    for t in range(triangles.shape[0]):
        if _visible(triangles, t, screen_xy, outcodes, width, height):
            _draw_triangle(shade, shade, True, triangles[t, 0], triangles[t, 1],
                           triangles[t, 2], screen_xy, screen_z, screen_q, attributes, lighting,
                           pixels, depths, width, height, span_lo, span_hi, planes)


@ngjit
def rasterize_gouraud(triangles, screen_xy, screen_z, screen_q, outcodes, attributes, lighting,
                      pixels, depths, width, spans, planes):
    """Draw every front-facing triangle inside the clipping planes, nearest wins, with
    Gouraud shading.

    triangles: (m, 3) int32, counter-clockwise seen from the front.
    screen_xy: (2, n) int64, screen_z: (n,) float64, screen_q: (n,) float64, outcodes: (n,)
    uint8, from `project_vertices` (or `clip_triangles`). attributes: (a, n) float64, from
    `light_vertices` (Gouraud, a = 3) or `phong_vertices` (Phong, a = 9); any for overdraw.
    lighting: `Lighting` (used by Phong).
    pixels: (3 h w,) uint8 and depths: (h w,) float32, the frame buffers flattened,
    cleared to the background and depth 0; width: w. spans: (2, h) int64 and planes:
    (11, 3) float64 (at least 2 + a rows): scratch, passed in so that the kernel allocates
    nothing (numba's ``np.empty`` is a sizeable compile of its own on a cold start).

    Triangles with a vertex outside a clipping plane other than the far one are left for
    `clip_triangles`. A triangle shallow enough is shaded on the screen, with no division
    (see the module's docstring).
    """
    height = depths.shape[0] // width
    span_lo, span_hi = spans[0], spans[1]
    for t in range(triangles.shape[0]):
        if not _visible(triangles, t, screen_xy, outcodes, width, height):
            continue
        i0, i1, i2 = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        deep = _drift(screen_q[i0], screen_q[i1], screen_q[i2], attributes, i0, i1, i2) \
            >= AFFINE_BELOW
        _draw_triangle(shade_gouraud, shade_gouraud_on_screen, deep, i0, i1, i2, screen_xy,
                       screen_z, screen_q, attributes, lighting, pixels, depths, width, height,
                       span_lo, span_hi, planes)


@ngjit
def rasterize_phong(triangles, screen_xy, screen_z, screen_q, outcodes, attributes, lighting,
                    pixels, depths, width, spans, planes):
    """`rasterize_gouraud` with Phong shading, every triangle in perspective."""
    _rasterize(shade_phong, triangles, screen_xy, screen_z, screen_q, outcodes, attributes,
               lighting, pixels, depths, width, spans, planes)


@ngjit
def rasterize_overdraw(triangles, screen_xy, screen_z, screen_q, outcodes, attributes, lighting,
                       pixels, depths, width, spans, planes):
    """`rasterize_gouraud` counting the triangles that cover each pixel (`count_overdraw`)."""
    _rasterize(count_overdraw, triangles, screen_xy, screen_z, screen_q, outcodes, attributes,
               lighting, pixels, depths, width, spans, planes)
