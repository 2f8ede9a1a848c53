"""Shading in perspective: attributes interpolated as a GPU does, so close-ups show no drift.

Two references, neither of which relies on how the rasterizer interpolates: a receding floor
whose colour at each pixel is worked out by hand (cast the pixel's ray onto the floor, read
the colour where it lands), and close-ups drawn again from the same mesh with every
triangle cut 4 x 4 finer, towards the limit in which any interpolation along a triangle
converges on the perspective-correct picture.
"""

import math

import numpy as np
import pytest

from biceps.engine.appearance import scene_mesh
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.framing import outline, view_camera, zoomed_light
from biceps.engine.mesh import cylinder_mesh
from biceps.engine.render import Renderer
from biceps.engine.scene import Scene
from biceps.engine.transforms import Camera, Light

SIZE = (160, 120)
FOV = 60.0


def floor_picture(shading: str) -> tuple[np.ndarray, np.ndarray]:
    """A floor 1 cm below the eye, from 1 to 40 cm ahead, black at its near edge and white
    at its far one, lit by the ambient term alone: the picture, and each pixel's exact
    colour (NaN off the floor)."""
    near, far, half_width = -1.0, -40.0, 30.0
    vertices = np.array([[-half_width, -1.0, near], [half_width, -1.0, near],
                         [half_width, -1.0, far], [-half_width, -1.0, far]])
    albedo = np.array([[0.0] * 3, [0.0] * 3, [1.0] * 3, [1.0] * 3], np.float32)
    normals = np.tile([0.0, 1.0, 0.0], (4, 1))
    camera = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=FOV, near=0.1,
                    far=100.0)
    light = Light(position=(0.0, 10.0, 0.0), ambient=1.0, diffuse=0.0, specular=0.0)
    width, height = SIZE
    picture = Renderer().render(vertices, normals, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                                albedo, np.eye(4), camera, light, width, height,
                                shading=shading)
    # Each pixel centre's ray, (x, y, -1) in eye space, meets the floor y = -1 at depth 1 / -y.
    tan = math.tan(math.radians(FOV) / 2)
    x = ((np.arange(width) + 0.5) / width * 2 - 1) * tan * width / height
    y = (1 - (np.arange(height) + 0.5) / height * 2) * tan
    depth = np.where(y < 0, -1.0 / np.minimum(y, -1e-9), np.inf)[:, None] * np.ones(width)
    on_floor = (depth <= -far) & (np.abs(x[None, :] * depth) <= half_width)
    exact = np.where(on_floor, 255.0 * (depth - -near) / (near - far), np.nan)
    return picture[..., 0].astype(float), exact


@pytest.mark.parametrize("shading", ["gouraud", "phong"])
def test_a_receding_floor_shades_as_worked_out_by_hand(shading):
    picture, exact = floor_picture(shading)
    drawn = ~np.isnan(exact)
    # Well inside the floor (its edges may be a pixel either way), within a level.
    inside = drawn & np.roll(drawn, 1, 0) & np.roll(drawn, -1, 0) & np.roll(drawn, 1, 1) \
        & np.roll(drawn, -1, 1)
    assert inside.sum() > 1000
    assert np.abs(picture[inside] - exact[inside]).max() <= 1.0


def subdivided(vertices, normals, albedo, triangles, cuts: int):
    """Every triangle cut into ``cuts``^2, the new vertices linear in space (their normals
    renormalised, as the renderer renormalises every normal)."""
    steps = [(i, j) for i in range(cuts + 1) for j in range(cuts + 1 - i)]
    index = {step: k for k, step in enumerate(steps)}
    weights = np.array([[cuts - i - j, i, j] for i, j in steps]) / cuts
    small = []
    for i in range(cuts):
        for j in range(cuts - i):
            small.append((index[i, j], index[i + 1, j], index[i, j + 1]))
            if i + j < cuts - 1:
                small.append((index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]))
    small = np.array(small)

    def spread(values):
        return np.einsum("kc,mcd->mkd", weights, values[triangles]).reshape(-1, 3)

    fine_normals = spread(normals)
    fine_normals /= np.linalg.norm(fine_normals, axis=1, keepdims=True)
    offsets = len(steps) * np.arange(len(triangles))[:, None, None]
    return (spread(vertices), fine_normals, spread(albedo.astype(np.float64)).astype(np.float32),
            (small[None] + offsets).reshape(-1, 3).astype(np.int32))


