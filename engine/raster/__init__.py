"""The software rasterizer: numba kernels that take arrays and scalars, write into output
buffers and return nothing. ``engine/render.py`` calls them once each per frame:

1. ``transform_vertices``: model to world space, positions and (inverse-transpose) normals.
2. ``project_vertices``: world to clip space; an outcode per vertex (the clipping planes it
   is outside); for vertices inside them all, the screen position snapped to fixed point.
3. ``light_vertices`` (Gouraud) or ``phong_vertices`` (Phong): the per-vertex attributes
   the rasterizer interpolates.
4. ``rasterize_gouraud``, ``rasterize_phong`` or ``rasterize_overdraw``, into buffers
   cleared beforehand (``engine.render.clear``): per triangle, reject, cull, cover, shade.
5. Only when some vertex is outside a clipping plane: ``clip_triangles`` cuts the triangles
   that cross one into a small mesh already in screen space, drawn by the same kernel.
6. ``downsample``: average supersampled pixels.

Spaces are those of ``engine/transforms.py``: OpenGL clip space, then screen space with
``x`` right and ``y`` down in pixels, pixel ``(x, y)`` centred at ``(x + 0.5, y + 0.5)``,
depth reversed: 1 on the near plane, 0 on the far one, larger is nearer. Float32 is densest
near 0, and the usual depth crowds near 1 (it goes as 1 - near / distance), so the reversed
one keeps float32's precision at any distance (Reed, "Depth Precision Visualized", 2015).

Layouts. Per-vertex arrays are component-major, ``(3, n)`` rather than the mesh's
``(n, 3)``: with every matrix read into registers first, LLVM then vectorises the vertex
loops (AVX), several times faster than loops over rows. The frame buffers are passed
flattened, ``pixels: (3 h w,) uint8`` and ``depths: (h w,) float32`` (views of the
``(h, w, 3)`` and ``(h, w)`` buffers), so that the inner loops index them with one unsigned
offset: numba adds a negative-index fix-up to every signed index, which costs as much as
the rest of a pixel.

Coverage is exact, so a closed mesh shows no cracks and no pixel drawn twice along a shared
edge. Each vertex is projected and snapped to 1/256 pixel once (D3D10's 8 bits of subpixel
precision), and every triangle sharing it reads that same integer position. A pixel is
covered when its centre is inside all three integer edge functions (Pineda, "A Parallel
Algorithm for Polygon Rasterization", 1988), or on an edge that is top or left (the
top-left rule of the D3D10 rasterization rules). Rather than test every pixel of the
bounding box, each edge is walked down the rows as an exact floor division, stepped with a
remainder (Bresenham's idea, as in Hecker's "Perspective Texture Mapping, Part II", 1995),
which gives each row's span with no division per row.

Attributes (depth, colour, normal, position) are interpolated linearly in screen space from
plane equations through the three snapped vertices. Depth (``z / w``) is linear in screen
space, so that is exact. For the rest it is Gouraud's own choice (1971) and it saves a
division per pixel: the meshes here are finely tessellated (a triangle covers tens of
pixels even in a full-HD frame), where the error of skipping the perspective correction is
far below what 8-bit colour can show.

Triangles crossing the near plane are clipped in clip space (Sutherland-Hodgman), and so
are triangles reaching beyond a wide guard band around the screen, which keeps the fixed
point coordinates small enough that the edge functions cannot overflow int64.
"""

import math

import numpy as np

from biceps.engine.jit import helper, inline, ngjit

SUBPIXEL_BITS = 8
ONE = 1 << SUBPIXEL_BITS  # one pixel in fixed point
HALF = ONE >> 1  # the pixel centre's offset

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

LIGHTING = ("light x", "light y", "light z", "eye x", "eye y", "eye z",
            "ambient", "diffuse", "specular", "shininess", "highlight threshold")
"""The layout of the ``lighting: (11,) float64`` argument of the rasterize kernels. Below
the highlight threshold, ``(1 / (2 255 specular)) ^ (1 / shininess)``, ``n.h`` gives a
highlight under half a colour level, so Phong skips its ``pow``."""


