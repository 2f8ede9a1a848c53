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
from biceps.engine.raster.coverage import HALF, ONE, SUBPIXEL_BITS, band_spans, may_cover
from biceps.engine.raster.shading import (count_overdraw, light_phong,
                                          shade_gouraud, shade_gouraud_on_screen, shade_phong)

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
def _set_planes(i0, i1, i2, perspective, screen_xy, screen_z, screen_q, attributes, planes):
    """The planes of the triangle of vertices i0, i1, i2, in pixels, through the snapped
    positions the coverage used.

    screen_xy: (2, n) int64, screen_z: (n,) float64, screen_q: (n,) float64 (1 / w),
    attributes: (a, n) float64. planes: (>= 2 + a, 3) float64, scratch, written with the
    planes of the depth, of q = 1 / w and of each attribute times q (q taken as 1 unless
    ``perspective``).
    """
    x0, y0 = screen_xy[0, i0], screen_xy[1, i0]
    e1x, e1y = (screen_xy[0, i1] - x0) / ONE, (screen_xy[1, i1] - y0) / ONE
    e2x, e2y = (screen_xy[0, i2] - x0) / ONE, (screen_xy[1, i2] - y0) / ONE
    inv_det = 1.0 / (e1x * e2y - e1y * e2x)
    fx, fy = x0 / ONE, y0 / ONE
    q0, q1, q2 = (screen_q[i0], screen_q[i1], screen_q[i2]) if perspective else (1.0, 1.0, 1.0)
    _set_plane(planes, 0, fx, fy, e1x, e1y, e2x, e2y, inv_det, screen_z[i0], screen_z[i1],
               screen_z[i2])
    _set_plane(planes, 1, fx, fy, e1x, e1y, e2x, e2y, inv_det, q0, q1, q2)
    for k in range(attributes.shape[0]):
        _set_plane(planes, 2 + k, fx, fy, e1x, e1y, e2x, e2y, inv_det, attributes[k, i0] * q0,
                   attributes[k, i1] * q1, attributes[k, i2] * q2)


@inline
def _draw_triangle(shade, shade_on_screen, perspective, i0, i1, i2, screen_xy, screen_z,
                   screen_q, attributes, lighting, pixels, depths, width, first, end,
                   span_lo, span_hi, planes, hits, shaded):
    """Shade the triangle's spans on the rows ``first <= y < end`` (`coverage.band_spans`)
    with the span shader ``shade`` in ``perspective``, or else with ``shade_on_screen`` (the
    two may be the same); hits, shaded: their scratch, unused by these."""
    _set_planes(i0, i1, i2, perspective, screen_xy, screen_z, screen_q, attributes, planes)
    if perspective:
        for y in range(first, end):
            lo, hi = span_lo[y], span_hi[y]
            if lo < hi:
                shade(pixels, depths, np.uint64(y * width + lo), np.uint64(y * width + hi),
                      lo + 0.5, y + 0.5, planes, lighting, hits, shaded, 0)
    else:
        for y in range(first, end):
            lo, hi = span_lo[y], span_hi[y]
            if lo < hi:
                shade_on_screen(pixels, depths, np.uint64(y * width + lo),
                                np.uint64(y * width + hi), lo + 0.5, y + 0.5, planes, lighting,
                                hits, shaded, 0)


@inline
def _draw_triangle_lit(shade, light, i0, i1, i2, screen_xy, screen_z, screen_q, attributes,
                       lighting, pixels, depths, width, first, end, span_lo, span_hi, planes,
                       hits, shaded):
    """`_draw_triangle` in perspective for a span shader that lists the pixels it passes
    in hits and shaded, and ``light``, which lights them all at once (Phong's, see
    ``engine/raster/shading.py``): when the list could overflow, and at the end. Apart from
    `_draw_triangle`, as the calls of even a ``light`` that does nothing made Gouraud's
    loop half as slow again."""
    _set_planes(i0, i1, i2, True, screen_xy, screen_z, screen_q, attributes, planes)
    # Where ``light`` steps from: the centre of the pixel nearest the first vertex on the
    # screen, the same in every band (so the picture is too) and never far from a pixel.
    column = screen_xy[0, i0] >> SUBPIXEL_BITS
    row = screen_xy[1, i0] >> SUBPIXEL_BITS
    height = depths.shape[0] // width
    column = column if column > 0 else 0
    row = row if row > 0 else 0
    origin_x = (column if column < width else width - 1) + 0.5
    origin_y = (row if row < height else height - 1) + 0.5
    count = 0
    for y in range(first, end):
        lo, hi = span_lo[y], span_hi[y]
        if lo < hi:
            if count + (hi - lo) > hits.shape[0]:
                light(pixels, count, origin_x, origin_y, planes, lighting, hits, shaded)
                count = 0
            count = shade(pixels, depths, np.uint64(y * width + lo), np.uint64(y * width + hi),
                          lo + 0.5, y + 0.5, planes, lighting, hits, shaded, count)
    light(pixels, count, origin_x, origin_y, planes, lighting, hits, shaded)


