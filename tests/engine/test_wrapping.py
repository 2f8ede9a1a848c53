"""Wrapping surfaces: the shortest way round a cylinder and an ellipsoid, hand-checked."""

import math

import numpy as np
import pytest

from biceps.engine.wrapping import Cylinder, Ellipsoid

UPRIGHT = np.eye(3)


def test_a_segment_across_a_cylinder_goes_round_it_by_two_tangents_and_an_arc():
    # From (-4, 1) to (4, 1), 1 cm off the axis of a cylinder of radius 2: the path goes
    # round the near side (+y) between tangent points acos(2 / sqrt(17)) round from each end.
    cylinder = Cylinder(centre=np.zeros(3), rotation=UPRIGHT, radius=2.0, length=10.0)
    start, end = np.array([-4.0, 1.0, 0.0]), np.array([4.0, 1.0, 0.0])
    way = cylinder.wrap(start, end)
    reach = math.hypot(4.0, 1.0)
    leave = math.atan2(1.0, -4.0) - math.acos(2.0 / reach)  # from the start, turning clockwise
    arrive = math.atan2(1.0, 4.0) + math.acos(2.0 / reach)
    tangent = math.sqrt(reach**2 - 4.0)
    assert way.length == pytest.approx(2.0 * (leave - arrive), rel=1e-12)
    assert way.total(start, end) == pytest.approx(2 * tangent + 2.0 * (leave - arrive), rel=1e-12)
    assert np.all(way.points[:, 1] > 0.0)  # the near side
    np.testing.assert_allclose(np.hypot(way.points[:, 0], way.points[:, 1]), 2.0, rtol=1e-12)


def test_a_climb_along_the_axis_makes_the_unrolled_path_one_straight_line():
    cylinder = Cylinder(centre=np.zeros(3), rotation=UPRIGHT, radius=2.0, length=10.0)
    level = cylinder.wrap(np.array([-4.0, 1.0, 0.0]), np.array([4.0, 1.0, 0.0]))
    start, end = np.array([-4.0, 1.0, -1.5]), np.array([4.0, 1.0, 1.5])
    climbing = cylinder.wrap(start, end)
    flat = level.total(np.array([-4.0, 1.0, 0.0]), np.array([4.0, 1.0, 0.0]))
    assert climbing.total(start, end) == pytest.approx(math.hypot(flat, 3.0), rel=1e-12)


def test_a_segment_that_misses_or_starts_inside_a_cylinder_stays_straight():
    cylinder = Cylinder(centre=np.zeros(3), rotation=UPRIGHT, radius=2.0, length=10.0)
    assert cylinder.wrap(np.array([-4.0, 2.5, 0.0]), np.array([4.0, 2.5, 0.0])) is None
    assert cylinder.wrap(np.array([-1.0, 0.5, 0.0]), np.array([4.0, 1.0, 0.0])) is None
    # Past its ends, as OpenSim's finite cylinder.
    assert cylinder.wrap(np.array([-4.0, 1.0, 6.0]), np.array([4.0, 1.0, 6.0])) is None


def test_a_quadrant_sends_the_path_round_the_far_side():
    # The near side is +y; kept to the -y half, the path goes the long way round.
    cylinder = Cylinder(centre=np.zeros(3), rotation=UPRIGHT, radius=2.0, length=10.0,
                        quadrant=(1, -1))
    way = cylinder.wrap(np.array([-4.0, 1.0, 0.0]), np.array([4.0, 1.0, 0.0]))
    assert way.points[len(way.points) // 2][1] < 0.0


def test_round_a_sphere_the_shortest_path_is_a_great_circle():
    # A sphere of radius 1 (an ellipsoid of equal axes) between two points 3 from its
    # centre, 160 degrees apart (so the straight line passes 0.52 from the centre): two
    # tangents and the arc between, in their common plane.
    sphere = Ellipsoid(centre=np.zeros(3), rotation=UPRIGHT, radii=np.ones(3))
    start = np.array([3.0, 0.0, 0.0])
    apart = math.radians(160.0)
    end = 3.0 * np.array([math.cos(apart), math.sin(apart), 0.0])
    way = sphere.wrap(start, end)
    arc = apart - 2 * math.acos(1.0 / 3.0)
    assert way.total(start, end) == pytest.approx(2 * math.sqrt(8.0) + arc, rel=1e-5)
    np.testing.assert_allclose(np.linalg.norm(way.points, axis=1), 1.0, rtol=1e-9)


def test_an_ellipsoids_quadrant_keeps_the_path_on_its_half():
    # A segment across the ellipsoid's middle: left to itself it goes the shorter way (over
    # +z, the ellipsoid being flatter there); kept to the -z half, under it, and longer.
    ellipsoid = Ellipsoid(centre=np.zeros(3), rotation=UPRIGHT, radii=np.array([1.0, 2.0, 1.0]))
    start, end = np.array([-3.0, 0.0, 0.2]), np.array([3.0, 0.0, 0.2])
    over = ellipsoid.wrap(start, end)
    under = Ellipsoid(centre=np.zeros(3), rotation=UPRIGHT, radii=np.array([1.0, 2.0, 1.0]),
                      quadrant=(2, -1)).wrap(start, end)
    assert over.points[len(over.points) // 2][2] > 0.0
    assert under.points[len(under.points) // 2][2] < 0.0
    assert under.total(start, end) > over.total(start, end)


def test_a_segment_clear_of_an_ellipsoid_stays_straight():
    ellipsoid = Ellipsoid(centre=np.zeros(3), rotation=UPRIGHT, radii=np.array([1.0, 2.0, 1.0]))
    assert ellipsoid.wrap(np.array([-3.0, 0.0, 1.5]), np.array([3.0, 0.0, 1.5])) is None
    assert ellipsoid.wrap(np.array([0.0, 0.0, 0.5]), np.array([3.0, 0.0, 0.5])) is None
