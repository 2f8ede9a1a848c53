"""The rasterizer: exact coverage, depth, shading, clipping and supersampling.

Coverage is checked against a plain-Python reference that applies the top-left rule as
D3D10 states it (a top edge is horizontal with the triangle below it; a left edge has the
triangle to its right), with exact fractions, over every pixel centre.
"""

import math
from fractions import Fraction

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from biceps.engine import raster
from biceps.engine.render import Renderer
from biceps.engine.transforms import Camera, Light, model_matrix, transform_points, viewport

def reference_coverage(triangle, width, height):
    """The pixels (x, y) whose centres the top-left rule puts inside ``triangle``, three
    (x, y) screen points (y down, any winding, non-degenerate)."""
    a, b, c = [(Fraction(x), Fraction(y)) for x, y in triangle]
    edges = [(a, b, c), (b, c, a), (c, a, b)]  # (start, end, opposite vertex)

    def cross(p, q, s):
        return (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])

    def top_or_left(p, q, r):
        if p[1] == q[1]:
            return r[1] > p[1]  # horizontal, the triangle below it: a top edge
        x_at_r = p[0] + (q[0] - p[0]) * (r[1] - p[1]) / (q[1] - p[1])
        return r[0] > x_at_r  # the triangle to its right: a left edge

    covered = set()
    for y in range(height):
        for x in range(width):
            centre = (Fraction(2 * x + 1, 2), Fraction(2 * y + 1, 2))
            inside = True
            for p, q, r in edges:
                side, inner = cross(p, q, centre), cross(p, q, r)
                if side * inner < 0 or (side == 0 and not top_or_left(p, q, r)):
                    inside = False
            if inside:
                covered.add((x, y))
    return covered


def front_facing(points, triangles):
    """``triangles`` (m, 3) reordered so that each is front-facing on the y-down screen."""
    p = np.asarray(points, dtype=np.float64)
    triangles = np.array(triangles, dtype=np.int32).reshape(-1, 3)
    a, b, c = p[triangles[:, 0]], p[triangles[:, 1]], p[triangles[:, 2]]
    area = (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]) - (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
    triangles[area < 0] = triangles[area < 0][:, ::-1]
    return triangles


def draw_on_screen(points, triangles, width, height, *, colours=None,
                   kernel=raster.rasterize_overdraw):
    """Run the pipeline from `project_vertices` on, for ``points`` (n, 2) given in screen
    pixels (an identity projection, w = 1). Returns the (height, width, 3) picture: with the
    default kernel, the red channel counts how often each pixel is drawn."""
    points = np.asarray(points, dtype=np.float64)
    n = len(points)
    world = np.zeros((3, n))
    world[0] = 2.0 * points[:, 0] / width - 1.0
    world[1] = 1.0 - 2.0 * points[:, 1] / height
    clip, xy = np.empty((4, n)), np.empty((2, n), np.int64)
    z, q, codes = np.empty(n), np.empty(n), np.empty(n, np.uint8)
    raster.project_vertices(world, np.eye(4), width, height, clip, xy, z, q, codes, 0, n)
    attributes = np.empty((0, n)) if colours is None else np.ascontiguousarray(colours.T)
    colour = np.zeros((height, width, 3), np.uint8)
    depths = np.zeros(height * width, np.float32)  # the far plane
    triangles = np.ascontiguousarray(triangles, dtype=np.int32)
    spans = np.empty((4, height), np.int64)
    spans[2], spans[3] = width, 0  # nothing drawn yet
    kernel(triangles, xy, z, q, codes, attributes, raster.Lighting(*[0.0] * 11),
           colour.reshape(-1), depths, width, 0, height, spans,
           np.empty((11, 3)), np.empty(width, np.int64), np.empty((8, width), np.float32))
    return colour


def counts(picture):
    return picture[..., 0].astype(int)


def covered_set(picture):
    ys, xs = np.nonzero(counts(picture))
    return set(zip(xs.tolist(), ys.tolist()))


def spans_set(triangle, width, height):
    """The pixels `triangle_spans` covers, for a front-facing triangle in screen pixels."""
    (x0, y0), (x1, y1), (x2, y2) = [(int(x * 256), int(y * 256)) for x, y in triangle]
    lo, hi = np.zeros(height, np.int64), np.zeros(height, np.int64)
    first, end = raster.triangle_spans(x0, y0, x1, y1, x2, y2, width, height, lo, hi)
    return {(x, y) for y in range(first, end) for x in range(lo[y], hi[y])}


def plain_camera(distance=1.0, fov=90.0, near=0.1, far=100.0):
    return Camera(eye=(0.0, 0.0, distance), target=(0.0, 0.0, 0.0), fov_y_deg=fov,
                  near=near, far=far)


def flat_light():
    """Ambient only: a vertex's colour is its albedo times 255."""
    return Light(position=(0.0, 0.0, 10.0), ambient=1.0, diffuse=0.0, specular=0.0)


def render(vertices, triangles, *, albedo=None, normals=None, camera=None, light=None,
           size=(16, 16), model=None, **options):
    vertices = np.asarray(vertices, dtype=np.float64)
    n = len(vertices)
    normals = np.tile([0.0, 0.0, 1.0], (n, 1)) if normals is None else normals
    albedo = np.ones((n, 3), np.float32) if albedo is None else np.asarray(albedo, np.float32)
    return Renderer().render(vertices, normals, np.asarray(triangles, np.int32), albedo,
                             np.eye(4) if model is None else model,
                             camera or plain_camera(), light or flat_light(), *size, **options)


def sphere(subdivisions=3, inward=False):
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions)
    faces = mesh.faces[:, ::-1] if inward else mesh.faces
    vertices = np.array(mesh.vertices)
    return vertices, vertices.copy(), faces.astype(np.int32)  # a unit sphere: normal = position


