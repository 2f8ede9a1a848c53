"""Sections along a muscle: equal steps, radii from the nodes, distances along a path."""

import numpy as np
import pytest

from biceps.engine.stations import distances_along, section_radii, shares


def test_shares_are_linspace_and_cannot_be_changed():
    steps = shares(9)
    assert np.array_equal(steps, np.linspace(0.0, 1.0, 9))
    assert shares(9) is steps  # worked out once
    with pytest.raises(ValueError):
        steps[0] = 1.0


def test_section_radii_keep_the_nodes_and_run_straight_between_them():
    radii = np.array([1.0, 3.0, 2.0])
    sections = section_radii(radii, 9)  # four sections a segment
    assert np.array_equal(sections[::4], radii)
    assert sections[2] == 2.0 and sections[6] == 2.5


def test_distances_along_a_bent_path():
    points = np.array([[0.0, 0.0, 0.0], [3.0, 4.0, 0.0], [3.0, 4.0, 2.0]])
    assert np.array_equal(distances_along(points), [0.0, 5.0, 7.0])
