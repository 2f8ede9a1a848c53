"""The moment arm and the sweep across the elbow's range."""

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from biceps.engine.arm import Arm
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.skeleton import Skeleton
from biceps.engine.sweep import MOST_ANGLES, angles, flexion_range, sweep

ARM = load_config(DEFAULT_CONFIG).arm
ON_THE_AXES = dict(origin_forward=0.0, origin_lateral=0.0, insertion_forward=0.0,
                   insertion_lateral=0.0)


def test_a_3_4_5_triangle_has_the_moment_arm_of_its_height():
    # Origin 4 cm up the upper arm, insertion 3 cm down the forearm, muscle 5 cm: the elbow
    # is at 90 degrees, and the distance from the right angle to the hypotenuse is 3 * 4 / 5.
    muscle = Muscle.of([0.1, 0.2, 0.1], [0.0, 0.1, 0.0], 5.0)
    arm = Arm(muscle, Skeleton(origin_to_elbow=4.0, elbow_to_insertion=3.0, **ON_THE_AXES))
    assert arm.moment_arm == pytest.approx(2.4, rel=1e-14)


@pytest.mark.parametrize("flexion", [10.0, 45.0, 90.0, 110.0, 130.0])
def test_the_moment_arm_is_the_length_lost_per_radian_of_flexion(flexion):
    skeleton, step = ARM.skeleton, 1e-5
    shortened = skeleton.length_at(flexion - step) - skeleton.length_at(flexion + step)
    assert ARM.at_flexion(flexion).moment_arm == pytest.approx(
        shortened / np.radians(2 * step), rel=1e-7)


def test_a_straight_arm_gives_the_muscle_leverage_only_off_the_bones_axes():
    # The insertion in front of the forearm's axis gives the biceps a lever even with the
    # arm straight (arm26: 0.94 cm); with both attachments on the axes, as the seed had
    # them, it has none until the elbow bends.
    assert ARM.at_flexion(0.0).moment_arm == pytest.approx(0.641, abs=1e-3)
    on_the_axes = replace(ARM, skeleton=replace(ARM.skeleton, **ON_THE_AXES))
    assert on_the_axes.at_flexion(0.0).moment_arm == pytest.approx(0.0, abs=1e-12)
    assert on_the_axes.at_flexion(1.0).moment_arm > 0


@pytest.mark.parametrize("flexion", [0.0, 60.0, 130.0])
def test_the_pose_and_the_law_of_cosines_agree_on_the_moment_arm(flexion):
    assert ARM.at_flexion(flexion).moment_arm == pytest.approx(
        ARM.skeleton.moment_arm(flexion), rel=1e-12)


def test_angles_end_on_the_last_step_without_rounding_build_up():
    tenths = angles(0.0, 1.0, 0.1)
    assert len(tenths) == 11 and tenths[-1] == pytest.approx(1.0)
    assert tenths[3] == 3 * 0.1  # start + k * step, not a running sum
    assert angles(0.0, 130.0, 10.0) == [10.0 * k for k in range(14)]
    assert angles(0.0, 25.0, 10.0) == [0.0, 10.0, 20.0]


def test_angles_end_exactly_on_the_last_angle_when_a_step_lands_there():
    assert 3 * 0.1 > 0.3
    assert angles(0.0, 0.3, 0.1) == [0.0, 0.1, 0.2, 0.3]
    assert angles(0.0, 130.0, 130.0 / 120)[-1] == 130.0


def test_angles_walk_down_when_the_last_is_below_the_first():
    assert angles(90.0, 60.0, 10.0) == [90.0, 80.0, 70.0, 60.0]


@pytest.mark.parametrize(("step", "message"), [
    (0.0, "the step must be above 0 degrees"),
    (-5.0, "the step must be above 0 degrees"),
    (float("nan"), "the step must be above 0 degrees"),
    (1e-6, f"makes 130,000,001 rows; at most {MOST_ANGLES:,} are allowed"),
    (1e-308, "makes more than a billion rows"),  # a count beyond any float: OverflowError
])
def test_angles_refuse_a_step_that_is_no_step_or_far_too_fine(step, message):
    with pytest.raises(RefusedChange, match=message):
        angles(0.0, 130.0, step)


def test_a_sweep_row_holds_the_arm_at_its_angle():
    (row,) = sweep(ARM, [90.0])
    arm = ARM.at_flexion(90.0)
    assert row.flexion == 90.0
    assert row.length == arm.length and row.moment_arm == arm.moment_arm
    assert np.array_equal(row.radii, arm.muscle.radii)
    assert row.girth == pytest.approx(2 * np.pi * row.max_radius)
    assert row.volume_error < 1e-12


def test_a_sweep_past_the_joint_is_refused():
    with pytest.raises(RefusedChange, match="outside the joint's range"):
        sweep(ARM, [0.0, 90.0, 140.0])


def test_the_flexion_range_is_the_joints_unless_the_config_limits_the_length():
    assert flexion_range(ARM) == (0.0, 130.0)
    limited = replace(ARM, min_length=29.0, max_length=34.0)
    least, most = flexion_range(limited)
    assert least == pytest.approx(ARM.skeleton.flexion(34.0))
    assert most == pytest.approx(ARM.skeleton.flexion(29.0))


@settings(max_examples=300, deadline=None)
@given(st.floats(27.5, 35.5), st.floats(0.1, 5.0))
def test_both_ends_of_the_flexion_range_are_reachable(longest, span):
    limited = replace(ARM, min_length=longest - span, max_length=longest)
    for flexion in flexion_range(limited):
        assert limited.at_flexion(flexion).length == pytest.approx(
            limited.skeleton.length_at(flexion))