# Projection.


def test_projection_applies_the_viewport_and_snaps_to_a_256th_of_a_pixel():
    rng = np.random.default_rng(7)
    world = rng.uniform(-1, 1, (3, 50)) + [[0], [0], [-4]]
    camera = plain_camera(distance=1.0, fov=70.0, near=0.5, far=20.0)
    view_projection = camera.projection_matrix(1.5) @ camera.view_matrix()
    clip, xy = np.empty((4, 50)), np.empty((2, 50), np.int64)
    z, q, codes = np.empty(50), np.empty(50), np.empty(50, np.uint8)
    raster.project_vertices(world, view_projection, 300, 200, clip, xy, z, q, codes, 0, 50)
    expected = transform_points(viewport(300, 200) @ view_projection, world.T)
    assert np.all(codes == 0)
    np.testing.assert_array_equal(xy.T, np.floor(expected[:, :2] * 256 + 0.5))
    np.testing.assert_allclose(z, expected[:, 2], rtol=1e-12)
    np.testing.assert_allclose(q, 1.0 / (1.0 - world[2]), rtol=1e-12)  # w: the distance


def test_outcodes_name_the_planes_a_vertex_is_outside():
    # Clip-space points (identity projection, so w = 1): beyond the near plane (z < -w),
    # the far one (z > w), the guard band on the right, a NaN, and one inside.
    world = np.array([[0.0, 0.0, -1.5], [0.0, 0.0, 2.0], [1e9, 0.0, 0.0], [np.nan, 0.0, 0.0],
                      [0.5, -0.5, 0.0]]).T
    clip, xy = np.empty((4, 5)), np.empty((2, 5), np.int64)
    z, q, codes = np.empty(5), np.empty(5), np.empty(5, np.uint8)
    raster.project_vertices(world.copy(), np.eye(4), 64, 48, clip, xy, z, q, codes, 0, 5)
    assert codes.tolist() == [raster.NEAR, raster.FAR, raster.RIGHT, raster.INVALID, 0]


# Coverage: the top-left rule.

EDGE_CASES = {
    # Edges through pixel centres: the top and left ones count, the slanted right one not.
    "top and left edges on centres": [(0.5, 0.5), (0.5, 6.5), (6.5, 0.5)],
    # The same turned round: bottom and right edges on centres, none of them count.
    "bottom and right edges on centres": [(7.5, 7.5), (7.5, 1.5), (1.5, 7.5)],
    "vertex on a centre": [(3.5, 3.5), (1.25, 6.0), (6.0, 5.0)],
    "thin sliver": [(0.25, 0.5), (7.75, 2.5), (0.25, 0.75)],
    "half off the screen": [(-3.0, -2.0), (-1.0, 9.5), (10.0, 4.5)],
    "smaller than a pixel": [(2.25, 2.25), (2.25, 2.75), (2.75, 2.25)],
    "grid-aligned square half": [(2.0, 2.0), (2.0, 6.0), (6.0, 6.0)],
}


