"""arm26's six paths (engine/arm26.py) against OpenSim's own, at every 5 degrees: absolute
lengths, moment arms and where each path meets a wrapping surface."""

import json
from pathlib import Path

import numpy as np
import pytest

from biceps.engine import arm26, arm26_frame

# OpenSim 4.6 on arm26 at every 5 degrees: benchmarks/arm26_reference.py --write made it.
REFERENCE = json.loads((Path(__file__).parent / "data" / "arm26_elbow.json").read_text())
FLEXIONS = REFERENCE["flexion_deg"]


def test_the_reference_covers_the_joints_range_every_5_degrees():
    assert FLEXIONS == list(range(0, 131, 5))
    assert set(REFERENCE["length_mm"]) == set(arm26.MUSCLES)


@pytest.mark.parametrize("name", arm26.MUSCLES)
def test_each_paths_length_is_arm26s_within_a_tenth_of_a_millimetre(name):
    path = arm26.path(name)
    ours = np.array([10.0 * path.length_at(flexion) for flexion in FLEXIONS])
    assert np.abs(ours - REFERENCE["length_mm"][name]).max() <= 0.1


@pytest.mark.parametrize("name", arm26.MUSCLES)
def test_each_paths_moment_arm_is_arm26s_within_half_a_millimetre(name):
    # OpenSim's moment arm is its generalized-force solver's; ours is -dL/dtheta.
    path = arm26.path(name)
    ours = np.array([10.0 * path.moment_arm_at(flexion) for flexion in FLEXIONS])
    assert np.abs(ours - REFERENCE["moment_arm_mm"][name]).max() <= 0.5


@pytest.mark.parametrize("name", arm26.MUSCLES)
def test_the_moment_arm_is_the_length_lost_per_radian(name):
    path = arm26.path(name)
    step = 1e-4  # degrees
    for flexion in (2.0, 37.0, 64.0, 101.0, 128.0):
        change = path.length_at(flexion + step) - path.length_at(flexion - step)
        assert path.moment_arm_at(flexion) == pytest.approx(
            -change / np.radians(2 * step), abs=1e-5)


@pytest.mark.parametrize("name", arm26.MUSCLES)
def test_each_path_wraps_where_arm26s_does_and_meets_the_surface_where_it_does(name):
    # OpenSim names the two points where a path meets a surface pwpt1 and pwpt2; they are
    # stored in the humerus's frame, mm. Its cylinder's tangent points are tangent only to
    # within a degree, so they stand up to 0.9 mm from the exact ones.
    path = arm26.path(name)
    for flexion, theirs in zip(FLEXIONS, REFERENCE["path_points_mm"][name]):
        touches = [arm26_frame.world_point("r_humerus", np.array(where) / 1000.0)
                   for label, *where in theirs if label.startswith("pwpt")]
        places, ways = path.segments(flexion)
        ours = [point for way in ways if way is not None for point in way.points[[0, -1]]]
        assert len(ours) == len(touches), (name, flexion)
        for mine, arm26s in zip(ours, touches):
            assert np.linalg.norm(mine - arm26s) <= 0.15, (name, flexion)


def test_the_via_points_are_arm26s_in_its_frames():
    # The first and last points of the stored paths are the muscle's origin and insertion.
    for name in arm26.MUSCLES:
        path = arm26.path(name)
        for flexion, theirs in zip(FLEXIONS[::13], REFERENCE["path_points_mm"][name][::13]):
            ours = path.places(flexion)
            for mine, (label, *where) in zip(ours[[0, -1]], (theirs[0], theirs[-1])):
                expected = arm26_frame.world_point("r_humerus", np.array(where) / 1000.0)
                assert np.linalg.norm(mine - expected) <= 1e-5, (name, label)


def test_the_hinge_is_the_worlds_z_and_the_head_stands_straight_above_the_elbow():
    axis = np.array(arm26_frame.ELBOW_AXIS)
    np.testing.assert_allclose(arm26_frame.WORLD @ axis / np.linalg.norm(axis), [0.0, 0.0, 1.0],
                               atol=1e-12)
    assert arm26_frame.HEAD[0] == pytest.approx(0.0, abs=1e-12)
    assert arm26_frame.HEAD[1] == pytest.approx(28.98, abs=0.01)
