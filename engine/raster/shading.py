"""Shading: the span shaders, which depth-test and colour the covered pixels of one row of
a triangle.

Each fills the pixels at flat offsets start to end (exclusive, uint64), whose first centre
is (xc, yc), from planes: (2 + a, 3) float64, the rows (value at the origin, d/dx, d/dy) of
the depth, of ``q = 1 / w`` and of the a attributes times q, which ``engine/raster/draw.py``
sets up per triangle. An attribute at a pixel is its plane's value over q's: perspective
correct. The division is done only for the pixels that pass the depth test, and not at all
where ``draw`` finds the triangle shallow enough to interpolate on the screen (then q is 1).
"""

import math
from typing import NamedTuple

import numpy as np

from biceps.engine.jit import helper, inline


class Lighting(NamedTuple):
    """The rasterize kernels' lighting (see `shade_phong`): a white point light and the eye,
    world space; the weights of the ambient, diffuse and specular terms; the Blinn-Phong
    exponent; and the ``n.h`` below which there is no highlight to draw (see
    `highlight_threshold`).

    Every field a float: numba types the whole as eleven float64, which its cache keeps as
    it keeps an array's type; an int among them would make another type, and every rasterize
    kernel would be compiled again for it.
    """

    light_x: float
    light_y: float
    light_z: float
    eye_x: float
    eye_y: float
    eye_z: float
    ambient: float
    diffuse: float
    specular: float
    shininess: float
    highlight_threshold: float


def highlight_threshold(specular: float, shininess: float) -> float:
    """The least ``n.h`` whose highlight, ``255 specular (n.h) ^ shininess``, reaches half a
    colour level: ``(1 / (2 255 specular)) ^ (1 / shininess)``. Below it Phong skips its
    ``pow``; 2 (beyond any ``n.h``) if there is no highlight at all."""
    if specular <= 0.0:
        return 2.0
    if shininess == 0.0:
        return 0.0
    return (0.5 / (255.0 * specular)) ** (1.0 / shininess)


@helper
def _channel(value):
    """value clamped to [0, 255]; NaN gives 0 (the comparison fails, as it does with NaN).

    Here and below, conditional expressions rather than the builtin ``min`` and ``max``:
    numba compiles those as functions of their own for each type and each caller, each one
    more compile on the first, cold run."""
    value = value if value > 0.0 else 0.0
    return value if value < 255.0 else 255.0


@helper
def _fixed(value):
    """value (float) in 16.16 fixed point (int64), rounded."""
    return np.int64(math.floor(value * 65536.0 + 0.5))


@helper
def _byte(value):
    """A colour channel (float) as the nearest byte value, clamped to [0, 255]."""
    return np.uint8(_channel(value + 0.5))


@inline
def shade_gouraud(pixels, depths, start, end, xc, yc, planes, lighting, hits, shaded, count):
    """Gouraud: depth-test, then the colour interpolated from the vertices, in perspective.
    planes: depth, q, and red, green, blue in [0, 255] times q. lighting, hits, shaded:
    unused; count returned as it is (every span shader takes and returns the same, see
    `shade_phong`).

    Every plane steps along the span by forward differences in float64, exact enough over
    any span; the colour, a convex combination of the vertices', is within [0, 255] but for
    rounding, which `_byte` clamps.
    """
    z = planes[0, 0] + planes[0, 1] * xc + planes[0, 2] * yc
    q = planes[1, 0] + planes[1, 1] * xc + planes[1, 2] * yc
    r = planes[2, 0] + planes[2, 1] * xc + planes[2, 2] * yc
    g = planes[3, 0] + planes[3, 1] * xc + planes[3, 2] * yc
    b = planes[4, 0] + planes[4, 1] * xc + planes[4, 2] * yc
    dz, dq, dr, dg, db = planes[0, 1], planes[1, 1], planes[2, 1], planes[3, 1], planes[4, 1]
    three = np.uint64(3)
    for i in range(start, end):
        depth = np.float32(z)
        if depth > depths[i]:
            depths[i] = depth
            w = 1.0 / q
            pixels[three * i] = _byte(r * w)
            pixels[three * i + np.uint64(1)] = _byte(g * w)
            pixels[three * i + np.uint64(2)] = _byte(b * w)
        z += dz
        q += dq
        r += dr
        g += dg
        b += db
    return count


@inline
def shade_gouraud_on_screen(pixels, depths, start, end, xc, yc, planes, lighting, hits,
                            shaded, count):
    """`shade_gouraud` for a triangle shallow enough to interpolate on the screen (q is 1
    throughout, see ``engine/raster/draw.py``): no division.

    The colour steps along the span in 16.16 fixed point. At a covered pixel centre it is a
    convex combination of the vertices' colours, in [0, 255], so the integer part of
    (colour + 1/2) is the rounded byte, with no clamping.
    """
    z = planes[0, 0] + planes[0, 1] * xc + planes[0, 2] * yc
    r = _fixed(planes[2, 0] + planes[2, 1] * xc + planes[2, 2] * yc + 0.5)
    g = _fixed(planes[3, 0] + planes[3, 1] * xc + planes[3, 2] * yc + 0.5)
    b = _fixed(planes[4, 0] + planes[4, 1] * xc + planes[4, 2] * yc + 0.5)
    dz, dr, dg, db = planes[0, 1], _fixed(planes[2, 1]), _fixed(planes[3, 1]), _fixed(planes[4, 1])
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
    return count