# The vertex stage. Per-vertex buffers are component-major, (3, n) rather than the mesh's
# (n, 3), and every matrix is read into registers before its loop: then LLVM vectorises
# the loops (AVX), about five times faster than the same loops over rows.


@ngjit
def transform_vertices(vertices, normals, model, normal_matrix, world, world_normals):
    """Model space to world space.

    vertices, normals: (3, n) float64. model: (4, 4) float64 acting on column vectors.
    normal_matrix: (3, 3) float64, the inverse transpose of ``model[:3, :3]``.
    Writes world: (3, n) float64 and world_normals: (3, n) float64, renormalised.
    """
    # The vertex kernels call no helpers: each compiled function costs tens of milliseconds
    # of numba's time the first time it runs (see engine/jit.py).
    m00, m01, m02, m03 = model[0, 0], model[0, 1], model[0, 2], model[0, 3]
    m10, m11, m12, m13 = model[1, 0], model[1, 1], model[1, 2], model[1, 3]
    m20, m21, m22, m23 = model[2, 0], model[2, 1], model[2, 2], model[2, 3]
    for i in range(vertices.shape[1]):
        x, y, z = vertices[0, i], vertices[1, i], vertices[2, i]
        world[0, i] = m00 * x + m01 * y + m02 * z + m03
        world[1, i] = m10 * x + m11 * y + m12 * z + m13
        world[2, i] = m20 * x + m21 * y + m22 * z + m23
    n00, n01, n02 = normal_matrix[0, 0], normal_matrix[0, 1], normal_matrix[0, 2]
    n10, n11, n12 = normal_matrix[1, 0], normal_matrix[1, 1], normal_matrix[1, 2]
    n20, n21, n22 = normal_matrix[2, 0], normal_matrix[2, 1], normal_matrix[2, 2]
    for i in range(normals.shape[1]):
        x, y, z = normals[0, i], normals[1, i], normals[2, i]
        nx = n00 * x + n01 * y + n02 * z
        ny = n10 * x + n11 * y + n12 * z
        nz = n20 * x + n21 * y + n22 * z
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        scale = 1.0 / length if length > 0.0 else 0.0
        world_normals[0, i] = nx * scale
        world_normals[1, i] = ny * scale
        world_normals[2, i] = nz * scale


@helper
def _guard(size):
    """How far out (in units of w) the guard band's planes are, for a screen ``size`` wide."""
    return 1.0 + 2.0 * GUARD_BAND / size


@helper
def _to_screen(x, y, z, w, width, height):
    """Clip space to screen space: (X, Y) int64 in 1/256 pixel and the reversed depth
    ``(1 - z / w) / 2`` (float64, 1 on the near plane, 0 on the far one). The same
    arithmetic as `project_vertices`, for the vertices that clipping makes."""
    inv_w = 1.0 / w
    sx = (x * inv_w + 1.0) * (0.5 * width)
    sy = (1.0 - y * inv_w) * (0.5 * height)
    return (np.int64(math.floor(sx * ONE + 0.5)), np.int64(math.floor(sy * ONE + 0.5)),
            (w - z) * inv_w * 0.5)


