"""Transforms and camera: known points land where the conventions say."""

import math

import numpy as np
import pytest

from biceps.engine.transforms import (
    Camera,
    frame_camera,
    look_at,
    model_matrix,
    normal_matrix,
    perspective,
    rotation_x,
    rotation_y,
    rotation_z,
    transform_points,
    viewport,
)


def apply(matrix, *points):
    return transform_points(matrix, np.array(points, dtype=np.float64))


def test_yaw_turns_x_towards_minus_z():
    # Right-handed, about +y: z goes to x, so x goes to -z.
    np.testing.assert_allclose(apply(rotation_y(math.pi / 2), (1, 0, 0)), [[0, 0, -1]], atol=1e-15)


def test_pitch_turns_y_towards_z():
    np.testing.assert_allclose(apply(rotation_x(math.pi / 2), (0, 1, 0)), [[0, 0, 1]], atol=1e-15)


def test_roll_turns_x_towards_y():
    np.testing.assert_allclose(apply(rotation_z(math.pi / 2), (1, 0, 0)), [[0, 1, 0]], atol=1e-15)


def test_model_matrix_rotates_and_scales_about_the_pivot_then_translates():
    pivot, shift = (1.0, 2.0, 3.0), (10.0, 0.0, 0.0)
    matrix = model_matrix(yaw=math.pi / 2, scale=2.0, translation=shift, pivot=pivot)
    # The pivot only moves by the translation; a point 1 along x from it ends up 2 along -z.
    np.testing.assert_allclose(apply(matrix, pivot, (2, 2, 3)),
                               [[11, 2, 3], [11, 2, 1]], atol=1e-12)


def test_model_matrix_applies_roll_then_pitch_then_yaw():
    matrix = model_matrix(yaw=0.3, pitch=0.2, roll=0.1)
    np.testing.assert_allclose(matrix, rotation_y(0.3) @ rotation_x(0.2) @ rotation_z(0.1))


def test_normal_matrix_keeps_normals_perpendicular_under_non_uniform_scale():
    matrix = model_matrix(scale=(4.0, 1.0, 1.0))
    tangent = matrix[:3, :3] @ np.array([1.0, -1.0, 0.0])  # along the surface x + y = 0
    normal = normal_matrix(matrix) @ np.array([1.0, 1.0, 0.0])
    assert abs(tangent @ normal) < 1e-12


def test_look_at_puts_the_eye_at_the_origin_and_the_target_down_minus_z():
    view = look_at(eye=(1, 2, 10), target=(1, 2, 0), up=(0, 1, 0))
    np.testing.assert_allclose(apply(view, (1, 2, 10), (1, 2, 0), (1, 3, 10), (2, 2, 10)),
                               [[0, 0, 0], [0, 0, -10], [0, 1, 0], [1, 0, 0]], atol=1e-12)


def test_look_at_from_the_side_keeps_up_up():
    view = look_at(eye=(10, 0, 0), target=(0, 0, 0), up=(0, 1, 0))
    # Looking down -x, the viewer's right is forward x up = (-1, 0, 0) x (0, 1, 0) = -z.
    np.testing.assert_allclose(apply(view, (0, 0, 0), (10, 1, 0), (10, 0, -1)),
                               [[0, 0, -10], [0, 1, 0], [1, 0, 0]], atol=1e-12)


def test_perspective_maps_the_frustum_onto_the_ndc_cube():
    near, far, fov, aspect = 2.0, 50.0, math.radians(90.0), 2.0
    projection = perspective(fov, aspect, near, far)
    # At distance d the half-height of the view is d tan(45) = d, the half-width 2 d.
    np.testing.assert_allclose(
        apply(projection, (0, 0, -near), (0, 0, -far), (0, near, -near), (2 * far, -far, -far)),
        [[0, 0, -1], [0, 0, 1], [0, 1, -1], [1, -1, 1]], atol=1e-12)


def test_perspective_w_is_the_distance_in_front_of_the_eye():
    projection = perspective(1.0, 1.0, 1.0, 10.0)
    clip = projection @ np.array([0.3, -0.2, -7.0, 1.0])
    assert clip[3] == pytest.approx(7.0)


def test_viewport_maps_ndc_corners_to_the_screen_with_y_down_and_depth_reversed():
    screen = apply(viewport(640, 480), (-1, 1, -1), (1, -1, 1), (0, 0, 0))
    np.testing.assert_allclose(screen, [[0, 0, 1], [640, 480, 0], [320, 240, 0.5]])


def test_camera_matrices_compose_to_the_frustum():
    camera = Camera(eye=(0, 0, 10), target=(0, 0, 0), fov_y_deg=90, near=1, far=100)
    clip_from_world = camera.projection_matrix(1.0) @ camera.view_matrix()
    np.testing.assert_allclose(apply(clip_from_world, (0, 1, 9), (0, 0, -90)),
                               [[0, 1, -1], [0, 0, 1]], atol=1e-12)


@pytest.mark.parametrize("aspect", [0.5, 1.0, 16 / 9])
def test_frame_camera_fits_the_box_and_fills_the_view(aspect):
    low, high = np.array([-3.0, -1.0, -2.0]), np.array([5.0, 7.0, 1.0])
    camera = frame_camera(low, high, aspect, fov_y_deg=40.0, fill=0.9)
    corners = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                        for z in (low[2], high[2])])
    ndc = apply(camera.projection_matrix(aspect) @ camera.view_matrix(), *corners)
    assert np.all(np.abs(ndc[:, :2]) <= 0.9 + 1e-9)  # inside, with the margin asked for
    assert np.all((ndc[:, 2] > -1) & (ndc[:, 2] < 1))  # between the near and far planes
    assert np.isclose(np.abs(ndc[:, :2]).max(), 0.9)  # and as large as that allows
    assert camera.eye[2] > high[2] and camera.target == tuple((low + high) / 2)
