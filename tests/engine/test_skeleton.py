"""The skeleton and the arm: the law of cosines with the attachments off the bones' axes,
arm26's BIClong, poses, limits."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from biceps.engine.arm import Arm
from biceps.engine.config import BUNDLED, load_config
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.skeleton import Attachment, Skeleton, check_skeleton, forearm_frame

ARM26 = Skeleton()
ON_THE_AXES = dict(origin_forward=0.0, origin_lateral=0.0, insertion_forward=0.0,
                   insertion_lateral=0.0)  # the seed's skeleton: both ends on the bones' axes
# OpenSim's BIClong at every 10 degrees: benchmarks/arm26_reference.py --write made it.
REFERENCE = json.loads(
    (Path(__file__).parents[2] / "engine" / "data" / "arm26_biclong.json").read_text())


def test_a_3_4_5_triangle_bends_the_elbow_to_90_degrees():
    skeleton = Skeleton(origin_to_elbow=4.0, elbow_to_insertion=3.0, **ON_THE_AXES)
    assert math.degrees(skeleton.interior_angle(5.0)) == pytest.approx(90.0, abs=1e-12)
    assert skeleton.flexion(5.0) == pytest.approx(90.0, abs=1e-12)


def test_offsets_turn_the_triangle_and_add_the_sideways_gap_in_quadrature():
    # Origin 4 up and 3 in front: 5 from the elbow, 36.87 degrees forward of the humerus;
    # insertion 3 down the forearm, 4 cm to the side of the origin. At a straight arm the
    # triangle's angle is 180 - 36.87 degrees.
    skeleton = Skeleton(origin_to_elbow=4.0, origin_forward=3.0, origin_lateral=-2.0,
                        elbow_to_insertion=3.0, insertion_forward=0.0, insertion_lateral=2.0)
    psi = math.pi - math.atan2(3.0, 4.0)
    expected = math.sqrt(5**2 + 3**2 - 2 * 5 * 3 * math.cos(psi) + 4**2)
    assert skeleton.length_at(0.0) == pytest.approx(expected, rel=1e-12)
    pose = skeleton.pose(expected)
    assert np.linalg.norm(pose.insertion - pose.origin) == pytest.approx(expected, rel=1e-12)
    assert pose.flexion == pytest.approx(0.0, abs=1e-6)


def test_a_straight_arm_has_no_flexion_and_no_nan():
    longest = ARM26.length_range()[1]
    for just_past in (longest, longest * (1 + 1e-15)):
        assert ARM26.flexion(just_past) == pytest.approx(0.0, abs=1e-3)
        assert not np.isnan(ARM26.interior_angle(just_past))
    on_axes = Skeleton(**ON_THE_AXES)
    length = on_axes.origin_to_elbow + on_axes.elbow_to_insertion
    for just_past in (length, length * (1 + 1e-15), length + 1e-9):
        assert on_axes.flexion(just_past) == pytest.approx(0.0, abs=1e-3)


def test_a_fully_folded_arm_has_no_nan():
    on_axes = Skeleton(**ON_THE_AXES)
    length = on_axes.origin_to_elbow - on_axes.elbow_to_insertion
    assert on_axes.flexion(length * (1 - 1e-12)) == pytest.approx(180.0, abs=1e-3)


def test_the_length_range_is_about_the_spec_and_arm26s():
    # SPEC 2.3: about 35.6 cm straight to 27.1 cm at 130 degrees.
    shortest, longest = ARM26.length_range()
    assert longest == pytest.approx(35.42, abs=0.01)
    assert shortest == pytest.approx(26.94, abs=0.01)


def test_length_and_flexion_are_inverse():
    for flexion in (0.0, 30.0, 90.0, 130.0):
        assert ARM26.flexion(ARM26.length_at(flexion)) == pytest.approx(flexion, abs=1e-6)


def test_the_moment_arm_is_the_lengths_rate_of_change():
    step = 1e-6
    for flexion in (0.0, 45.0, 100.0, 130.0):
        change = ARM26.length_at(flexion + step) - ARM26.length_at(flexion - step)
        rate = -change / (2 * math.radians(step))
        assert ARM26.moment_arm(flexion) == pytest.approx(rate, rel=1e-6)


def test_the_straight_arm_has_a_moment_arm_where_the_seeds_had_none():
    assert ARM26.moment_arm(0.0) == pytest.approx(0.641, abs=0.001)  # cm; arm26: 0.938
    assert Skeleton(**ON_THE_AXES).moment_arm(0.0) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("index", range(len(REFERENCE["flexion_deg"])))
def test_length_change_and_moment_arm_follow_arm26s_biclong(index):
    # The bound: length change within 2 mm and moment arm within 3 mm of OpenSim's
    # arm26 BIClong, at every 10 degrees (the straight muscle comes within 1.98 and 2.97).
    flexion = REFERENCE["flexion_deg"][index]
    their_change = REFERENCE["length_mm"][index] - REFERENCE["length_mm"][0]
    our_change = 10.0 * (ARM26.length_at(flexion) - ARM26.length_at(0.0))
    assert our_change == pytest.approx(their_change, abs=2.0)
    assert 10.0 * ARM26.moment_arm(flexion) == pytest.approx(REFERENCE["moment_arm_mm"][index],
                                                             abs=3.0)


def test_pose_puts_the_muscle_ends_length_apart():
    for length in (27.5, 31.0, 35.4):
        pose = ARM26.pose(length)
        assert np.linalg.norm(pose.insertion - pose.origin) == pytest.approx(length)
        assert np.linalg.norm(pose.hand - pose.elbow) == pytest.approx(ARM26.forearm)
        assert np.linalg.norm(pose.shoulder - pose.elbow) == pytest.approx(ARM26.upper_arm)


def test_a_straight_arm_hangs_down_and_flexion_swings_it_forward():
    straight = ARM26.pose(ARM26.length_at(0.0))
    assert np.allclose(straight.hand, [0.0, -ARM26.forearm, 0.0], atol=1e-6)
    right_angle = ARM26.pose(ARM26.length_at(90.0))
    assert np.allclose(right_angle.hand, [ARM26.forearm, 0.0, 0.0], atol=1e-6)


def test_attachments_sit_off_the_axes_where_the_skeleton_says():
    pose = ARM26.pose(ARM26.length_at(90.0))
    np.testing.assert_allclose(pose.origin, [0.0, 30.15, -2.2])
    # At 90 degrees the forearm points forward (+x) and its front faces up (+y).
    np.testing.assert_allclose(pose.insertion, [4.987, 0.753, 2.18], atol=1e-6)
    assert pose.place(Attachment("forearm", 10.0, 1.0)) == pytest.approx([10.0, 1.0, 0.0])
    np.testing.assert_allclose(forearm_frame(90.0) @ forearm_frame(90.0).T, np.eye(3),
                               atol=1e-12)


@pytest.mark.parametrize(
    ("skeleton", "message"),
    [
        (Skeleton(forearm=0.0), "forearm must be a finite number from 1e-06 to 1e\\+06 cm"),
        (Skeleton(origin_to_elbow=-1.0), "origin_to_elbow must be a finite number from"),
        (Skeleton(upper_arm=1e300), "upper_arm must be a finite number from 1e-06 to 1e\\+06"),
        (Skeleton(insertion_lateral=math.nan), "insertion_lateral must be a finite number"),
        (Skeleton(insertion_lateral=1e300), "insertion_lateral must be a finite number from "
                                            "-1e\\+08 to 1e\\+08 cm"),
        (Skeleton(elbow_to_insertion=30.0), "elbow_to_insertion must be at most the forearm's "
                                            "length, 25.4 cm, not 30"),
        (Skeleton(min_flexion=90.0, max_flexion=40.0), "min_flexion < max_flexion"),
        (Skeleton(insertion_forward=-2.0), "insertion_forward: .* behind the elbow's axis"),
        (Skeleton(origin_to_elbow=4.0, origin_forward=3.0, elbow_to_insertion=3.0,
                  insertion_forward=3.0), "flexion_range: at 130 degrees the forearm would fold"),
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
    with pytest.raises(RefusedChange, match=r"26.94 to 35.42 cm"):
        arm.at_length(36.0)
    with pytest.raises(RefusedChange, match=r"outside the joint's range, 0 to 130"):
        arm.at_flexion(140.0)


def test_config_limits_narrow_the_range(arm):
    limited = Arm(arm.muscle, arm.skeleton, min_length=30.0, max_length=34.0)
    assert limited.length_range() == (30.0, 34.0)


def test_a_step_past_the_limit_stops_at_it_and_says_so(arm):
    stretched, note = arm.stepped(+10.0)
    assert stretched.length == pytest.approx(ARM26.length_range()[1])
    assert "straight" in note
    contracted, note = arm.stepped(-10.0)
    assert contracted.flexion == pytest.approx(130.0)
    assert "shortest" in note and "130 degrees" in note


def test_a_step_within_range_has_no_note(arm):
    moved, note = arm.stepped(-0.5)
    assert moved.length == pytest.approx(32.5)
    assert note is None
    assert moved.muscle.volume_error < 1e-12


@pytest.fixture
def thin_toy() -> Arm:
    """The toy with node 1 at radius 0.2 and growth 5: stretched, it thins to nothing at
    10.63 cm, short of the straight arm's 12.10 cm."""
    toy = load_config(BUNDLED / "toy.toml").arm
    return toy.with_muscle(toy.muscle.with_radius(0, 0.2).with_growth(0, 5.0))


def test_the_range_ends_where_the_muscle_would_thin_to_nothing(thin_toy):
    low, high = thin_toy.length_range()
    assert thin_toy.skeleton.length_range()[1] == pytest.approx(12.1, abs=0.01)
    assert high == pytest.approx(thin_toy.muscle.longest_length)
    assert f"{high:.2f}" == "10.63"


def test_a_stretch_past_the_muscles_own_limit_stops_at_it_and_says_which_node(thin_toy):
    stretched, note = thin_toy.stepped(+1.0)
    assert stretched.length == thin_toy.muscle.longest_length
    assert note == ("the muscle is at its longest, 10.63 cm: stretched further, node 1's "
                    "radius would fall to zero")
    again, note = stretched.stepped(+1.0)
    assert again.length == stretched.length and note is not None


def test_a_length_past_the_muscles_own_limit_is_refused_with_the_reason(thin_toy):
    with pytest.raises(RefusedChange, match=r"6.16 to 10.63 cm .*node 1's radius would fall"):
        thin_toy.at_length(11.0)
