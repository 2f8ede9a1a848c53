"""The vertex stage: positions and normals to world space, to clip space and onto the
screen, and the attributes each vertex gives the rasterizer.

Every matrix is read into registers before its loop, over component-major buffers (the
layouts in ``engine/raster/__init__.py``): then LLVM vectorises the loops.

Each kernel works on the vertices ``first <= i < end`` only, so that threads can share a
large mesh's vertices, each its own range of every buffer (``engine/render.py``). The loops
count in unsigned integers: numba fixes up negative indices, and from a signed ``first``
LLVM cannot rule one out and no longer vectorises (``project_vertices`` ran 2.5 times as
slow).
"""

import math

import numpy as np

from biceps.engine.jit import ngjit
from biceps.engine.raster.clipping import (BOTTOM, FAR, GUARD_BAND, INVALID, LEFT, NEAR,
                                           RIGHT, TOP)
from biceps.engine.raster.coverage import ONE


@ngjit
def transform_vertices(vertices, normals, model, normal_matrix, world, world_normals, first,
                       end):
    """Model space to world space.

    vertices, normals: (3, n) float64. model: (4, 4) float64 acting on column vectors.
    normal_matrix: (3, 3) float64, the inverse transpose of ``model[:3, :3]``.
    Writes world: (3, n) float64 and world_normals: (3, n) float64, renormalised.
    """
    # The vertex kernels call no helpers: each function numba compiles lengthens the first,
    # cold run (see engine/jit.py).
    m00, m01, m02, m03 = model[0, 0], model[0, 1], model[0, 2], model[0, 3]
    m10, m11, m12, m13 = model[1, 0], model[1, 1], model[1, 2], model[1, 3]
    m20, m21, m22, m23 = model[2, 0], model[2, 1], model[2, 2], model[2, 3]
    for i in range(np.uint64(first), np.uint64(end)):
        x, y, z = vertices[0, i], vertices[1, i], vertices[2, i]
        world[0, i] = m00 * x + m01 * y + m02 * z + m03
        world[1, i] = m10 * x + m11 * y + m12 * z + m13
        world[2, i] = m20 * x + m21 * y + m22 * z + m23
    n00, n01, n02 = normal_matrix[0, 0], normal_matrix[0, 1], normal_matrix[0, 2]
    n10, n11, n12 = normal_matrix[1, 0], normal_matrix[1, 1], normal_matrix[1, 2]
    n20, n21, n22 = normal_matrix[2, 0], normal_matrix[2, 1], normal_matrix[2, 2]
    for i in range(np.uint64(first), np.uint64(end)):
        x, y, z = normals[0, i], normals[1, i], normals[2, i]
        nx = n00 * x + n01 * y + n02 * z
        ny = n10 * x + n11 * y + n12 * z
        nz = n20 * x + n21 * y + n22 * z
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        scale = 1.0 / length if length > 0.0 else 0.0
        world_normals[0, i] = nx * scale
        world_normals[1, i] = ny * scale
        world_normals[2, i] = nz * scale


@ngjit
def project_vertices(world, view_projection, width, height, clip, screen_xy, screen_z, screen_q,
                     outcodes, first, end):
    """World space to clip space and, where inside the clip planes, to screen space.

    world: (3, n) float64. view_projection: (4, 4) float64. width, height: the screen in pixels.
    Writes clip: (4, n) float64; outcodes: (n,) uint8 (bits NEAR ... INVALID); and for the
    vertices inside every clipping plane (outcode 0 or FAR), screen_xy: (2, n) int64 in
    1/256 pixel, screen_z: (n,) float64 depth and screen_q: (n,) float64, 1 / w, with which
    the rasterizer interpolates attributes in perspective (elsewhere 0, 0 and 1).

    The outcode is branch-free apart from selects, so that the loop vectorises; INVALID
    if a coordinate is not finite (or so large that the sum of magnitudes overflows). The
    screen position is `clipping._to_screen`'s, written out here (no helpers, as above).
    """
    gx = 1.0 + 2.0 * GUARD_BAND / width  # the guard band's planes, in units of w
    gy = 1.0 + 2.0 * GUARD_BAND / height
    half_w, half_h = 0.5 * width, 0.5 * height
    vp = view_projection
    m00, m01, m02, m03 = vp[0, 0], vp[0, 1], vp[0, 2], vp[0, 3]
    m10, m11, m12, m13 = vp[1, 0], vp[1, 1], vp[1, 2], vp[1, 3]
    m20, m21, m22, m23 = vp[2, 0], vp[2, 1], vp[2, 2], vp[2, 3]
    m30, m31, m32, m33 = vp[3, 0], vp[3, 1], vp[3, 2], vp[3, 3]
    for i in range(np.uint64(first), np.uint64(end)):
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
        screen_q[i] = inv_w


@ngjit
def light_vertices(world, world_normals, albedo, light_position, ambient, diffuse, colours,
                   first, end):
    """Gouraud's vertex colours: Lambert's law plus ambient, from a white point light.

    world, world_normals: (3, n) float64. albedo: (3, n) float32 in [0, 1].
    light_position: (3,) float64, world space. ambient, diffuse: weights.
    Writes colours: (3, n) float64 in [0, 255].
    """
    px, py, pz = light_position[0], light_position[1], light_position[2]
    for i in range(np.uint64(first), np.uint64(end)):
        lx, ly, lz = px - world[0, i], py - world[1, i], pz - world[2, i]
        n_dot_l = world_normals[0, i] * lx + world_normals[1, i] * ly + world_normals[2, i] * lz
        length = math.sqrt(lx * lx + ly * ly + lz * lz)
        # Written so that a NaN (a bad normal, a vertex on the light) gives 0, not NaN.
        lambert = n_dot_l / length if n_dot_l > 0.0 and length > 0.0 else 0.0
        intensity = 255.0 * (ambient + diffuse * lambert)
        for c in range(3):
            # Clamped to [0, 255], NaN giving 0, as `shading._channel` (written out: no helpers).
            value = albedo[c, i] * intensity
            value = value if value > 0.0 else 0.0
            colours[c, i] = value if value < 255.0 else 255.0


@ngjit
def phong_vertices(albedo, attributes, first, end):
    """Phong's vertex attributes, interpolated per pixel and lit there: attributes: (9, n)
    float64, position (3), normal (3) and 255 albedo (3). The first six rows are the world
    positions and normals themselves, as `transform_vertices` wrote them (the renderer
    passes it views of those rows), so only the albedo is written here, from
    albedo: (3, n) float32 in [0, 1]: copying the rest took a third of the vertex stage.
    """
    for c in range(3):
        for i in range(np.uint64(first), np.uint64(end)):
            attributes[6 + c, i] = 255.0 * albedo[c, i]