@ngjit
def project_vertices(world, view_projection, width, height, clip, screen_xy, screen_z, outcodes):
    """World space to clip space and, where inside the clip planes, to screen space.

    world: (3, n) float64. view_projection: (4, 4) float64. width, height: the screen in pixels.
    Writes clip: (4, n) float64; outcodes: (n,) uint8 (bits NEAR ... INVALID); and for the
    vertices inside every clipping plane (outcode 0 or FAR), screen_xy: (2, n) int64 in
    1/256 pixel and screen_z: (n,) float64 depth (elsewhere 0).

    The outcode is branch-free apart from selects, so that the loop vectorises; INVALID
    if a coordinate is not finite (or so large that the sum of magnitudes overflows). The
    screen position is `_to_screen`'s, written out here (no helpers, as above).
    """
    gx = 1.0 + 2.0 * GUARD_BAND / width  # the guard band's planes, in units of w
    gy = 1.0 + 2.0 * GUARD_BAND / height
    half_w, half_h = 0.5 * width, 0.5 * height
    vp = view_projection
    m00, m01, m02, m03 = vp[0, 0], vp[0, 1], vp[0, 2], vp[0, 3]
    m10, m11, m12, m13 = vp[1, 0], vp[1, 1], vp[1, 2], vp[1, 3]
    m20, m21, m22, m23 = vp[2, 0], vp[2, 1], vp[2, 2], vp[2, 3]
    m30, m31, m32, m33 = vp[3, 0], vp[3, 1], vp[3, 2], vp[3, 3]
    for i in range(world.shape[1]):
        x, y, z = world[0, i], world[1, i], world[2, i]
        cx = m00 * x + m01 * y + m02 * z + m03
        cy = m10 * x + m11 * y + m12 * z + m13
        cz = m20 * x + m21 * y + m22 * z + m23
        cw = m30 * x + m31 * y + m32 * z + m33
        clip[0, i], clip[1, i], clip[2, i], clip[3, i] = cx, cy, cz, cw
        code = 0
        if cz + cw < 0.0:
            code |= NEAR
        if cx + gx * cw < 0.0:
            code |= LEFT
        if gx * cw - cx < 0.0:
            code |= RIGHT
        if cy + gy * cw < 0.0:
            code |= BOTTOM
        if gy * cw - cy < 0.0:
            code |= TOP
        if cw - cz < 0.0:
            code |= FAR
        if not abs(cx) + abs(cy) + abs(cz) + abs(cw) < math.inf:  # false for NaN too
            code = INVALID
        outcodes[i] = code
        if code & ~FAR:
            cx, cy, cz, cw = 0.0, 0.0, 0.0, 1.0  # not used: keeps the conversion in range
        inv_w = 1.0 / cw
        sx = (cx * inv_w + 1.0) * half_w
        sy = (1.0 - cy * inv_w) * half_h
        screen_xy[0, i] = np.int64(math.floor(sx * ONE + 0.5))
        screen_xy[1, i] = np.int64(math.floor(sy * ONE + 0.5))
        screen_z[i] = (cw - cz) * inv_w * 0.5


@ngjit
def light_vertices(world, world_normals, albedo, light_position, ambient, diffuse, colours):
    """Gouraud's vertex colours: Lambert's law plus ambient, from a white point light.

    world, world_normals: (3, n) float64. albedo: (3, n) float32 in [0, 1].
    light_position: (3,) float64, world space. ambient, diffuse: weights.
    Writes colours: (3, n) float64 in [0, 255].
    """
    px, py, pz = light_position[0], light_position[1], light_position[2]
    for i in range(world.shape[1]):
        lx, ly, lz = px - world[0, i], py - world[1, i], pz - world[2, i]
        n_dot_l = world_normals[0, i] * lx + world_normals[1, i] * ly + world_normals[2, i] * lz
        length = math.sqrt(lx * lx + ly * ly + lz * lz)
        # Written so that a NaN (a bad normal, a vertex on the light) gives 0, not NaN.
        lambert = n_dot_l / length if n_dot_l > 0.0 and length > 0.0 else 0.0
        intensity = 255.0 * (ambient + diffuse * lambert)
        for c in range(3):
            # Clamped to [0, 255], NaN giving 0, as `_channel` (written out: no helpers).
            value = albedo[c, i] * intensity
            value = value if value > 0.0 else 0.0
            colours[c, i] = value if value < 255.0 else 255.0


@helper
def _channel(value):
    """value clamped to [0, 255]; NaN gives 0 (the comparison fails, as it does with NaN).

    Here and below, conditional expressions rather than the builtin ``min`` and ``max``:
    numba compiles those as functions of their own for each type and each caller, which
    costs the first, cold run tens of milliseconds apiece."""
    value = value if value > 0.0 else 0.0
    return value if value < 255.0 else 255.0


