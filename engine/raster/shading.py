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
    """Gouraud: depth-test, then the colour interpolated from the vertices, in perspective.
    planes: depth, q, and red, green, blue in [0, 255] times q. lighting: unused.

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


@inline
def shade_gouraud_on_screen(pixels, depths, start, end, xc, yc, planes, lighting):
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


@helper
def _phong_attributes(planes, x, y):
    """Phong's attributes at (x, y), in perspective: world position (3), world normal (3),
    albedo (3)."""
    w = 1.0 / (planes[1, 0] + planes[1, 1] * x + planes[1, 2] * y)
    return ((planes[2, 0] + planes[2, 1] * x + planes[2, 2] * y) * w,
            (planes[3, 0] + planes[3, 1] * x + planes[3, 2] * y) * w,
            (planes[4, 0] + planes[4, 1] * x + planes[4, 2] * y) * w,
            (planes[5, 0] + planes[5, 1] * x + planes[5, 2] * y) * w,
            (planes[6, 0] + planes[6, 1] * x + planes[6, 2] * y) * w,
            (planes[7, 0] + planes[7, 1] * x + planes[7, 2] * y) * w,
            (planes[8, 0] + planes[8, 1] * x + planes[8, 2] * y) * w,
            (planes[9, 0] + planes[9, 1] * x + planes[9, 2] * y) * w,
            (planes[10, 0] + planes[10, 1] * x + planes[10, 2] * y) * w)


@inline
def shade_phong(pixels, depths, start, end, xc, yc, planes, lighting):
    """Phong: depth-test, then light each pixel with its interpolated normal: ambient plus
    Lambert plus the Blinn-Phong highlight (Blinn, "Models of Light Reflection for Computer
    Synthesized Pictures", 1977) of a white point light.

    planes: depth, q, and times q: world position (3), world normal (3), albedo (3) in
    [0, 255]. lighting: `Lighting`.
    """
    for i in range(start, end):
        x = xc + np.float64(i - start)
        depth = np.float32(planes[0, 0] + planes[0, 1] * x + planes[0, 2] * yc)
        if not depth > depths[i]:
            continue
        depths[i] = depth
        px, py, pz, nx, ny, nz, red, green, blue = _phong_attributes(planes, x, yc)
        nx, ny, nz = _normalised(nx, ny, nz)
        lx, ly, lz = _normalised(lighting.light_x - px, lighting.light_y - py,
                                 lighting.light_z - pz)
        vx, vy, vz = _normalised(lighting.eye_x - px, lighting.eye_y - py, lighting.eye_z - pz)
        n_dot_l = nx * lx + ny * ly + nz * lz
        intensity = lighting.ambient
        highlight = 0.0
        if n_dot_l > 0.0:
            intensity += lighting.diffuse * n_dot_l
            hx, hy, hz = _normalised(lx + vx, ly + vy, lz + vz)
            n_dot_h = nx * hx + ny * hy + nz * hz
            if n_dot_h > lighting.highlight_threshold:
                highlight = (255.0 * lighting.specular
                             * np.float32(n_dot_h) ** np.float32(lighting.shininess))
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