def assert_matches_a_finely_cut_reference(mesh, albedo, model, camera, light, shading):
    width, height = 480, 270

    def draw(vertices, normals, colours, triangles):
        return Renderer().render(vertices, normals, triangles, colours, model, camera, light,
                                 width, height, shading=shading).astype(int)

    ours = draw(mesh.vertices, mesh.normals, albedo, mesh.triangles)
    reference = draw(*subdivided(mesh.vertices, mesh.normals, albedo, mesh.triangles, 4))
    # Compare away from silhouettes, where the finer mesh's snapped vertices may move an
    # edge by a pixel; along a line where two parts cross (muscle into bone) they may also
    # change which is nearer, for the odd pixel.
    covered = np.any(ours != 0, axis=2) & np.any(reference != 0, axis=2)
    inside = covered.copy()
    for axis in (0, 1):
        for shift in (1, -1):
            inside &= np.roll(covered, shift, axis)
    assert inside.sum() > 5000
    difference = np.abs(ours - reference).max(axis=2)[inside]
    assert np.mean(difference > 3) <= 0.0005
    assert np.percentile(difference, 99.5) <= 1


@pytest.mark.parametrize("scale", [3.0, 8.0])
def test_the_issues_close_up_matches_a_finely_cut_reference(scale):
    # snapshot --flexion 100 --yaw 80 --pitch -10 --scale 8 --shading phong, and at 3x.
    # (The bones' fine tessellation alone keeps these within 3 levels; the rod below is
    # where interpolating on the screen fails.)
    scene = Scene.of(load_config(DEFAULT_CONFIG))
    scene = (scene.with_arm(scene.arm.at_flexion(100.0))
             .with_view(yaw=80.0, pitch=-10.0, scale=scale).with_render(shading="phong"))
    mesh, albedo, _ = scene_mesh(scene.arm, scene.render)
    camera, model = view_camera(scene.view, outline(mesh.vertices), 480 / 270)
    assert_matches_a_finely_cut_reference(mesh, albedo, model, camera,
                                          zoomed_light(scene.light, scale, camera), "phong")


@pytest.mark.parametrize("shading", ["gouraud", "phong"])
def test_a_long_rod_seen_along_its_length_matches_a_finely_cut_reference(shading):
    # The forearm of old: one frustum 25 cm long, here from behind the eye (the near plane
    # cuts it) to 28 cm ahead, 1.5 cm below: on the screen its colour drifts by tens of
    # levels. Gouraud's colours are lit at the vertices, so the light is ambient only there.
    rod = cylinder_mesh([0.0, -1.5, 2.0], [0.0, -1.5, -28.0], 0.8, segments=32, caps="flat")
    albedo = np.column_stack([np.linspace(0.2, 1.0, len(rod.vertices))] * 3).astype(np.float32)
    camera = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, -0.3, -1.0), fov_y_deg=50.0, near=0.5,
                    far=100.0)
    light = Light(position=(20.0, 30.0, 10.0), specular=0.5) if shading == "phong" else \
        Light(ambient=1.0, diffuse=0.0, specular=0.0)
    assert_matches_a_finely_cut_reference(rod, albedo, np.eye(4), camera, light, shading)


@pytest.mark.parametrize("seed", range(5))
def test_the_outline_holds_the_farthest_point_along_each_direction(seed):
    points = np.random.default_rng(seed).normal(size=(4000, 3)) * [30.0, 10.0, 5.0]
    kept = outline(points, directions=64, stride=1)
    index = np.arange(64) + 0.5
    height = 1.0 - 2.0 * index / 64
    turn = np.pi * (1.0 + 5.0**0.5) * index
    ring = np.sqrt(1.0 - height**2)
    lattice = np.column_stack([ring * np.cos(turn), height, ring * np.sin(turn)])
    centre = (points.min(axis=0) + points.max(axis=0)) / 2.0
    farthest = points[np.argmax((points - centre) @ lattice.T, axis=0)]  # every pair, plainly
    assert sorted(map(tuple, kept)) == sorted(set(map(tuple, farthest)))