@pytest.mark.parametrize("name", sorted(EDGE_CASES))
def test_one_triangle_covers_what_the_top_left_rule_says(name):
    points = EDGE_CASES[name]
    triangles = front_facing(points, [0, 1, 2])
    picture = draw_on_screen(points, triangles, 8, 8)
    assert counts(picture).max() <= 1
    assert covered_set(picture) == reference_coverage(points, 8, 8)


def test_top_and_left_edges_through_centres_count():
    picture = draw_on_screen(EDGE_CASES["top and left edges on centres"],
                             [[0, 1, 2]], 8, 8)
    # Row 0 and column 0 lie on the top and left edges; the diagonal x + y = 6 is the
    # hypotenuse (a right edge), so (6, 0), (0, 6) and everything on it stay out.
    expected = {(x, y) for y in range(7) for x in range(7) if x + y < 6}
    assert covered_set(picture) == expected


def quarter_pixels(low, high):
    return st.integers(4 * low, 4 * high).map(lambda k: k / 4)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(quarter_pixels(-2, 10), quarter_pixels(-2, 10)), min_size=3, max_size=3))
def test_coverage_matches_the_reference_on_random_triangles(points):
    (x0, y0), (x1, y1), (x2, y2) = points
    if (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0) == 0:
        return  # degenerate: nothing to compare (drawn as nothing, see below)
    triangle = [points[i] for i in front_facing(points, [0, 1, 2])[0]]
    assert spans_set(triangle, 8, 8) == reference_coverage(triangle, 8, 8)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(quarter_pixels(2, 5), quarter_pixels(2, 5)), min_size=3, max_size=3))
def test_coverage_of_triangles_narrower_than_an_edge_walk_matches_the_reference(points):
    # At most three pixel centres wide: covered by testing each centre (coverage.NARROW).
    (x0, y0), (x1, y1), (x2, y2) = points
    if (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0) == 0:
        return
    triangle = [points[i] for i in front_facing(points, [0, 1, 2])[0]]
    assert spans_set(triangle, 8, 8) == reference_coverage(triangle, 8, 8)


def test_back_faces_and_degenerate_triangles_draw_nothing():
    points = [(1.0, 1.0), (1.0, 7.0), (7.0, 1.0), (4.0, 4.0), (2.0, 2.0)]
    back = front_facing(points, [0, 1, 2])[:, ::-1]
    degenerate = [[0, 3, 4], [0, 0, 1], [2, 2, 2]]  # collinear, repeated vertices
    picture = draw_on_screen(points, np.concatenate([back, degenerate]), 8, 8)
    assert counts(picture).sum() == 0


# Coverage: shared edges, exactly once.


def test_two_triangles_sharing_a_diagonal_cover_the_screen_exactly_once():
    corners = [(0, 0), (8, 0), (8, 8), (0, 8)]
    picture = draw_on_screen(corners, front_facing(corners, [[0, 1, 2], [0, 2, 3]]), 8, 8)
    assert np.all(counts(picture) == 1)


@settings(max_examples=100, deadline=None)
@given(centre=st.tuples(quarter_pixels(1, 11), quarter_pixels(1, 7)),
       cuts=st.lists(st.integers(1, 4 * 40 - 1), min_size=1, max_size=30, unique=True))
def test_a_fan_covering_the_screen_covers_each_pixel_exactly_once(centre, cuts):
    width, height = 12, 8
    # Points along the screen's border, in quarter pixels of perimeter, and the 4 corners.
    perimeter = 2 * (width + height)

    sides = [(width, (0, 0), (1, 0)), (height, (width, 0), (0, 1)),
             (width, (width, height), (-1, 0)), (height, (0, height), (0, -1))]

    def border(t):
        t = t / 4 % perimeter
        for length, start, step in sides:
            if t < length:
                return (start[0] + step[0] * t, start[1] + step[1] * t)
            t -= length

    stops = sorted(set(cuts) | {0, 4 * width, 4 * (width + height), 4 * (2 * width + height)})
    points = [centre] + [border(t) for t in stops]
    ring = list(range(1, len(points)))
    fan = [[0, ring[i], ring[(i + 1) % len(ring)]] for i in range(len(ring))]
    picture = draw_on_screen(points, front_facing(points, fan), width, height)
    assert np.all(counts(picture) == 1)


