"""The picture fills the view: the arm large, centred and whole in every pose, and zoom
about the picture's centre."""

from dataclasses import replace

import numpy as np
import pytest

from biceps.engine.config import DEFAULT_CONFIG, load_config, rgb
from framing import arm_mask, assert_fills_the_view
from biceps.engine.scene import Scene, SceneRenderer, scene_mesh, view_camera
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
