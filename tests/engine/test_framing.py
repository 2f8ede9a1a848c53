"""The picture fills the view: the arm large, centred and whole in every pose, and zoom
about the picture's centre."""

import math
from dataclasses import replace

import numpy as np
import pytest

from biceps.engine.config import DEFAULT_CONFIG, load_config, rgb
from framing import arm_mask, assert_fills_the_view
from biceps.engine.appearance import scene_mesh
from biceps.engine.framing import fit_points, view_camera
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.engine.transforms import transform_points


@pytest.fixture(scope="module")
def default_scene() -> Scene:
    return Scene.of(load_config(DEFAULT_CONFIG))


@pytest.mark.parametrize("flexion", [0.0, 60.0, 130.0])
def test_a_default_snapshot_fills_the_view_in_every_pose(default_scene, flexion):
    scene = default_scene.with_arm(default_scene.arm.at_flexion(flexion))
    background = rgb(scene.render.background)
    assert_fills_the_view(arm_mask(SceneRenderer().render(scene, 1920, 1080), background))


@pytest.mark.parametrize("yaw, pitch", [(-90.0, 0.0), (90.0, 0.0), (180.0, 20.0), (0.0, 80.0)])
def test_from_any_side_the_arm_is_whole_and_centred(default_scene, yaw, pitch):
    scene = default_scene.with_arm(default_scene.arm.at_flexion(60.0)).with_view(yaw=yaw,
                                                                                  pitch=pitch)
    mask = arm_mask(SceneRenderer().render(scene, 640, 360), rgb(scene.render.background))
    assert_fills_the_view(mask)


def test_zoom_grows_the_picture_about_its_centre_wherever_the_model_was_moved(default_scene):
    moved = default_scene.with_view(offset=(4.0, -3.0, 0.0))
    vertices = scene_mesh(moved.arm, moved.render)[0].vertices
    camera, model = view_camera(moved.view, vertices, 16 / 9)
    # The model's point at the picture's centre, the camera's target, stays there.
    centre = transform_points(np.linalg.inv(model), [camera.target])
    for scale in (1.5, 3.0, 8.0):
        zoomed, zoomed_model = view_camera(replace(moved.view, scale=scale), vertices, 16 / 9)
        assert (zoomed.eye, zoomed.target) == (camera.eye, camera.target)
        np.testing.assert_allclose(transform_points(zoomed_model, centre)[0], camera.target,
                                   atol=1e-9)


def _aimed_in_numpy(points, aspect, fov_y_deg, fill):
    """fit_points' eye and aim as numpy gave them before its kernel: four moves of the aim
    by the picture's offset, then the least eye z."""
    low, high = points.min(axis=0), points.max(axis=0)
    aim = (low + high) / 2.0
    tan_y = math.tan(math.radians(fov_y_deg) / 2.0) * fill
    tans = np.array([tan_y * aspect, tan_y])
    for _ in range(4):
        off = points[:, :2] - aim[:2]
        eye_z = float(np.max(points[:, 2] + np.max(np.abs(off) / tans, axis=1)))
        seen = off / (eye_z - points[:, 2:3])
        aim[:2] += (seen.min(axis=0) + seen.max(axis=0)) / 2.0 * (eye_z - aim[2])
    off = points[:, :2] - aim[:2]
    eye_z = float(np.max(points[:, 2] + np.max(np.abs(off) / tans, axis=1)))
    return (float(aim[0]), float(aim[1]), eye_z), tuple(float(c) for c in aim)


@pytest.mark.parametrize("seed", range(20))
def test_fit_points_aims_to_the_last_bit_as_numpy_did(seed):
    # The framing of every picture: a kernel moved it out of numpy, and the pictures must
    # stay the same.
    rng = np.random.default_rng(seed)
    points = (rng.normal(size=(int(rng.integers(2, 300)), 3)) * rng.uniform(0.1, 20, 3)
              + rng.normal(size=3) * 5)
    aspect, fov = float(rng.uniform(0.3, 3.0)), float(rng.uniform(10.0, 80.0))
    camera = fit_points(points, aspect, fov, 0.9)
    assert (camera.eye, camera.target) == _aimed_in_numpy(points, aspect, fov, 0.9)


@pytest.mark.parametrize("aspect", [0.5, 1.0, 16 / 9])
def test_fit_points_keeps_every_point_in_view_centred_and_as_large_as_it_may(aspect):
    rng = np.random.default_rng(3)
    points = rng.normal(size=(200, 3)) * [4.0, 9.0, 3.0] + [2.0, -5.0, 1.0]
    camera = fit_points(points, aspect, fov_y_deg=40.0, fill=0.9)
    ndc = transform_points(camera.projection_matrix(aspect) @ camera.view_matrix(), points)
    assert np.all(np.abs(ndc[:, :2]) <= 0.9 + 1e-9)  # every point inside the margin
    assert np.all((ndc[:, 2] > -1) & (ndc[:, 2] < 1))  # between the near and far planes
    assert np.isclose(np.abs(ndc[:, :2]).max(), 0.9)  # and as large as that allows
    # Centred: on the tighter axis the picture reaches both edges' margins alike.
    tighter = np.argmax(np.abs(ndc[:, :2]).max(axis=0))
    assert ndc[:, tighter].min() == pytest.approx(-ndc[:, tighter].max(), abs=0.01)