@settings(max_examples=50, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_a_jittered_grid_covers_each_pixel_exactly_once(seed):
    rng = np.random.default_rng(seed)
    cells, size = 5, 20
    xs, ys = np.meshgrid(np.linspace(0, size, cells + 1), np.linspace(0, size, cells + 1))
    points = np.stack([xs.ravel(), ys.ravel()], axis=1)
    inner = (points > 0).all(axis=1) & (points < size).all(axis=1)
    # Move the inner vertices by up to 0.2 cell, in quarter pixels: quads stay convex.
    points[inner] += np.round(rng.uniform(-0.8, 0.8, (inner.sum(), 2)) * 4) / 4
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    quads = np.stack([i, i + 1, i + cells + 2, i + cells + 1], axis=1)
    triangles = np.concatenate([quads[:, [0, 2, 1]], quads[:, [0, 3, 2]]])
    assert np.array_equal(front_facing(points, triangles), triangles)  # none folded over
    picture = draw_on_screen(points, triangles, size, size)
    assert np.all(counts(picture) == 1)


def test_a_closed_convex_mesh_covers_its_silhouette_once_with_no_holes():
    vertices, normals, faces = sphere()
    picture = render(vertices, faces, normals=normals, size=(48, 40),
                     camera=plain_camera(distance=3.0, fov=60.0), shading="overdraw")
    drawn = counts(picture)
    assert drawn.max() == 1  # the front half only, nothing twice
    # The silhouette of a convex solid is convex: no row or column has a gap (a crack).
    for line in list(drawn) + list(drawn.T):
        covered = np.flatnonzero(line)
        if covered.size:
            assert covered[-1] - covered[0] + 1 == covered.size
    # And its size is about a sphere's: radius 1 at distance 3 with a 60 degree view.
    radius_px = 40 / 2 / math.tan(math.radians(30)) * math.tan(math.asin(1 / 3))
    assert abs(drawn.sum() / (math.pi * radius_px**2) - 1) < 0.1


def test_from_inside_a_closed_mesh_every_pixel_is_drawn_exactly_once():
    # Seen from its centre, a sphere wound inwards covers the whole view exactly once; the
    # triangles beside the camera cross the near plane and go through the clipper.
    vertices, normals, faces = sphere(inward=True)
    for target in [(0, 0, -1), (1, 0.3, 0), (0.2, -1, 0.1)]:
        camera = Camera(eye=(0, 0, 0), target=target, fov_y_deg=100, near=0.05, far=10)
        picture = render(vertices, faces, normals=-normals, camera=camera, size=(40, 30),
                         shading="overdraw")
        assert np.all(counts(picture) == 1)


def test_a_floor_through_the_near_plane_is_drawn_once_and_without_holes():
    # A floor from behind the camera to far ahead: the triangles at the camera's feet cross
    # the near plane and are clipped; the rest are not. Together they must tile the view.
    cells = 40
    xs = np.linspace(-50, 50, cells + 1)
    zs = np.linspace(20, -100, cells + 1)
    x, z = np.meshgrid(xs, zs)
    vertices = np.stack([x.ravel(), np.full(x.size, -1.0), z.ravel()], axis=1)
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    quads = np.stack([i, i + 1, i + cells + 2, i + cells + 1], axis=1)
    triangles = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])  # facing +y
    camera = Camera(eye=(0, 0, 0), target=(0, -0.2, -1), fov_y_deg=90, near=0.1, far=500)
    picture = render(vertices, triangles, normals=np.tile([0.0, 1.0, 0.0], (len(vertices), 1)),
                     camera=camera, size=(48, 32), shading="overdraw")
    drawn = counts(picture)
    assert drawn.max() == 1
    assert np.all(drawn[-10:] == 1)  # the rows near the bottom see the floor near the feet


def test_triangles_far_beyond_the_guard_band_still_tile_the_view():
    # Corners 10^8 view widths out: every vertex is outside the guard band, so both
    # triangles go through the clipper, and must still cover each pixel once.
    far = 1e8
    square = [(-far, -far, 0), (far, -far, 0), (far, far, 0), (-far, far, 0)]
    picture = render(square, [[0, 1, 2], [0, 2, 3]], camera=plain_camera(1.0, 90.0),
                     size=(24, 16), shading="overdraw")
    assert np.all(counts(picture) == 1)


# Depth.


def test_the_nearer_triangle_wins_whatever_the_order():
    # Two triangles overlapping in the middle; the red one is nearer the camera (z = 0.5).
    vertices = [(-1, -1, 0.5), (1, -1, 0.5), (0, 1, 0.5), (-1, 1, 0), (0, -1, 0), (1, 1, 0)]
    albedo = [(1, 0, 0)] * 3 + [(0, 0, 1)] * 3
    red, blue = [0, 1, 2], [3, 4, 5]
    camera = plain_camera(distance=3.0, fov=60.0)
    first = render(vertices, [red, blue], albedo=albedo, camera=camera)
    second = render(vertices, [blue, red], albedo=albedo, camera=camera)
    np.testing.assert_array_equal(first, second)
    assert first[8, 8].tolist() == [255, 0, 0]
    assert (first[..., 2] == 255).any()  # and blue shows where only it is


