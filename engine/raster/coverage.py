"""Coverage: the pixels a triangle covers, exactly, from vertices in fixed point.

Coverage is exact, so a closed mesh shows no cracks and no pixel drawn twice along a shared
edge. Each vertex is projected and snapped to 1/256 pixel once (D3D10's 8 bits of subpixel
precision), and every triangle sharing it reads that same integer position. A pixel is
covered when its centre is inside all three integer edge functions (Pineda, "A Parallel
Algorithm for Polygon Rasterization", 1988), or on an edge that is top or left (the
top-left rule of the D3D10 rasterization rules). Rather than test every pixel of the
bounding box, each edge is walked down the rows as an exact floor division, stepped with a
remainder (Bresenham's idea, as in Hecker's "Perspective Texture Mapping, Part II", 1995),
which gives each row's span with no division per row; a triangle a few pixels wide, as
most of a fine mesh's are on a small picture, has its few centres tested one by one
instead (`NARROW`), which needs no division at all.
"""

import numpy as np

from biceps.engine.jit import helper, inline

SUBPIXEL_BITS = 8
ONE = 1 << SUBPIXEL_BITS  # one pixel in fixed point
HALF = ONE >> 1  # the pixel centre's offset

NARROW = 4
"""Columns below which a triangle's spans come from testing each pixel centre of its
bounding box against the three edge functions instead of from walking the edges: for the
tiny triangles of a fine mesh that saves the walkers' six 64-bit divisions, most of their
setup. Both give the same spans (the same integer inequalities)."""


@helper
def _pixel_range(a, b, c, size):
    """The pixels along one axis, clipped to ``0 .. size - 1``, whose centres lie between
    the least and the greatest of three fixed-point coordinates (as in `triangle_spans`).

    The centre of pixel p is at ``p ONE + HALF``, so the pixels whose centres lie in
    [low, high] run from ``ceil((low - HALF) / ONE)`` to ``floor((high - HALF) / ONE)``.
    Conditional expressions rather than the builtin ``min`` and ``max``, which numba
    compiles as functions of their own for each caller, each one more compile on a cold
    start."""
    low = a if a < b else b
    low = low if low < c else c
    high = a if a > b else b
    high = high if high > c else c
    first = -((HALF - low) >> SUBPIXEL_BITS)
    last = (high - HALF) >> SUBPIXEL_BITS
    return (first if first > 0 else 0), (last if last < size - 1 else size - 1)


@helper
def _pixel_box(x0, y0, x1, y1, x2, y2, width, height):
    """The pixels whose centres lie in the bounding box of a triangle (fixed point, as in
    `triangle_spans`), clipped to the screen: rows first to last, columns left to right."""
    first, last = _pixel_range(y0, y1, y2, height)
    left, right = _pixel_range(x0, x1, x2, width)
    return first, last, left, right


@helper
def _edge_value(ax, ay, bx, by, px, py):
    """The edge a -> b's function at the centre of pixel (px, py) with the top-left rule's
    bias (see `_edge_walker`): >= 0 where the edge admits the pixel."""
    a = by - ay
    b = ax - bx
    bias = 0 if a > 0 or (a == 0 and b > 0) else -1
    return a * (px * ONE + HALF - ax) + b * (py * ONE + HALF - ay) + bias


@helper
def _test_centres(x0, y0, x1, y1, x2, y2, first, last, left, right, span_lo, span_hi):
    """The spans of a triangle (as in `band_spans`) on the rows first to last, from testing
    each pixel centre of the columns left to right: whether it covers any. A helper, not
    inlined by numba, which added a second to the first run's compilation."""
    covered = False
    for y in range(first, last + 1):
        lo, hi = right + 1, left
        for x in range(left, right + 1):
            inside = (_edge_value(x0, y0, x1, y1, x, y) >= 0) \
                & (_edge_value(x1, y1, x2, y2, x, y) >= 0) \
                & (_edge_value(x2, y2, x0, y0, x, y) >= 0)
            lo = x if inside & (x < lo) else lo
            hi = x + 1 if inside else hi
        span_lo[y], span_hi[y] = lo, (hi if hi > lo else lo)
        covered |= hi > lo
    return covered


