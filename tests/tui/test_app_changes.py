"""The scene changes behind the keys, checked without a terminal."""

import numpy as np
import pytest

from biceps.engine.errors import RefusedChange
from biceps.engine.scene import Scene
from biceps.tui.changes import (
    LARGEST_SCALE,
    SMALLEST_SCALE,
    has_unsaved_edits,
    moved,
    length_changed,
    turned,
    with_antialiasing_switched,
    with_node,
    zoomed,
)


@pytest.fixture
def scene(config) -> Scene:
    return Scene.of(config)


def test_a_full_turn_comes_back_to_the_same_angle(scene):
    for _ in range(72):
        scene = turned(scene, yaw=5.0)
    assert scene.view.yaw == pytest.approx(-25.0)


def test_angles_stay_within_a_half_turn_either_way(scene):
    assert turned(scene, yaw=200.0).view.yaw == pytest.approx(175.0)
    assert turned(scene, pitch=-200.0).view.pitch == pytest.approx(170.0)


@pytest.mark.parametrize("steps, limit, word", [(100, LARGEST_SCALE, "largest"),
                                                (-100, SMALLEST_SCALE, "smallest")])
def test_scale_stops_at_a_limit_then_refuses(scene, steps, limit, word):
    scene = zoomed(scene, steps)
    assert scene.view.scale == limit
    with pytest.raises(RefusedChange, match=word):
        zoomed(scene, steps)


def test_anti_aliasing_switches_off_from_any_level(scene):
    assert with_antialiasing_switched(scene.with_render(ssaa=3)).render.ssaa == 1
    assert with_antialiasing_switched(scene).render.ssaa == 2


def test_contracting_then_stretching_back_leaves_nothing_to_save(scene):
    shorter = scene.with_arm(length_changed(scene.arm, -1.0)[0])
    assert has_unsaved_edits(shorter, scene)
    back = scene.with_arm(length_changed(shorter.arm, 1.0)[0])
    assert not has_unsaved_edits(back, scene)


def test_small_steps_forth_and_back_come_back_to_the_same_length(scene):
    arm = scene.arm
    for change in [-0.1] * 7 + [0.1] * 7:
        arm, _ = length_changed(arm, change)
        assert arm.length == round(arm.length, 6)
    assert arm.length == 33.0


@pytest.mark.parametrize("change", [
    lambda s: s.with_light(position=(0.0, 0.0, 1.0)),
    lambda s: turned(s, yaw=13.783785),
    lambda s: with_antialiasing_switched(s),
])
def test_the_view_the_light_and_the_settings_are_not_model_edits(scene, change):
    assert not has_unsaved_edits(change(scene), scene)


def test_a_drag_turns_and_moves_to_round_numbers(scene):
    assert turned(scene, yaw=13.783785, pitch=-0.04).view.yaw == -11.2
    assert moved(scene, right=1.23456).view.offset == (1.23, 0.0, 0.0)


def test_an_untouched_node_edit_keeps_the_muscle(scene):
    muscle = scene.arm.muscle
    assert with_node(muscle, 7, muscle.radii[7], muscle.growth[7]) is muscle


def test_a_node_edit_sets_both_values(scene):
    edited = with_node(scene.arm.muscle, 7, 2.5, 1.0)
    assert (edited.radii[7], edited.growth[7]) == (2.5, 1.0)
    assert np.array_equal(np.delete(edited.radii, 7), np.delete(scene.arm.muscle.radii, 7))


def test_scaling_up_and_down_comes_back_to_a_round_number(scene):
    bigger = zoomed(zoomed(scene, 1), 1)
    assert bigger.view.scale == 1.21
    assert zoomed(zoomed(bigger, -1), -1).view.scale == 1.0


def test_an_edit_of_a_node_that_has_gone_since_is_refused(scene):
    muscle = scene.arm.muscle.without_node(14)  # deleted while the node's dialog was open
    with pytest.raises(RefusedChange, match="node 15 is no longer there: the muscle has 14 "
                                            "nodes now"):
        with_node(muscle, 14, 1.0, 1.0)