@inline
def shade_phong(pixels, depths, start, end, xc, yc, planes, lighting, hits, shaded, count):
    """Phong's span: depth-test, and list the pixels that pass for `light_phong`, which
    lights them all at once, once per triangle (or when the list is full). Returns the
    length of the list, ``count`` before.

    hits: (c,) int64, the pixels' offsets; shaded: (8, c) float32, rows 0 and 1 their
    centres' x and y. A triangle's pixels lit in one loop, rather than a span's, make that
    loop long enough for LLVM's vector code to pay (a span of a small triangle is a few
    pixels long, and its setup costs as much as the pixels); and a pixel is lit once per
    triangle found nearest so far, never once per triangle covering it.
    """
    # x stepped by adding 1, exact for half-integers (and the same x as ``xc + (i - start)``):
    # converting the unsigned offset to a float, pixel by pixel, is slow (x86 has no
    # instruction for it before AVX-512).
    x = xc
    y = np.float32(yc)
    for i in range(start, end):
        depth = np.float32(planes[0, 0] + planes[0, 1] * x + planes[0, 2] * yc)
        if depth > depths[i]:
            depths[i] = depth
            hits[count] = np.int64(i)
            shaded[0, count] = np.float32(x)
            shaded[1, count] = y
            count += 1
        x += 1.0
    return count


@inline
def light_phong(pixels, count, origin_x, origin_y, planes, lighting, hits, shaded):
    """Light the ``count`` pixels `shade_phong` listed: ambient plus Lambert plus the
    Blinn-Phong highlight (Blinn, "Models of Light Reflection for Computer Synthesized
    Pictures", 1977) of a white point light, with each pixel's interpolated normal.

    planes: depth, q, and times q: world position (3), world normal (3), albedo (3) in
    [0, 255]. lighting: `Lighting`. shaded rows 2 to 7: scratch. origin_x, origin_y: a
    point near the triangle, the same for all its pixels (see below).

    Passes: the lighting, in float32 with no branch and no call, which LLVM vectorises;
    the highlight's power for a whole exponent, as the default (`_whole_powers`); then the
    writes, with a ``pow`` for the pixels near the highlight (where Phong's cosine reaches
    `highlight_threshold`) when the exponent has a fraction.

    Only the albedo needs the attribute over q: the normal and the vectors to the light and
    to the eye are each normalised, and scaling by q > 0 (1 / w, positive in front of the
    eye) does not change a direction, so they are interpolated times q as they come, with
    no division: ``light q - position q`` is linear on the screen as both terms are. Each
    quantity is its value at the origin (float64, where the planes reach far from the
    screen's corner) plus float32 steps from there: a pixel's colour depends on the pixel
    and the triangle alone, not on which band or which list it was lit in.
    """
    if count == 0:
        return
    ox, oy = origin_x, origin_y
    lx, ly, lz = lighting.light_x, lighting.light_y, lighting.light_z
    ex, ey, ez = lighting.eye_x, lighting.eye_y, lighting.eye_z
    q = _at(planes, 1, ox, oy)
    px, py, pz = _at(planes, 2, ox, oy), _at(planes, 3, ox, oy), _at(planes, 4, ox, oy)
    q0, qx, qy = np.float32(q), np.float32(planes[1, 1]), np.float32(planes[1, 2])
    n0x, nxx, nxy = _start(planes, 5, ox, oy)
    n0y, nyx, nyy = _start(planes, 6, ox, oy)
    n0z, nzx, nzy = _start(planes, 7, ox, oy)
    a0r, arx, ary = _start(planes, 8, ox, oy)
    a0g, agx, agy = _start(planes, 9, ox, oy)
    a0b, abx, aby = _start(planes, 10, ox, oy)
    t0x, txx, txy = _towards(planes, 2, lx, q, px)
    t0y, tyx, tyy = _towards(planes, 3, ly, q, py)
    t0z, tzx, tzy = _towards(planes, 4, lz, q, pz)
    v0x, vxx, vxy = _towards(planes, 2, ex, q, px)
    v0y, vyx, vyy = _towards(planes, 3, ey, q, py)
    v0z, vzx, vzy = _towards(planes, 4, ez, q, pz)
    ambient, diffuse = np.float32(lighting.ambient), np.float32(lighting.diffuse)
    threshold = np.float32(lighting.highlight_threshold)
    specular = np.float32(255.0 * lighting.specular)
    shininess = np.float32(lighting.shininess)
    power = np.int64(lighting.shininess)
    whole = power == lighting.shininess  # as the default, 24
    fx, fy = np.float32(ox), np.float32(oy)
    zero, one = np.float32(0.0), np.float32(1.0)
    for j in range(count):
        u, v = shaded[0, j] - fx, shaded[1, j] - fy
        nx, ny, nz = n0x + u * nxx + v * nxy, n0y + u * nyx + v * nyy, n0z + u * nzx + v * nzy
        tx, ty, tz = t0x + u * txx + v * txy, t0y + u * tyx + v * tyy, t0z + u * tzx + v * tzy
        vx, vy, vz = v0x + u * vxx + v * vxy, v0y + u * vyx + v * vyy, v0z + u * vzx + v * vzy
        n_scale = _inverse_length(nx, ny, nz)
        t_scale = _inverse_length(tx, ty, tz)
        v_scale = _inverse_length(vx, vy, vz)
        tx, ty, tz = tx * t_scale, ty * t_scale, tz * t_scale
        hx, hy, hz = tx + vx * v_scale, ty + vy * v_scale, tz + vz * v_scale
        h_scale = _inverse_length(hx, hy, hz)
        n_dot_l = (nx * tx + ny * ty + nz * tz) * n_scale
        n_dot_h = (nx * hx + ny * hy + nz * hz) * n_scale * h_scale
        lit = n_dot_l > zero
        intensity = (ambient + diffuse * (n_dot_l if lit else zero)) / (q0 + u * qx + v * qy)
        shaded[2, j] = (a0r + u * arx + v * ary) * intensity
        shaded[3, j] = (a0g + u * agx + v * agy) * intensity
        shaded[4, j] = (a0b + u * abx + v * aby) * intensity
        shaded[5, j] = n_dot_h if lit else -one
    if whole:
        _whole_powers(shaded, count, power)
    three = np.uint64(3)
    for j in range(count):
        n_dot_h = shaded[5, j]
        if n_dot_h > threshold:
            highlight = specular * (shaded[6, j] if whole else n_dot_h ** shininess)
        else:
            highlight = zero
        offset = three * np.uint64(hits[j])
        pixels[offset] = _byte(shaded[2, j] + highlight)
        pixels[offset + np.uint64(1)] = _byte(shaded[3, j] + highlight)
        pixels[offset + np.uint64(2)] = _byte(shaded[4, j] + highlight)