@helper
def _visible(triangles, t, screen_xy, outcodes, width, height):
    """Whether triangle t may cover a pixel: inside every clipping plane but the far one
    (a triangle crossing one is left for `clip_triangles`), front-facing, on the screen.
    A helper, for LLVM to inline: inlined by numba (``@inline``) it made Phong's kernel
    slower on small pictures."""
    i0, i1, i2 = triangles[t, 0], triangles[t, 1], triangles[t, 2]
    c0, c1, c2 = outcodes[i0], outcodes[i1], outcodes[i2]
    if c0 & c1 & c2 or (c0 | c1 | c2) & ~FAR:
        return False
    return may_cover(screen_xy[0, i0], screen_xy[1, i0], screen_xy[0, i1], screen_xy[1, i1],
                     screen_xy[0, i2], screen_xy[1, i2], width, height)


@helper
def _in_band(screen_xy, i0, i1, i2, band_start, band_end):
    """Whether the triangle's bounding box holds a pixel centre on the rows
    ``band_start <= y < band_end`` (as `coverage._pixel_range` counts them)."""
    a, b, c = screen_xy[1, i0], screen_xy[1, i1], screen_xy[1, i2]
    low = a if a < b else b
    low = low if low < c else c
    high = a if a > b else b
    high = high if high > c else c
    return -((HALF - low) >> SUBPIXEL_BITS) < band_end and (high - HALF) >> SUBPIXEL_BITS \
        >= band_start


@inline
def _rasterize(shade, on_screen, light, triangles, screen_xy, screen_z, screen_q, outcodes,
               attributes, lighting, pixels, depths, width, band_start, band_end, spans, planes,
               hits, shaded):
    """The triangle loop of the rasterize kernels, for the span shader ``shade`` in
    perspective; ``on_screen``, if it is not None, its shader for a triangle shallow enough
    to shade on the screen (`_drift`); ``light``, if it is not None, the lighting of the
    pixels ``shade`` lists (see `_draw_triangle_lit`). numba prunes the branches of a None."""
    # Views taken once: each made in the loop costs a refcount.
    span_lo, span_hi, drawn_lo, drawn_hi = spans[0], spans[1], spans[2], spans[3]
    height = depths.shape[0] // width
    for t in range(triangles.shape[0]):
        i0, i1, i2 = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        if not (_in_band(screen_xy, i0, i1, i2, band_start, band_end)
                and _visible(triangles, t, screen_xy, outcodes, width, height)):
            continue
        first, end = band_spans(screen_xy[0, i0], screen_xy[1, i0], screen_xy[0, i1],
                                screen_xy[1, i1], screen_xy[0, i2], screen_xy[1, i2], width,
                                band_start, band_end, span_lo, span_hi)
        if first >= end:
            continue  # no pixel centre: most triangles of a fine mesh on a small picture
        for y in range(first, end):  # (what the next frame clears: see clear_drawn)
            lo, hi = span_lo[y], span_hi[y]
            if lo < hi:
                drawn_lo[y] = lo if lo < drawn_lo[y] else drawn_lo[y]
                drawn_hi[y] = hi if hi > drawn_hi[y] else drawn_hi[y]
        if light is not None:
            _draw_triangle_lit(shade, light, i0, i1, i2, screen_xy, screen_z, screen_q,
                               attributes, lighting, pixels, depths, width, first, end,
                               span_lo, span_hi, planes, hits, shaded)
        elif on_screen is None:
            _draw_triangle(shade, shade, True, i0, i1, i2, screen_xy, screen_z, screen_q,
                           attributes, lighting, pixels, depths, width, first, end,
                           span_lo, span_hi, planes, hits, shaded)
        else:
            deep = _drift(screen_q[i0], screen_q[i1], screen_q[i2], attributes, i0, i1, i2) \
                >= AFFINE_BELOW
            _draw_triangle(shade, on_screen, deep, i0, i1, i2, screen_xy, screen_z, screen_q,
                           attributes, lighting, pixels, depths, width, first, end,
                           span_lo, span_hi, planes, hits, shaded)