# Shading.


def test_gouraud_colour_is_linear_along_a_span():
    # Red runs from 0 at x = 0 to 255 at x = 51: 5 per pixel, so the pixel centred at
    # x + 1/2 gets 5 x + 2.5, rounded half up to 5 x + 3.
    width, height = 51, 4
    points = [(0, 0), (width, 0), (width, height), (0, height)]
    colours = np.array([[0, 0, 0], [255, 0, 0], [255, 0, 0], [0, 0, 0]], np.float64)
    triangles = front_facing(points, [[0, 1, 2], [0, 2, 3]])
    picture = draw_on_screen(points, triangles, width, height, colours=colours,
                             kernel=raster.rasterize_gouraud)
    expected = np.minimum(5 * np.arange(width) + 3, 255)
    for row in picture[..., 0]:
        np.testing.assert_array_equal(row, expected)


def test_lambert_lighting_follows_the_cosine_law():
    square = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    faces = [[0, 1, 2], [0, 2, 3]]

    def lit(angle):
        far = 1e6  # so far that the light's direction is the same all over the square
        light = Light(position=(far * math.sin(angle), 0.0, far * math.cos(angle)),
                      ambient=0.1, diffuse=0.5, specular=0.0)
        return int(render(square, faces, camera=plain_camera(3.0, 60.0), light=light)[8, 8, 0])

    assert lit(0.0) == round(255 * (0.1 + 0.5))  # head on: cos 0 = 1
    assert lit(math.radians(60)) == round(255 * (0.1 + 0.5 * 0.5))  # cos 60 = 1/2
    assert lit(math.radians(120)) == round(255 * 0.1)  # from behind: ambient alone


def test_the_light_stays_put_when_the_model_turns():
    vertices, normals, faces = sphere()
    light = Light(position=(10.0, 0.0, 0.0), ambient=0.0, diffuse=1.0)
    camera = plain_camera(distance=4.0, fov=45.0)
    turned = model_matrix(yaw=math.pi)  # the sphere's own +x side now faces -x
    picture = render(vertices, faces, normals=normals, light=light, camera=camera, model=turned,
                     size=(32, 32))
    row = picture[16, :, 0].astype(int)
    assert row[22] > 100 and row[9] == 0  # still lit on the right, dark on the left


def test_phong_adds_a_highlight_where_gouraud_would_not_have_one():
    # One big quad, lit from in front of its centre: every vertex sees the light at a slant,
    # but per-pixel lighting finds the highlight in the middle.
    square = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    faces = [[0, 1, 2], [0, 2, 3]]
    light = Light(position=(0.0, 0.0, 2.0), ambient=0.1, diffuse=0.5, specular=0.5,
                  shininess=50.0)
    camera = plain_camera(2.0, 60.0)
    gouraud = render(square, faces, light=light, camera=camera, shading="gouraud")
    phong = render(square, faces, light=light, camera=camera, shading="phong")
    assert int(phong[8, 8, 0]) > int(gouraud[8, 8, 0]) + 100
    assert abs(int(phong[1, 8, 0]) - int(phong[8, 1, 0])) <= 1  # symmetric about the centre


# Extreme poses.


@pytest.mark.parametrize("pose", ["behind", "straddling", "huge", "tiny", "flat", "nan"])
def test_extreme_poses_draw_sensibly_and_never_fail(pose):
    vertices, normals, faces = sphere(subdivisions=3)
    camera = plain_camera(distance=5.0, fov=90.0, near=0.5, far=1e12)
    model = {
        "behind": model_matrix(translation=(0, 0, 20)),
        # Radius 2, nearest point 4.54: the near plane (z = 4.5) cuts a hole in the middle.
        "straddling": model_matrix(scale=2.0, translation=(0, 0, 2.54)),
        "huge": model_matrix(scale=1e9, translation=(1e9, 0, -2e9)),
        "tiny": model_matrix(scale=1e-12),
        "flat": model_matrix(scale=0.0),
        "nan": np.eye(4),
    }[pose]
    if pose == "nan":
        vertices = vertices.copy()
        vertices[::7] = np.nan
    background = (10, 20, 30)
    picture = render(vertices, faces, normals=normals, camera=camera, model=model,
                     light=Light(), size=(32, 24), background=background)
    assert picture.shape == (24, 32, 3) and picture.dtype == np.uint8
    is_background = np.all(picture == background, axis=2)
    drawn = {"behind": 0, "straddling": None, "huge": None, "tiny": (0, 1), "flat": 0,
             "nan": None}[pose]
    if drawn == 0:
        assert is_background.all()
    elif drawn == (0, 1):
        assert (~is_background).sum() <= 1
    else:
        assert (~is_background).any()
    if pose == "straddling":
        assert is_background[12, 16]  # through the hole, the inside faces away: culled


