"""Bands: a frame drawn by several threads is the frame drawn by one, byte for byte."""

import numpy as np
import pytest

from biceps.engine import raster
from biceps.engine.appearance import scene_mesh
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.errors import SettingError
from biceps.engine.framing import outline, view_camera, zoomed_light
from biceps.engine.raster.bands import Bands, default_threads
from biceps.engine.render import Renderer
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import supersampling
from biceps.engine.settings import THREADS_VARIABLE
from biceps.engine.transforms import Camera, Light

SCENES = {
    "gouraud": {},
    "phong": {"render": {"shading": "phong"}},
    "overdraw": {"render": {"shading": "overdraw"}},
    "supersampled phong": {"render": {"shading": "phong", "ssaa": 3}},
    "close-up, clipped": {"view": {"scale": 9.0, "yaw": 40.0}},
    "phong close-up, clipped": {"render": {"shading": "phong"},
                                "view": {"scale": 9.0, "yaw": 40.0}},
}
WIDTH, HEIGHT = 401, 271
"""Odd, so that the bands are of different heights; more than `bands.SMALL_PICTURE`
pixels even drawn once a pixel, so that the picture is drawn in bands."""


def frame(scene: Scene, renderer: Renderer, width: int, height: int,
          background=(0, 0, 0)) -> np.ndarray:
    """The scene as `SceneRenderer` draws it, by ``renderer``: a copy."""
    mesh, albedo, _ = scene_mesh(scene.arm, scene.render)
    camera, model = view_camera(scene.view, outline(mesh.vertices), width / height)
    light = zoomed_light(scene.light, scene.view.scale, camera)
    return renderer.render(mesh.vertices, mesh.normals, mesh.triangles, albedo, model, camera,
                           light, width, height, shading=scene.render.shading,
                           ssaa=supersampling(scene.render, height),
                           background=background).copy()


@pytest.mark.parametrize("threads", [2, 3, 7])
@pytest.mark.parametrize("name", list(SCENES))
def test_several_threads_draw_the_picture_one_thread_draws(name, threads):
    changes = SCENES[name]
    scene = Scene.of(load_config(DEFAULT_CONFIG))
    scene = scene.with_render(**changes.get("render", {})).with_view(**changes.get("view", {}))
    alone, together = Renderer(threads=1), Renderer(threads=threads)
    expected = frame(scene, alone, WIDTH, HEIGHT)
    drawn = frame(scene, together, WIDTH, HEIGHT)
    assert len(together._bands.rows) == threads  # it was drawn in bands
    assert np.count_nonzero(expected) > 1000  # something drawn (on black)
    np.testing.assert_array_equal(drawn, expected)


@pytest.mark.parametrize("name", ["gouraud", "phong", "phong close-up, clipped"])
def test_threads_sharing_the_vertices_draw_the_picture_one_thread_draws(monkeypatch, name):
    monkeypatch.setattr("biceps.engine.render.PARALLEL_VERTICES", 1)  # any mesh is shared
    changes = SCENES[name]
    scene = Scene.of(load_config(DEFAULT_CONFIG))
    scene = scene.with_render(**changes.get("render", {})).with_view(**changes.get("view", {}))
    expected = frame(scene, Renderer(threads=1), WIDTH, HEIGHT)
    drawn = frame(scene, Renderer(threads=3), WIDTH, HEIGHT)
    assert np.count_nonzero(expected) > 1000
    np.testing.assert_array_equal(drawn, expected)


def test_a_renderer_that_drew_another_view_draws_what_a_fresh_one_draws():
    # It keeps the last camera's matrices and the last model's normals: a new view, a
    # light moved or the model turned must not draw with the old ones.
    base = Scene.of(load_config(DEFAULT_CONFIG))
    views = [base, base.with_view(scale=9.0, yaw=40.0), base.with_view(yaw=10.0),
             base.with_light(position=(-80.0, 20.0, 60.0)), base]
    renderer = Renderer(threads=1)
    drawn = [frame(scene, renderer, 160, 96) for scene in views]
    for scene, picture in zip(views, drawn):
        np.testing.assert_array_equal(picture, frame(scene, Renderer(threads=1), 160, 96))
    assert not np.array_equal(drawn[0], drawn[1])


