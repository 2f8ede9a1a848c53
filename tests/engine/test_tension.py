"""An active muscle's tension shape: the belly thicker, its ends thinner, at the same length
and exactly the same volume."""

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from biceps.configs import FOLDER
from biceps.engine.anatomy import arm_parts
from biceps.engine.appearance import (activation_colour, companion_segments, marked_albedo,
                                      scene_mesh)
from biceps.engine.config import load_config
from biceps.engine.muscle import volume
from biceps.engine.scene import Scene
from biceps.engine.tension import tensed, tensed_arm

ELBOW = load_config(FOLDER / "elbow.toml")
BICEPS = load_config(FOLDER / "biceps.toml")


@settings(max_examples=150, deadline=None)
@given(flexion=st.floats(0.0, 130.0), activation=st.floats(0.0, 1.0),
       which=st.integers(0, 5))
def test_the_volume_is_kept_to_1e_12_at_every_activation_and_pose(flexion, activation, which):
    muscle = ELBOW.arm.at_flexion(flexion).muscles[which]
    shaped = tensed(muscle, activation)
    assert shaped.length == muscle.length
    kept = volume(shaped.radii, shaped.length, shaped.volume_mode)
    assert abs(kept - muscle.reference_volume) <= 1e-12 * muscle.reference_volume
    assert shaped.volume_error <= 1e-12


@pytest.mark.parametrize("config", [ELBOW, BICEPS], ids=["elbow", "biceps"])
def test_the_belly_thickens_its_ends_thin_and_the_tendons_stay(config):
    for muscle in config.arm.muscles:
        shaped = tensed(muscle, 1.0)
        change = shaped.radii - muscle.radii
        thickest = int(np.argmax(muscle.growth))
        assert change[thickest] > 0.05 * muscle.max_radius
        assert (shaped.radii / muscle.radii).min() < 0.85  # the belly's ends 15 % thinner
        assert np.all(change[muscle.growth == 0.0] == 0.0)
        assert np.all(shaped.radii > 0.0)


def test_more_activation_more_tension_and_none_the_shape_as_it_is():
    muscle = ELBOW.arm.muscle
    assert tensed(muscle, 0.0) is muscle
    peaks = [tensed(muscle, a).max_radius for a in (0.1, 0.5, 1.0)]
    assert muscle.max_radius < peaks[0] < peaks[1] < peaks[2]


def test_the_arm_tenses_each_muscle_by_its_own_activation():
    arm = ELBOW.arm
    activations = (1.0, 0.0, 0.5, 0.0, 0.0, 0.2)
    shaped = tensed_arm(arm, activations)
    for muscle, before, activation in zip(shaped.muscles, arm.muscles, activations):
        assert np.array_equal(muscle.radii, tensed(before, activation).radii)
    assert shaped.skeleton == arm.skeleton and shaped.names == arm.names
    assert tensed_arm(arm, ()) is arm


def test_colour_by_activation_runs_from_neutral_to_red_through_amber():
    rest, half, full = (activation_colour(a) for a in (0.0, 0.5, 1.0))
    assert full[0] > 0.8 and full[1] < 0.1  # red
    assert half[0] > 0.9 and half[1] > 0.6 and half[2] < 0.2  # amber
    assert np.ptp(rest) < 0.1  # a pale neutral
    scene = Scene.of(ELBOW).with_render(colour_by="activation").with_activations(
        (1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    mesh, albedo, _ = scene_mesh(scene.arm, scene.render, activations=scene.activations)
    parts = arm_parts(tensed_arm(scene.arm, scene.activations), scene.render.segments,
                      companion_segments=companion_segments(scene.render.segments))
    driver = len(parts["BIClong"].vertices)  # the first part
    reds = (albedo[:, 0] > 0.8) & (albedo[:, 1] < 0.15)
    assert reds[:driver].any() and not reds[driver:].any()
    assert len(mesh.vertices) == sum(len(part.vertices) for part in parts.values())


def test_the_pick_is_marked_over_the_colours_of_activation():
    scene = replace(Scene.of(ELBOW).with_render(colour_by="activation").with_activations(
        (1.0, 0.4, 0.0, 0.0, 0.0, 0.0)), marked=True, selected=1)
    mesh, albedo, spans = scene_mesh(scene.arm, scene.render, activations=scene.activations)
    marked = marked_albedo(scene, mesh, albedo, spans)
    start, end = spans["BRA"]
    assert np.all(marked[start:end] >= albedo[start:end])  # BRA's amber lighter
    assert (marked[start:end] > albedo[start:end] + 0.05).any()
    outside = np.r_[0:start, end:len(albedo)]
    assert np.array_equal(marked[outside], albedo[outside])  # BIClong stays red
    red = (albedo[:, 0] > 0.8) & (albedo[:, 1] < 0.15)
    assert red[spans["BIClong"][0]:spans["BIClong"][1]].any()