@ngjit
def rasterize_gouraud(triangles, screen_xy, screen_z, screen_q, outcodes, attributes,
                      lighting, pixels, depths, width, band_start, band_end, spans, planes, hits,
                      shaded):
    """Draw every front-facing triangle inside the clipping planes on the rows
    ``band_start <= y < band_end``, nearest wins, with Gouraud shading.

    triangles: (m, 3) int32, counter-clockwise seen from the front.
    screen_xy: (2, n) int64, screen_z: (n,) float64, screen_q: (n,) float64, outcodes: (n,)
    uint8, from `project_vertices` (or `clip_triangles`). attributes: (a, n) float64, from
    `light_vertices` (Gouraud, a = 3) or `phong_vertices` (Phong, a = 9); any for overdraw.
    lighting: `Lighting` (used by Phong).
    pixels: (3 h w,) uint8 and depths: (h w,) float32, the frame buffers flattened,
    cleared to the background and depth 0; width: w. Scratch, passed in so that the kernel
    allocates nothing (numba's ``np.empty`` is a sizeable compile of its own on a cold
    start), one set per band drawn at once: spans: (4, h) int64, planes: (11, 3) float64
    (at least 2 + a rows), hits: (c,) int64 and shaded: (8, c) float32, c >= w. The spans'
    last two rows are not scratch: on each row the kernel widens ``[spans[2], spans[3])``
    to take in every span it draws (for `clear_drawn`).

    Only the rows of the band are written, so bands drawn at once by several threads never
    share a pixel; each pixel sees the same triangles in the same order whatever the bands,
    so the picture is the same. Triangles with a vertex outside a clipping plane other than
    the far one are left for `clip_triangles`. A triangle shallow enough is shaded on the
    screen, with no division (see the module's docstring).
    """
    _rasterize(shade_gouraud, shade_gouraud_on_screen, None, triangles, screen_xy, screen_z,
               screen_q, outcodes, attributes, lighting, pixels, depths, width, band_start,
               band_end, spans, planes, hits, shaded)


@ngjit
def rasterize_phong(triangles, screen_xy, screen_z, screen_q, outcodes, attributes,
                    lighting, pixels, depths, width, band_start, band_end, spans, planes, hits,
                    shaded):
    """`rasterize_gouraud` with Phong shading, every triangle in perspective."""
    _rasterize(shade_phong, None, light_phong, triangles, screen_xy, screen_z, screen_q, outcodes,
               attributes, lighting, pixels, depths, width, band_start, band_end,
               spans, planes, hits, shaded)


@ngjit
def rasterize_overdraw(triangles, screen_xy, screen_z, screen_q, outcodes, attributes,
                       lighting, pixels, depths, width, band_start, band_end, spans, planes,
                       hits, shaded):
    """`rasterize_gouraud` counting the triangles that cover each pixel (`count_overdraw`)."""
    _rasterize(count_overdraw, None, None, triangles, screen_xy, screen_z, screen_q, outcodes,
               attributes, lighting, pixels, depths, width, band_start, band_end,
               spans, planes, hits, shaded)


@ngjit
def clear_drawn(pixels, depths, width, band_start, band_end, spans, red, green, blue):
    """Clear what the last frame drew on the rows ``band_start <= y < band_end``: on each
    row, the columns ``[spans[2, y], spans[3, y])``, which the rasterize kernels widened to
    take in every span they drew, to the background (``red``, ``green``, ``blue``: uint8)
    and depth 0; then leave them empty for this frame's spans. The rest of the frame is as
    the frame before last left it, cleared, if the buffers and the background are the same
    (the caller's to ensure: see ``engine/render.py``).

    A close-up of the arm covers about 40 % of a frame, and clearing all of a 4K frame took
    2.2 ms of its 5.5 (as fast as memory takes 58 MB); the arm framed whole covers a few
    percent. The background is three scalars, not a row to copy: the stores of constants
    vectorise, a byte-by-byte copy (which LLVM cannot prove does not overlap) ran at a
    sixth of the speed.
    """
    for y in range(band_start, band_end):
        lo, hi = spans[2, y], spans[3, y]
        if lo < hi:
            start = np.uint64(y * width + lo)
            for k in range(hi - lo):
                at = np.uint64(3) * (start + np.uint64(k))
                pixels[at] = red
                pixels[at + np.uint64(1)] = green
                pixels[at + np.uint64(2)] = blue
            for k in range(hi - lo):
                depths[start + np.uint64(k)] = 0.0
        spans[2, y], spans[3, y] = width, 0
