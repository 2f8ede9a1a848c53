"""A muscle's path over the elbow: straight, or round a cylinder about the elbow's axis."""

import math

import numpy as np
import pytest

from biceps.engine.path import MusclePath, Wrap
from biceps.engine.skeleton import Attachment, Skeleton

# A flexor straight down the front of the arm: 10 cm up the humerus and 4 cm down the
# forearm, each 0.5 cm in front of its bone's axis, level sideways.
ORIGIN = Attachment("upper_arm", 10.0, 0.5, 0.0)
INSERTION = Attachment("forearm", 4.0, 0.5, 0.0)


def test_a_straight_path_is_the_skeletons_law_of_cosines():
    skeleton = Skeleton()
    path = MusclePath(skeleton.origin, skeleton.insertion)
    for flexion in range(0, 131, 10):
        assert path.length_at(flexion) == pytest.approx(skeleton.length_at(flexion), rel=1e-14)
        assert not path.wraps(flexion)


def test_a_wrapped_path_is_two_tangents_and_the_arc_between():
    # Straight, the line passes 0.5 cm in front of the axis: a cylinder of 2 cm catches it.
    path = MusclePath(ORIGIN, INSERTION, Wrap(2.0, "front"))
    assert path.wraps(0.0)
    a, b, r = math.hypot(10.0, 0.5), math.hypot(4.0, 0.5), 2.0
    # Each tangent point lies acos(r / distance) round from its attachment's direction.
    into = math.atan2(10.0, 0.5) - math.acos(r / a)
    out = math.atan2(-4.0, 0.5) + math.acos(r / b)
    expected = math.sqrt(a * a - r * r) + math.sqrt(b * b - r * r) + r * (into - out)
    assert path.length_at(0.0) == pytest.approx(expected, rel=1e-14)


def test_a_line_clear_on_its_side_stays_straight_and_one_on_the_other_side_goes_round():
    straight = float(np.linalg.norm(np.subtract(*MusclePath(ORIGIN, INSERTION).ends(0.0))))
    clear = MusclePath(ORIGIN, INSERTION, Wrap(0.4, "front"))  # passes 0.5 cm in front
    assert not clear.wraps(0.0)
    assert clear.length_at(0.0) == pytest.approx(straight, rel=1e-14)
    # Kept behind the axis (as the triceps over the olecranon), it goes round the back.
    behind = MusclePath(ORIGIN, INSERTION, Wrap(0.4, "back"))
    assert behind.wraps(0.0) and behind.length_at(0.0) > straight


def test_sideways_separation_adds_in_quadrature_as_a_helix():
    level = MusclePath(ORIGIN, INSERTION, Wrap(2.0, "front"))
    apart = MusclePath(ORIGIN, Attachment("forearm", 4.0, 0.5, 3.0), Wrap(2.0, "front"))
    assert apart.length_at(0.0) == pytest.approx(math.hypot(level.length_at(0.0), 3.0))


@pytest.mark.parametrize("flexion", [0.0, 20.0])
def test_the_centreline_runs_evenly_from_origin_to_insertion_round_the_cylinder(flexion):
    path = MusclePath(ORIGIN, Attachment("forearm", 4.0, 0.5, 1.0), Wrap(2.0, "front"))
    assert path.wraps(flexion)
    points, axes = path.centreline(flexion, 81)
    start, end = path.ends(flexion)
    assert np.allclose(points[[0, -1]], [start, end], atol=1e-12)
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    assert steps.sum() == pytest.approx(path.length_at(flexion), rel=1e-3)  # chords of an arc
    assert np.allclose(np.linalg.norm(axes, axis=1), 1.0)
    # Nowhere inside the cylinder, and on it over the arc.
    reach = np.hypot(points[:, 0], points[:, 1])
    assert reach.min() == pytest.approx(2.0, rel=1e-9)
    assert np.all(reach >= 2.0 - 1e-9)


@pytest.mark.parametrize("wrap", [None, Wrap(2.0, "front")])
def test_the_moment_arm_is_the_length_lost_per_radian_straight_or_wrapped(wrap):
    path = MusclePath(ORIGIN, Attachment("forearm", 4.0, 0.5, 1.0), wrap)
    for flexion in (0.0, 20.0, 60.0, 110.0):
        change = path.length_at(flexion + 1e-4) - path.length_at(flexion - 1e-4)
        assert path.moment_arm_at(flexion) == pytest.approx(-change / math.radians(2e-4),
                                                           abs=1e-6)


def test_a_straight_paths_moment_arm_is_the_skeletons():
    skeleton = Skeleton()
    path = MusclePath(skeleton.origin, skeleton.insertion)
    for flexion in range(0, 131, 10):
        assert path.moment_arm_at(flexion) == pytest.approx(skeleton.moment_arm(flexion),
                                                            rel=1e-12)
