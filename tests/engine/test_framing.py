"""The picture fills the view: the arm large, centred and whole in every pose, and zoom
about the picture's centre."""

from dataclasses import replace

import numpy as np
import pytest

from biceps.engine.config import DEFAULT_CONFIG, load_config, rgb
from biceps.engine.scene import Scene, SceneRenderer, scene_mesh, view_camera
from biceps.engine.transforms import transform_points


def arm_mask(picture: np.ndarray, scene: Scene) -> np.ndarray:
    """(h, w) bool: the pixels that are not background."""
    return np.any(picture != rgb(scene.render.background), axis=2)


def box(mask: np.ndarray) -> tuple[int, int, int, int]:
    """The first and last row and column of ``mask``'s true pixels."""
    rows, columns = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return rows[0], rows[-1], columns[0], columns[-1]


def assert_fills_the_view(mask: np.ndarray) -> None:
    """The issue's framing: the arm's box spans at least 70 % of the width or the height,
    its centre lies within 10 % of the picture's, and nothing touches the edges."""
    height, width = mask.shape
    top, bottom, left, right = box(mask)
    assert max((bottom - top + 1) / height, (right - left + 1) / width) >= 0.7
    assert abs((top + bottom + 1) / 2 - height / 2) <= 0.1 * height
    assert abs((left + right + 1) / 2 - width / 2) <= 0.1 * width
    assert not (mask[0].any() or mask[-1].any() or mask[:, 0].any() or mask[:, -1].any())


@pytest.fixture(scope="module")
def default_scene() -> Scene:
    return Scene.of(load_config(DEFAULT_CONFIG))


@pytest.mark.parametrize("flexion", [0.0, 60.0, 130.0])
def test_a_default_snapshot_fills_the_view_in_every_pose(default_scene, flexion):
    scene = default_scene.with_arm(default_scene.arm.at_flexion(flexion))
    assert_fills_the_view(arm_mask(SceneRenderer().render(scene, 1920, 1080), scene))


@pytest.mark.parametrize("yaw, pitch", [(-90.0, 0.0), (90.0, 0.0), (180.0, 20.0), (0.0, 80.0)])
def test_from_any_side_the_arm_is_whole_and_centred(default_scene, yaw, pitch):
    scene = default_scene.with_arm(default_scene.arm.at_flexion(60.0)).with_view(yaw=yaw,
                                                                                  pitch=pitch)
    mask = arm_mask(SceneRenderer().render(scene, 640, 360), scene)
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
