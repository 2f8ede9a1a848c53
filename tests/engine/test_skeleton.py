"""The skeleton and the arm: law of cosines, poses, limits."""

import numpy as np
import pytest

from biceps.engine.arm import Arm
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.skeleton import Skeleton, check_skeleton

ARM26 = Skeleton()


def test_a_3_4_5_triangle_bends_the_elbow_to_90_degrees():
    skeleton = Skeleton(origin_to_elbow=4.0, elbow_to_insertion=3.0)
    assert np.degrees(skeleton.interior_angle(5.0)) == pytest.approx(90.0, abs=1e-12)
    assert skeleton.flexion(5.0) == pytest.approx(90.0, abs=1e-12)


def test_a_straight_arm_has_no_flexion_and_no_nan():
    length = ARM26.origin_to_elbow + ARM26.elbow_to_insertion
    for just_past in (length, length * (1 + 1e-15), length + 1e-9):
        assert ARM26.flexion(just_past) == pytest.approx(0.0, abs=1e-3)
        assert not np.isnan(ARM26.interior_angle(just_past))


def test_a_fully_folded_arm_has_no_nan():
    length = ARM26.origin_to_elbow - ARM26.elbow_to_insertion
    assert ARM26.flexion(length * (1 - 1e-12)) == pytest.approx(180.0, abs=1e-3)


def test_arm26_lengths_match_the_spec():
    shortest, longest = ARM26.length_range()
    assert longest == pytest.approx(35.6)
    assert shortest == pytest.approx(27.05, abs=0.01)


def test_length_and_flexion_are_inverse():
    for flexion in (0.0, 30.0, 90.0, 130.0):
        assert ARM26.flexion(ARM26.length_at(flexion)) == pytest.approx(flexion, abs=1e-6)


def test_pose_puts_the_muscle_ends_length_apart():
    for length in (27.5, 31.0, 35.6):
        pose = ARM26.pose(length)
        assert np.linalg.norm(pose.insertion - pose.origin) == pytest.approx(length)
        assert np.linalg.norm(pose.hand - pose.elbow) == pytest.approx(ARM26.forearm)
        assert np.linalg.norm(pose.shoulder - pose.elbow) == pytest.approx(ARM26.upper_arm)


def test_a_straight_arm_hangs_down_and_flexion_swings_it_forward():
    straight = ARM26.pose(ARM26.length_at(0.0))
    assert np.allclose(straight.hand, [0.0, -ARM26.forearm, 0.0], atol=1e-9)
    right_angle = ARM26.pose(ARM26.length_at(90.0))
    assert np.allclose(right_angle.hand, [ARM26.forearm, 0.0, 0.0], atol=1e-9)


@pytest.mark.parametrize(
    ("skeleton", "message"),
    [
        (Skeleton(forearm=0.0), "forearm must be above 0"),
        (Skeleton(origin_to_elbow=-1.0), "origin_to_elbow must be above 0"),
        (Skeleton(min_flexion=90.0, max_flexion=40.0), "min_flexion < max_flexion"),
    ],
)
def test_an_impossible_skeleton_is_refused(skeleton, message):
    with pytest.raises(RefusedChange, match=message):
        check_skeleton(skeleton)


@pytest.fixture
def arm() -> Arm:
    muscle = Muscle.of([0.4, 1.5, 2.0, 1.5, 0.4], [0.0, 1.4, 2.0, 1.4, 0.0], 33.0)
    return Arm(muscle, ARM26)


def test_a_length_outside_the_joint_range_is_refused(arm):
    with pytest.raises(RefusedChange, match=r"27.05 to 35.60 cm"):
        arm.at_length(36.0)
    with pytest.raises(RefusedChange, match=r"outside the joint's range, 0 to 130"):
        arm.at_flexion(140.0)


def test_config_limits_narrow_the_range(arm):
    limited = Arm(arm.muscle, arm.skeleton, min_length=30.0, max_length=34.0)
    assert limited.length_range() == (30.0, 34.0)


def test_a_step_past_the_limit_stops_at_it_and_says_so(arm):
    stretched, note = arm.stepped(+10.0)
    assert stretched.length == pytest.approx(35.6)
    assert "straight" in note
    contracted, note = arm.stepped(-10.0)
    assert contracted.flexion == pytest.approx(130.0)
    assert "shortest" in note and "130 degrees" in note


def test_a_step_within_range_has_no_note(arm):
    moved, note = arm.stepped(-0.5)
    assert moved.length == pytest.approx(32.5)
    assert note is None
    assert moved.muscle.volume_error < 1e-12