# Supersampling.


def test_downsample_averages_each_block_rounding_to_nearest():
    source = np.zeros((4, 4, 3), np.uint8)
    source[:2, :2] = 255  # the top-left block is full
    source[0, 2] = 255  # a quarter of the top-right one
    source[2:, :2, 1] = [[1, 2], [3, 4]]  # mean 2.5 rounds up to 3
    target = np.empty((2, 2, 3), np.uint8)
    raster.downsample(source.reshape(-1), 2, target.reshape(-1), 2, np.empty(12, np.int32))
    np.testing.assert_array_equal(target[..., 0], [[255, 64], [0, 0]])
    assert target[1, 0, 1] == 3


def test_supersampling_averages_a_half_covered_pixel():
    # A square whose right edge x = 0.25 lies on the boundary between two fine pixels, in
    # the middle of coarse pixel 2 (of 4): that column gets half the colour.
    square = [(-2, -2, 0), (0.25, -2, 0), (0.25, 2, 0), (-2, 2, 0)]
    picture = render(square, [[0, 1, 2], [0, 2, 3]], camera=plain_camera(1.0, 90.0),
                     size=(4, 4), ssaa=2)
    np.testing.assert_array_equal(picture[:, :, 0], [[255, 255, 128, 0]] * 4)


# The renderer.


def test_render_returns_a_read_only_view_of_the_picture():
    picture = render([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 2]], size=(5, 3))
    assert picture.shape == (3, 5, 3) and picture.dtype == np.uint8
    assert not picture.flags.writeable


@pytest.mark.parametrize("options", [{"shading": "flat"}, {"ssaa": 0}, {"size": (0, 4)}])
def test_render_refuses_bad_options(options):
    with pytest.raises(ValueError):
        render([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 2]], **options)


def test_render_refuses_triangles_indexing_missing_vertices():
    with pytest.raises(ValueError):
        render([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 3]])


def test_a_mesh_passed_again_is_drawn_as_it_is_now():
    # The renderer keeps a mesh's read-only arrays between frames; a new mesh of as many
    # vertices, or a writeable array changed in place, is drawn anew.
    vertices, normals, faces = sphere(2)
    renderer = Renderer(threads=1)
    camera, light = plain_camera(3.0, 60.0), flat_light()
    albedo = np.ones((len(vertices), 3), np.float32)

    def draw(points):
        return renderer.render(points, normals, faces, albedo, np.eye(4), camera, light, 32,
                               32).copy()

    fixed = vertices.copy()
    fixed.flags.writeable = False
    first = draw(fixed)
    moved = fixed + [0.5, 0.0, 0.0]
    moved.flags.writeable = False
    assert np.count_nonzero(draw(moved) != first) > 0
    assert np.array_equal(draw(fixed), first)
    changing = vertices.copy()
    assert np.array_equal(draw(changing), first)
    changing += [0.5, 0.0, 0.0]
    assert np.array_equal(draw(changing), draw(moved))


@pytest.mark.parametrize("shininess", [1.0, 7.0, 24.0, 100.0, 511.0])
def test_a_whole_exponent_lights_as_pow_does(shininess):
    # Whole exponents are raised by squaring, others by pow: a hair above the whole
    # number, the highlight must come out the same but for rounding.
    vertices, normals, faces = sphere(3)
    camera = plain_camera(3.0, 60.0)

    def picture(exponent):
        light = Light(position=(1.0, 2.0, 4.0), ambient=0.1, diffuse=0.4, specular=0.9,
                      shininess=exponent)
        return render(vertices, faces, normals=normals, camera=camera, light=light,
                      size=(64, 64), shading="phong").astype(int)

    whole, fraction = picture(shininess), picture(shininess * (1 + 1e-6))
    assert np.count_nonzero(whole > 250) > 4  # a highlight
    assert np.abs(whole - fraction).max() <= 1