@helper
def _whole_powers(shaded, count, power):
    """shaded[6, :count] = shaded[5, :count] ** power, for a whole power, by squaring
    (shaded[7] the squares): a pass over the pixels for each bit of the power, each a
    loop of a multiplication that LLVM vectorises, where ``pow`` would be called pixel by
    pixel. For the default 24, four squarings and two multiplications a pixel."""
    one = np.float32(1.0)
    odd = power & 1
    for j in range(count):
        x = shaded[5, j]
        shaded[7, j] = x
        shaded[6, j] = x if odd else one
    bit = 2
    while bit <= power:
        for j in range(count):
            shaded[7, j] *= shaded[7, j]
        if power & bit:
            for j in range(count):
                shaded[6, j] *= shaded[7, j]
        bit <<= 1


@helper
def _start(planes, row, x, y):
    """The plane ``planes[row]`` at (x, y) and its steps along x and y, float32."""
    return (np.float32(_at(planes, row, x, y)), np.float32(planes[row, 1]),
            np.float32(planes[row, 2]))


@helper
def _towards(planes, row, target, q, position):
    """The plane of ``target q - position q`` (one coordinate of the vector from a pixel's
    point to ``target``, times q) as `_start` gives it, from q and the position's plane
    ``planes[row]`` at the first pixel."""
    return (np.float32(target * q - position),
            np.float32(target * planes[1, 1] - planes[row, 1]),
            np.float32(target * planes[1, 2] - planes[row, 2]))


@helper
def _at(planes, row, x, y):
    """The plane ``planes[row]`` at (x, y), float64."""
    return planes[row, 0] + planes[row, 1] * x + planes[row, 2] * y


@helper
def _inverse_length(x, y, z):
    """1 / |(x, y, z)| (float32), or 0 for the zero vector (a normal that cancels out, a
    pixel on the light), which then lights nothing: a select, not a branch, so that the
    loop calling it vectorises."""
    square = x * x + y * y + z * z
    return np.float32(1.0) / np.sqrt(square) if square > np.float32(0.0) else np.float32(0.0)


@inline
def count_overdraw(pixels, depths, start, end, xc, yc, planes, lighting, hits, shaded, count):
    """Add 1 to the red channel of every pixel, with no depth test: how many triangles
    cover each pixel. planes, lighting: unused."""
    for i in range(start, end):
        pixels[np.uint64(3) * i] += 1
    return count