@helper
def _edge_walker(ax, ay, bx, by, row):
    """The edge a -> b as a bound on the covered pixels' x, row by row.

    Its edge function, positive inside, at the centre of pixel (px, py), is
    ``E = A (px ONE + HALF - ax) + B (py ONE + HALF - ay)`` with ``A = by - ay``,
    ``B = ax - bx``. The top-left rule keeps a centre exactly on the edge only if the edge
    is left (A > 0: the inside is towards +x) or top (A = 0, B > 0: horizontal, inside
    below it), so other edges get a bias of -1: ``E - 1 >= 0`` is ``E > 0`` in integers.

    Write ``E + bias = A ONE px + R(py)``. On a row, a left edge (A > 0) admits
    ``px >= -floor(R / D)`` and a right edge (A < 0) ``px <= floor(R / D)`` with
    ``D = |A| ONE``; a horizontal edge admits the whole row if ``R >= 0``, none otherwise
    (``D = 1`` then, so ``floor(R / D) = R``). From one row to the next R grows by B ONE.

    Returns (A, D, q, r, dq, dr): ``q, r = divmod(R, D)`` (floored) on the first ``row``
    and ``dq, dr = divmod(B ONE, D)``, for `_edge_step`.
    """
    a = by - ay
    b = ax - bx
    start = _edge_value(ax, ay, bx, by, 0, row)
    d = a * ONE if a > 0 else (-a * ONE if a < 0 else np.int64(1))
    q, dq = start // d, (b * ONE) // d  # floored, as numba follows Python
    return a, d, q, start - q * d, dq, b * ONE - dq * d


@helper
def _edge_step(d, q, r, dq, dr):
    """The walker's (q, r) on the next row: R + B ONE = (q + dq) D + (r + dr), carried."""
    r += dr
    carry = np.int64(r >= d)  # arithmetic, not a branch: the carry is unpredictable
    return q + dq + carry, r - carry * d


@helper
def _edge_clamp(a, q, lo, hi):
    """Narrow the span [lo, hi] (inclusive) by an edge's bound on this row."""
    if a > 0:
        return (lo if lo > -q else -q), hi
    if a < 0:
        return lo, (hi if hi < q else q)
    return (lo, hi) if q >= 0 else (lo, lo - 1)


@inline
def triangle_spans(x0, y0, x1, y1, x2, y2, width, height, span_lo, span_hi):
    """The pixels a triangle covers by the top-left rule, row by row.

    x0 ... y2: int64 vertex positions in 1/256 pixel, wound so that the edge functions are
    positive inside: the signed area ``(y1 - y0)(x2 - x0) - (x1 - x0)(y2 - y0)`` is positive
    (counter-clockwise as the screen shows it, y down, as a front face is).
    width, height: the screen. span_lo, span_hi: (height,) int64, written for the rows
    returned: row y covers the pixels ``span_lo[y] <= x < span_hi[y]`` (maybe none).

    Returns (first, end): the rows ``first <= y < end`` that may hold covered pixels
    (``first >= end`` if none), clipped to the screen.
    """
    return band_spans(x0, y0, x1, y1, x2, y2, width, 0, height, span_lo, span_hi)


@inline
def band_spans(x0, y0, x1, y1, x2, y2, width, band_start, band_end, span_lo, span_hi):
    """`triangle_spans` within the rows ``band_start <= y < band_end`` of the screen: the
    same spans on those rows, whichever band they are asked for in, as each edge walker
    starts on the band's first row with an exact division (so bands drawn apart make the
    picture drawn whole, pixel for pixel)."""
    first, last, left, right = _pixel_box(x0, y0, x1, y1, x2, y2, width, band_end)
    first = first if first > band_start else band_start
    if first > last or left > right:
        return first, first
    if right - left < NARROW:
        covered = _test_centres(x0, y0, x1, y1, x2, y2, first, last, left, right, span_lo,
                                span_hi)
        return (first, last + 1) if covered else (first, first)
    covered = False
    a0, d0, q0, r0, dq0, dr0 = _edge_walker(x0, y0, x1, y1, first)
    a1, d1, q1, r1, dq1, dr1 = _edge_walker(x1, y1, x2, y2, first)
    a2, d2, q2, r2, dq2, dr2 = _edge_walker(x2, y2, x0, y0, first)
    for y in range(first, last + 1):
        lo, hi = _edge_clamp(a0, q0, left, right)
        lo, hi = _edge_clamp(a1, q1, lo, hi)
        lo, hi = _edge_clamp(a2, q2, lo, hi)
        span_lo[y], span_hi[y] = lo, (hi + 1 if hi >= lo else lo)
        covered |= hi >= lo
        q0, r0 = _edge_step(d0, q0, r0, dq0, dr0)
        q1, r1 = _edge_step(d1, q1, r1, dq1, dr1)
        q2, r2 = _edge_step(d2, q2, r2, dq2, dr2)
    return (first, last + 1) if covered else (first, first)


@inline
def may_cover(x0, y0, x1, y1, x2, y2, width, height):
    """Whether a triangle (fixed point, as in `triangle_spans`) is front-facing and its
    bounding box holds a pixel centre on the screen: the cheap tests that throw out the
    back half of a closed mesh, and the many triangles smaller than a pixel, before setup.
    Inlined: compiled on its own, it had numba compile `_pixel_box` a second time for it on
    every cold start."""
    if (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0) <= 0:
        return False  # back-facing or degenerate
    first, last, left, right = _pixel_box(x0, y0, x1, y1, x2, y2, width, height)
    return first <= last and left <= right