@pytest.mark.parametrize("threads", [1, 2])
def test_a_frame_leaves_nothing_of_the_last_behind(threads):
    # Each frame clears only what the last drew (draw.clear_drawn): a close-up, then the arm
    # small in a corner of the picture, a new background, a new size, a light moved.
    base = Scene.of(load_config(DEFAULT_CONFIG))
    close_up = base.with_view(scale=9.0, yaw=40.0)
    small = base.with_view(scale=0.4, offset=(30.0, -20.0, 0.0))
    frames = [(close_up, (18, 22, 28), WIDTH), (small, (18, 22, 28), WIDTH),
              (close_up, (18, 22, 28), WIDTH), (close_up, (200, 0, 90), WIDTH),
              (small, (200, 0, 90), WIDTH - 40), (base.with_light(position=(-80.0, 20.0, 60.0)),
                                                   (200, 0, 90), WIDTH - 40)]
    renderer = Renderer(threads=threads)
    for scene, background, width in frames:
        drawn = frame(scene, renderer, width, HEIGHT, background)
        fresh = frame(scene, Renderer(threads=threads), width, HEIGHT, background)
        np.testing.assert_array_equal(drawn, fresh)


def test_a_band_holds_exactly_the_spans_of_its_rows():
    triangle = (5 * 256 + 17, 3 * 256 + 5, 2 * 256 + 99, 40 * 256 + 200, 37 * 256 + 3, 29 * 256)
    whole_lo, whole_hi = np.zeros(48, np.int64), np.zeros(48, np.int64)
    first, end = raster.triangle_spans(*triangle, 40, 48, whole_lo, whole_hi)
    for start, stop in [(0, 10), (10, 11), (11, 30), (30, 48)]:
        lo, hi = np.zeros(48, np.int64), np.zeros(48, np.int64)
        band_first, band_end = raster.band_spans(*triangle, 40, start, stop, lo, hi)
        assert (band_first, band_end) == (max(first, start), min(end, stop))
        rows = slice(band_first, band_end)
        np.testing.assert_array_equal(lo[rows], whole_lo[rows])
        np.testing.assert_array_equal(hi[rows], whole_hi[rows])


def test_phong_lights_a_triangle_larger_than_its_list_of_pixels():
    # A square filling a 200x150 picture: 30,000 pixels against a list of 4,096, so the
    # list is lit many times over within each triangle. Ambient light only: every pixel
    # is its albedo, white.
    square = np.array([(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)], np.float64)
    camera = Camera(eye=(0.0, 0.0, 1.0), target=(0.0, 0.0, 0.0), fov_y_deg=90.0, near=0.1,
                    far=10.0)
    light = Light(position=(0.0, 0.0, 10.0), ambient=1.0, diffuse=0.0, specular=0.0)
    picture = Renderer(threads=1).render(
        square, np.tile([0.0, 0.0, 1.0], (4, 1)), np.array([[0, 1, 2], [0, 2, 3]], np.int32),
        np.ones((4, 3), np.float32), np.eye(4), camera, light, 200, 150, shading="phong")
    assert np.all(picture == 255)


@pytest.mark.parametrize(("value", "expected"), [("3", 3), (" 1 ", 1), ("", 5)])
def test_the_thread_count_comes_from_the_environment_or_the_cores(monkeypatch, value,
                                                                   expected):
    monkeypatch.setenv(THREADS_VARIABLE, value)
    monkeypatch.setattr("os.sched_getaffinity", lambda _: {0, 1, 2, 3, 4}, raising=False)
    monkeypatch.setattr("os.cpu_count", lambda: 5)
    assert default_threads() == expected


@pytest.mark.parametrize("value", ["0", "-2", "many", "1.5", "2e1"])
def test_a_thread_count_that_is_no_whole_number_from_1_is_refused_in_words(monkeypatch,
                                                                             value):
    monkeypatch.setenv(THREADS_VARIABLE, value)
    with pytest.raises(SettingError, match=f"BICEPS_THREADS is '{value}': it takes a whole"):
        default_threads()


@pytest.mark.parametrize("threads", [0, -1, 1.5, "2"])
def test_a_renderer_refuses_a_thread_count_that_is_not_a_positive_integer(threads):
    with pytest.raises(ValueError, match="threads"):
        Bands(threads)


def test_a_camera_given_arrays_is_drawn_and_its_move_seen():
    # The renderer compares each camera with the last one; arrays compare element-wise.
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    normals = np.array([[0.0, 0.0, 1.0]] * 3)
    triangle = np.array([[0, 1, 2]], np.int32)
    albedo = np.ones((3, 3), np.float32)
    renderer = Renderer(threads=1)

    def drawn(eye):
        return renderer.render(vertices, normals, triangle, albedo, np.eye(4),
                               Camera(eye=eye), Light(), 32, 32).copy()

    near = drawn((0.0, 0.0, 5.0))
    np.testing.assert_array_equal(drawn(np.array([0.0, 0.0, 5.0])), near)
    assert np.count_nonzero(drawn(np.array([0.0, 0.0, 6.0]))) < np.count_nonzero(near)
