"""The app's picture marks the pick: the selected muscle lighter among others, its picked
node ringed; a picture of the model alone (a snapshot, an export) marks nothing."""

from dataclasses import replace

import numpy as np
import pytest

from biceps.configs import FOLDER
from biceps.engine import scene_renderer
from biceps.engine.anatomy import node_places
from biceps.engine.appearance import RING_COLOUR, marked_albedo, scene_mesh
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer


@pytest.fixture(scope="module")
def elbow() -> Scene:
    return Scene.of(load_config(FOLDER / "elbow.toml"))


def _marked(scene: Scene):
    mesh, albedo, spans = scene_mesh(scene.arm, scene.render, scene.hidden)
    return mesh, albedo, spans, marked_albedo(scene, mesh, albedo, spans)


@pytest.mark.parametrize("selected", range(6))
def test_the_picked_muscle_alone_is_lighter_among_others(elbow, selected):
    scene = replace(elbow, marked=True, selected=selected)
    _, albedo, spans, marked = _marked(scene)
    start, end = spans[scene.arm.names[selected]]
    lighter = marked[start:end] - albedo[start:end]
    assert (lighter > 0.0).all() or np.allclose(albedo[start:end], 1.0)
    outside = np.ones(len(albedo), bool)
    outside[start:end] = False
    assert np.array_equal(marked[outside], albedo[outside])
    assert marked.max() <= 1.0


def test_the_picked_node_is_ringed_in_yellow_fading_within_half_a_node(elbow):
    scene = replace(elbow, marked=True, selected=0, picked_node=7)
    mesh, _, spans, marked = _marked(scene)
    start, end = spans["BIClong"]
    arm = scene.arm
    places = node_places(arm.muscles[0], arm.paths[0], arm.flexion, mesh.vertices[start:end])
    on_ring = np.abs(places - 7) < 0.05
    assert on_ring.sum() >= 8  # a whole ring of vertices
    assert np.allclose(marked[start:end][on_ring], RING_COLOUR, atol=0.02)
    far = np.abs(places - 7) > 0.5
    assert not np.isclose(marked[start:end][far], RING_COLOUR, atol=0.05).all(axis=1).any()


def test_one_muscle_is_not_lightened_and_a_hidden_pick_marks_nothing(elbow):
    single = replace(Scene.of(load_config(DEFAULT_CONFIG)), marked=True)
    _, albedo, _, marked = _marked(single)
    assert np.array_equal(marked, albedo)  # no node picked, nothing else to tell it from
    hidden = replace(elbow, marked=True, selected=1, picked_node=3,
                     hidden=frozenset({elbow.arm.names[1]}))
    _, albedo, _, marked = _marked(hidden)
    assert np.array_equal(marked, albedo)


def test_a_node_past_the_muscle_s_last_marks_no_ring(elbow):
    # The table may still show the last muscle's row for a moment after t picks another.
    scene = replace(elbow, marked=True, selected=1, picked_node=10_000)
    _, albedo, spans, marked = _marked(scene)
    lightened = replace(scene, picked_node=None)
    assert np.array_equal(marked, _marked(lightened)[3])


def test_the_renderer_draws_the_marks_only_for_a_marked_scene(elbow, monkeypatch):
    built = []
    monkeypatch.setattr(scene_renderer, "scene_mesh",
                        lambda *args: built.append(args) or scene_mesh(*args))
    renderer = SceneRenderer()
    plain = renderer.render(elbow, 160, 120).copy()
    marked = replace(elbow, marked=True, picked_node=7)
    assert not np.array_equal(renderer.render(marked, 160, 120), plain)
    assert np.array_equal(renderer.render(marked.unmarked(), 160, 120), plain)
    # The ring follows the picked node without the mesh built again.
    moved = renderer.render(marked.with_picked_node(3), 160, 120).copy()
    assert not np.array_equal(moved, plain)
    assert len(built) == 1
