"""The draw loop: each triangle rejected, culled, covered and shaded.

Attributes (depth, colour, normal, position) are interpolated linearly in screen space from
plane equations through the three snapped vertices. Depth (``z / w``) is linear in screen
space, so that is exact. For the rest it is Gouraud's own choice (1971) and it saves a
division per pixel: the meshes here are finely tessellated (a triangle covers tens of
pixels even in a full-HD frame), where the error of skipping the perspective correction is
far below what 8-bit colour can show.
"""

import numpy as np

from biceps.engine.jit import helper, inline, ngjit
from biceps.engine.raster.clipping import FAR
from biceps.engine.raster.coverage import ONE, may_cover, triangle_spans
from biceps.engine.raster.shading import count_overdraw, shade_gouraud, shade_phong


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


@inline
def _draw_triangle(shade, i0, i1, i2, screen_xy, screen_z, attributes, lighting, pixels, depths,
                   width, height, span_lo, span_hi, planes):
    """Cover and shade the triangle of vertices i0, i1, i2 with the span shader ``shade``.

    screen_xy: (2, n) int64, screen_z: (n,) float64, attributes: (a, n) float64.
    span_lo, span_hi: (height,) int64 and planes: (>= 1 + a, 3) float64: scratch.
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
    for k in range(1 + attributes.shape[0]):
        if k == 0:
            v0, v1, v2 = screen_z[i0], screen_z[i1], screen_z[i2]
        else:
            v0, v1, v2 = attributes[k - 1, i0], attributes[k - 1, i1], attributes[k - 1, i2]
        _set_plane(planes, k, fx, fy, e1x, e1y, e2x, e2y, inv_det, v0, v1, v2)
    for y in range(first, end):
        lo, hi = span_lo[y], span_hi[y]
        if lo < hi:
            shade(pixels, depths, np.uint64(y * width + lo), np.uint64(y * width + hi),
                  lo + 0.5, y + 0.5, planes, lighting)


@inline
def _rasterize(shade, triangles, screen_xy, screen_z, outcodes, attributes, lighting, pixels,
               depths, width, spans, planes):
    """The triangle loop of the rasterize kernels, for the span shader ``shade``."""
    height = depths.shape[0] // width
    span_lo, span_hi = spans[0], spans[1]
    for t in range(triangles.shape[0]):
        i0, i1, i2 = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        c0, c1, c2 = outcodes[i0], outcodes[i1], outcodes[i2]
        if c0 & c1 & c2 or (c0 | c1 | c2) & ~FAR:
            continue  # wholly outside a plane; or crossing one, left for clip_triangles
        if may_cover(screen_xy[0, i0], screen_xy[1, i0], screen_xy[0, i1], screen_xy[1, i1],
                      screen_xy[0, i2], screen_xy[1, i2], width, height):
            _draw_triangle(shade, i0, i1, i2, screen_xy, screen_z, attributes, lighting, pixels,
                           depths, width, height, span_lo, span_hi, planes)


@ngjit
def rasterize_gouraud(triangles, screen_xy, screen_z, outcodes, attributes, lighting, pixels,
                      depths, width, spans, planes):
    """Draw every front-facing triangle inside the clipping planes, nearest wins, with
    Gouraud shading.

    triangles: (m, 3) int32, counter-clockwise seen from the front.
    screen_xy: (2, n) int64, screen_z: (n,) float64, outcodes: (n,) uint8, from
    `project_vertices` (or `clip_triangles`). attributes: (a, n) float64, from
    `light_vertices` (Gouraud, a = 3) or `phong_vertices` (Phong, a = 9); any for overdraw.
    lighting: `Lighting` (used by Phong).
    pixels: (3 h w,) uint8 and depths: (h w,) float32, the frame buffers flattened,
    cleared to the background and depth 0; width: w. spans: (2, h) int64 and planes:
    (10, 3) float64 (at least 1 + a rows): scratch, passed in so that the kernel allocates
    nothing (numba's ``np.empty`` is a sizeable compile of its own on a cold start).

    Triangles with a vertex outside a clipping plane other than the far one are left for
    `clip_triangles`.
    """
    _rasterize(shade_gouraud, triangles, screen_xy, screen_z, outcodes, attributes, lighting,
               pixels, depths, width, spans, planes)


@ngjit
def rasterize_phong(triangles, screen_xy, screen_z, outcodes, attributes, lighting, pixels,
                    depths, width, spans, planes):
    """`rasterize_gouraud` with Phong shading."""
    _rasterize(shade_phong, triangles, screen_xy, screen_z, outcodes, attributes, lighting,
               pixels, depths, width, spans, planes)


@ngjit
def rasterize_overdraw(triangles, screen_xy, screen_z, outcodes, attributes, lighting, pixels,
                       depths, width, spans, planes):
    """`rasterize_gouraud` counting the triangles that cover each pixel (`count_overdraw`)."""
    _rasterize(count_overdraw, triangles, screen_xy, screen_z, outcodes, attributes, lighting,
               pixels, depths, width, spans, planes)
