"""Culling: the triangles that may cover a pixel, listed once per frame for every band.

A frame is drawn in horizontal bands, each by its own thread (``engine/raster/bands.py``);
the tests that throw out most triangles (outside a clipping plane, back-facing, smaller than
a pixel: most of a large mesh in a small picture) are done here once, over a share of the
triangles per thread, rather than again by every band.
"""

from biceps.engine.jit import helper, ngjit
from biceps.engine.raster.clipping import FAR
from biceps.engine.raster.coverage import may_cover


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


@ngjit
def cull_triangles(triangles, screen_xy, outcodes, width, height, chunks, chunk, visible):
    """List the triangles of one chunk that may cover a pixel, in their order.

    triangles: (m, 3) int32; screen_xy: (2, n) int64 and outcodes: (n,) uint8 from
    `project_vertices`; width, height: the screen. chunks: (k, 2) int64, row ``chunk`` the
    triangles ``start <= t < stop`` of this chunk, rewritten as (start, count): the count
    of triangles written to visible: (m,) int32 from ``start`` on.
    """
    start, stop = chunks[chunk, 0], chunks[chunk, 1]
    count = 0
    for t in range(start, stop):
        if _visible(triangles, t, screen_xy, outcodes, width, height):
            visible[start + count] = t
            count += 1
    chunks[chunk, 1] = count