@ngjit
def phong_vertices(world, world_normals, albedo, attributes):
    """Phong's vertex attributes, interpolated per pixel and lit there.

    world, world_normals: (3, n) float64. albedo: (3, n) float32 in [0, 1].
    Writes attributes: (9, n) float64: position (3), normal (3), 255 albedo (3).
    """
    for c in range(3):
        for i in range(world.shape[1]):
            attributes[c, i] = world[c, i]
            attributes[3 + c, i] = world_normals[c, i]
            attributes[6 + c, i] = 255.0 * albedo[c, i]


@ngjit
def downsample(source, factor, target, width, columns):
    """Average each ``factor`` x ``factor`` block of pixels of source: (3 factor h factor w,)
    uint8 into one pixel of target: (3 h w,) uint8, rounding to nearest; ``width`` is w,
    ``factor`` at most 16. columns: (3 factor w,) int32, scratch (passed in, as the
    rasterizers' is).

    Each output row first sums its ``factor`` source rows column by column (a loop that
    vectorises), then adds up each block's columns. The division by the block's size is a
    multiplication by ``ceil(2^24 / size)`` and a shift, exact for sums below 2^16.
    """
    fine = 3 * width * factor  # bytes in a source row
    count = factor * factor
    reciprocal = ((1 << 24) + count - 1) // count
    for y in range(target.shape[0] // (3 * width)):
        for i in range(fine):
            columns[i] = 0
        for row in range(y * factor, (y + 1) * factor):
            start = np.uint64(row * fine)
            for i in range(fine):
                columns[i] += source[start + np.uint64(i)]
        for x in range(width):
            for c in range(3):
                total = count // 2  # rounds the mean to nearest
                for k in range(factor):
                    total += columns[3 * (factor * x + k) + c]
                target[np.uint64(3 * (y * width + x) + c)] = (total * reciprocal) >> 24


@helper
def _pixel_range(a, b, c, size):
    """The pixels along one axis, clipped to ``0 .. size - 1``, whose centres lie between
    the least and the greatest of three fixed-point coordinates (as in `triangle_spans`).

    The centre of pixel p is at ``p ONE + HALF``, so the pixels whose centres lie in
    [low, high] run from ``ceil((low - HALF) / ONE)`` to ``floor((high - HALF) / ONE)``.
    Conditional expressions rather than the builtin ``min`` and ``max``, which numba
    compiles as functions of their own for each caller (tens of milliseconds apiece of a
    cold start)."""
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
    bias = 0 if a > 0 or (a == 0 and b > 0) else -1
    start = a * (HALF - ax) + b * (row * ONE + HALF - ay) + bias
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
    first, last, left, right = _pixel_box(x0, y0, x1, y1, x2, y2, width, height)
    if first > last or left > right:
        return first, first
    a0, d0, q0, r0, dq0, dr0 = _edge_walker(x0, y0, x1, y1, first)
    a1, d1, q1, r1, dq1, dr1 = _edge_walker(x1, y1, x2, y2, first)
    a2, d2, q2, r2, dq2, dr2 = _edge_walker(x2, y2, x0, y0, first)
    for y in range(first, last + 1):
        lo, hi = _edge_clamp(a0, q0, left, right)
        lo, hi = _edge_clamp(a1, q1, lo, hi)
        lo, hi = _edge_clamp(a2, q2, lo, hi)
        span_lo[y], span_hi[y] = lo, (hi + 1 if hi >= lo else lo)
        q0, r0 = _edge_step(d0, q0, r0, dq0, dr0)
        q1, r1 = _edge_step(d1, q1, r1, dq1, dr1)
        q2, r2 = _edge_step(d2, q2, r2, dq2, dr2)
    return first, last + 1


@inline
def _may_cover(x0, y0, x1, y1, x2, y2, width, height):
    """Whether a triangle (fixed point, as in `triangle_spans`) is front-facing and its
    bounding box holds a pixel centre on the screen: the cheap tests that throw out the
    back half of a closed mesh, and the many triangles smaller than a pixel, before setup.
    Inlined: compiled on its own it had `_pixel_box` compiled a second time for it (0.15 s
    of a cold start)."""
    if (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0) <= 0:
        return False  # back-facing or degenerate
    first, last, left, right = _pixel_box(x0, y0, x1, y1, x2, y2, width, height)
    return first <= last and left <= right


# Span shaders: each fills the pixels of one row, flat offsets start to end (exclusive,
# uint64), whose first centre is (xc, yc), from planes: (1 + a, 3) float64, the rows
# (value at the origin, d/dx, d/dy) of the depth and of the a attributes.


@helper
def _fixed(value):
    """value (float) in 16.16 fixed point (int64), rounded."""
    return np.int64(math.floor(value * 65536.0 + 0.5))


@helper
def _byte(value):
    """A colour channel (float) as the nearest byte value, clamped to [0, 255]."""
    return np.uint8(_channel(value + 0.5))


@helper
def _normalised(x, y, z):
    """(x, y, z) scaled to unit length (or left as is if zero)."""
    length = math.sqrt(x * x + y * y + z * z)
    if length > 0.0:
        inv = 1.0 / length
        return x * inv, y * inv, z * inv
    return x, y, z


@inline
def shade_gouraud(pixels, depths, start, end, xc, yc, planes, lighting):
    """Gouraud: depth-test, then the colour interpolated from the vertices.
    planes: depth, red, green, blue in [0, 255]. lighting: unused.

    The colour steps along the span in 16.16 fixed point. At a covered pixel centre it is a
    convex combination of the vertices' colours, in [0, 255], so the integer part of
    (colour + 1/2) is the rounded byte, with no clamping.
    """
    z = planes[0, 0] + planes[0, 1] * xc + planes[0, 2] * yc
    r = _fixed(planes[1, 0] + planes[1, 1] * xc + planes[1, 2] * yc + 0.5)
    g = _fixed(planes[2, 0] + planes[2, 1] * xc + planes[2, 2] * yc + 0.5)
    b = _fixed(planes[3, 0] + planes[3, 1] * xc + planes[3, 2] * yc + 0.5)
    dz, dr, dg, db = planes[0, 1], _fixed(planes[1, 1]), _fixed(planes[2, 1]), _fixed(planes[3, 1])
    three = np.uint64(3)
    for i in range(start, end):
        depth = np.float32(z)
        if depth > depths[i]:
            depths[i] = depth
            pixels[three * i] = r >> 16
            pixels[three * i + np.uint64(1)] = g >> 16
            pixels[three * i + np.uint64(2)] = b >> 16
        # Forward differences: in float64 and 16.16, exact enough over any span.
        z += dz
        r += dr
        g += dg
        b += db


@helper
def _phong_attributes(planes, x, y):
    """Phong's attributes at (x, y): world position (3), world normal (3), albedo (3)."""
    return (planes[1, 0] + planes[1, 1] * x + planes[1, 2] * y,
            planes[2, 0] + planes[2, 1] * x + planes[2, 2] * y,
            planes[3, 0] + planes[3, 1] * x + planes[3, 2] * y,
            planes[4, 0] + planes[4, 1] * x + planes[4, 2] * y,
            planes[5, 0] + planes[5, 1] * x + planes[5, 2] * y,
            planes[6, 0] + planes[6, 1] * x + planes[6, 2] * y,
            planes[7, 0] + planes[7, 1] * x + planes[7, 2] * y,
            planes[8, 0] + planes[8, 1] * x + planes[8, 2] * y,
            planes[9, 0] + planes[9, 1] * x + planes[9, 2] * y)


@inline
def shade_phong(pixels, depths, start, end, xc, yc, planes, lighting):
    """Phong: depth-test, then light each pixel with its interpolated normal: ambient plus
    Lambert plus the Blinn-Phong highlight (Blinn, "Models of Light Reflection for Computer
    Synthesized Pictures", 1977) of a white point light.

    planes: depth, world position (3), world normal (3), albedo (3) in [0, 255].
    lighting: (11,) float64, laid out as ``LIGHTING``.
    """
    for i in range(start, end):
        x = xc + np.float64(i - start)
        depth = np.float32(planes[0, 0] + planes[0, 1] * x + planes[0, 2] * yc)
        if not depth > depths[i]:
            continue
        depths[i] = depth
        px, py, pz, nx, ny, nz, red, green, blue = _phong_attributes(planes, x, yc)
        nx, ny, nz = _normalised(nx, ny, nz)
        lx, ly, lz = _normalised(lighting[0] - px, lighting[1] - py, lighting[2] - pz)
        vx, vy, vz = _normalised(lighting[3] - px, lighting[4] - py, lighting[5] - pz)
        n_dot_l = nx * lx + ny * ly + nz * lz
        intensity = lighting[6]
        highlight = 0.0
        if n_dot_l > 0.0:
            intensity += lighting[7] * n_dot_l
            hx, hy, hz = _normalised(lx + vx, ly + vy, lz + vz)
            n_dot_h = nx * hx + ny * hy + nz * hz
            if n_dot_h > lighting[10]:
                highlight = 255.0 * lighting[8] * np.float32(n_dot_h) ** np.float32(lighting[9])
        offset = np.uint64(3) * i
        pixels[offset] = _byte(red * intensity + highlight)
        pixels[offset + np.uint64(1)] = _byte(green * intensity + highlight)
        pixels[offset + np.uint64(2)] = _byte(blue * intensity + highlight)


@inline
def count_overdraw(pixels, depths, start, end, xc, yc, planes, lighting):
    """Add 1 to the red channel of every pixel, with no depth test: how many triangles
    cover each pixel. planes, lighting: unused."""
    for i in range(start, end):
        pixels[np.uint64(3) * i] += 1


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
        if _may_cover(screen_xy[0, i0], screen_xy[1, i0], screen_xy[0, i1], screen_xy[1, i1],
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
    lighting: (11,) float64 laid out as ``LIGHTING`` (used by Phong).
    pixels: (3 h w,) uint8 and depths: (h w,) float32, the frame buffers flattened,
    cleared to the background and depth 0; width: w. spans: (2, h) int64 and planes:
    (10, 3) float64 (at least 1 + a rows): scratch, passed in so that the kernel allocates
    nothing (numba's ``np.empty`` alone costs a cold start about 0.1 s to compile).

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


# Clipping is a separate pass, compiled the first time a frame needs it.


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
def clip_triangles(triangles, clip, screen_xy, screen_z, outcodes, attributes, width, height,
                   out_xy, out_z, out_attributes, out_triangles, counts):
    """Clip the triangles that cross a clipping plane (but are not wholly outside one) and
    write what is left of them as a mesh for the rasterize kernels.

    triangles: (m, 3) int32; clip: (4, n), screen_xy: (2, n), screen_z: (n,), outcodes:
    (n,) from `project_vertices`; attributes: (a, n) float64; width, height: the screen.
    Writes out_xy: (2, k) int64, out_z: (k,) float64, out_attributes: (a, k) float64 and
    out_triangles: (j, 3) int32, room enough being ``MAX_POLYGON`` vertices and
    ``MAX_POLYGON - 2`` triangles per triangle to clip, and counts: (2,) int64, the vertices
    and triangles written. Each clipped triangle leaves a convex polygon, drawn as a fan
    (the near plane alone leaves a triangle or a quadrilateral).
    """
    gx, gy = _guard(width), _guard(height)
    a = attributes.shape[0]
    polygon = np.empty((2, MAX_POLYGON, 4 + a))
    source = np.empty((2, MAX_POLYGON), np.int64)
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
                out_xy[0, o], out_xy[1, o], out_z[o] = screen_xy[0, v], screen_xy[1, v], screen_z[v]
            else:
                out_xy[0, o], out_xy[1, o], out_z[o] = _to_screen(
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
