"""The arm's anatomy: bones built from profiles, the muscle clear of them, tendons on bone.

The overlap of muscle and bone is measured on the exported meshes with manifold3d, a
library independent of ours, as the issue asks.
"""

import math

import numpy as np
import pytest
import trimesh

from biceps.engine.anatomy import PARTS, arm_parts, tendon_share
from biceps.engine.bones import bone_parts
from biceps.engine.clearance import GAP, path_offsets, section_offsets
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.skeleton import Skeleton
from solids import exported as exported_parts, solid

FLEXIONS = range(0, 131, 10)
SEGMENTS = 48


@pytest.fixture(scope="module")
def default_arm():
    return load_config(DEFAULT_CONFIG).arm


@pytest.fixture(scope="module")
def exported(default_arm, tmp_path_factory):
    """The arm at each flexion, exported as glTF and read back: {flexion: {part: mesh}}."""
    return exported_parts(default_arm, FLEXIONS, SEGMENTS, tmp_path_factory.mktemp("exports"))


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_the_muscle_shares_at_most_1_percent_with_the_bones_and_its_tendons_end_on_bone(
        exported, flexion):
    parts = exported[flexion]
    assert set(parts) == set(PARTS)
    muscle = solid(parts["muscle"])
    shared = {name: (muscle ^ solid(parts[name])).volume()
              for name in ("scapula", "humerus", "radius", "ulna")}
    assert sum(shared.values()) <= 0.01 * muscle.volume()
    # Each tendon's end sits on its bone: the origin on the shoulder blade's tubercle, the
    # insertion on the radius's tuberosity.
    assert shared["scapula"] > 0.0 and shared["radius"] > 0.0


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_the_exported_muscle_holds_the_conserved_volume_times_the_polygon_factor(
        default_arm, exported, flexion):
    arm = default_arm.at_flexion(flexion)
    assert arm.muscle.volume_error < 1e-12
    polygon = SEGMENTS * math.sin(2 * math.pi / SEGMENTS) / (2 * math.pi)
    # The frusta, moved sideways off the bones, keep exactly the polygon's share of their
    # volume; the caps' facets, a far smaller share, lose 4 parts in a million more.
    volume = exported[flexion]["muscle"].volume
    assert volume == pytest.approx(polygon * arm.muscle.volume, rel=1e-5)


def test_every_bone_part_is_closed_and_outward(default_arm):
    for name, mesh in arm_parts(default_arm, 24).items():
        closed = trimesh.Trimesh(mesh.vertices, mesh.triangles, process=False)
        assert closed.is_watertight and closed.is_winding_consistent, name
        assert closed.volume > 0, name


@pytest.mark.parametrize("upper_arm, forearm", [
    (29.1 * 4, 29.1), (25.4, 25.4 * 4),  # a bone as much longer than the other as it may be
    (1e6, 1e6), (1e-6 * 4, 1e-6),  # the ends of a bone's bound
])
def test_bones_at_their_bounds_are_closed_and_as_detailed_as_an_adult_s(upper_arm, forearm):
    # A humerus 5 times the forearm ended in "a profile runs from a pole to a pole" (the
    # ulna's spline, sized with both, dipped below zero); one of 1e6 cm was sampled every
    # 0.6 cm, millions of rings, 5 GB.
    ratio = upper_arm / 29.1
    skeleton = Skeleton(upper_arm=upper_arm, forearm=forearm, origin_to_elbow=30.15 * ratio,
                        origin_lateral=-2.2 * ratio, elbow_to_insertion=4.987 * forearm / 25.4)
    adult = {name: len(parts) for name, (_, parts) in bone_parts(Skeleton()).items()}
    for name, (_, parts) in bone_parts(skeleton).items():
        assert len(parts) == adult[name]
        for part in parts:
            assert np.all(part.profile[1:-1, 1] > 0), name
            assert len(part.profile) <= 2 * 32 * 10, name  # at most 32 samples between knots
        for part in parts:
            closed = trimesh.Trimesh(part.mesh(12).vertices, part.mesh(12).triangles,
                                     process=False)
            assert closed.is_watertight and closed.volume > 0, name


def test_the_tubercles_reach_the_attachments_wherever_they_are():
    skeleton = Skeleton(origin_to_elbow=32.0, origin_forward=1.5, origin_lateral=-3.5,
                        elbow_to_insertion=6.0, insertion_forward=1.6, insertion_lateral=1.0)
    bones = bone_parts(skeleton)
    for bone, point in (("scapula", skeleton.origin), ("radius", skeleton.insertion)):
        knob = bones[bone][1][-1].mesh(SEGMENTS)  # each bone's last part; its end's pole
        distances = np.linalg.norm(knob.vertices - point.in_frame(), axis=1)
        assert distances.min() == pytest.approx(0.0, abs=1e-9)


def test_a_section_moves_forward_just_clear_of_a_bone_in_its_way():
    # The muscle runs down the y axis through a ball of radius 2 on it, 10 cm down; the
    # elbow (the world's origin) lies behind the line, so forward is +x. The section
    # through the ball's centre, of radius 1, moves 1 + 2 + GAP.
    start, end = np.array([1e-9, 20.0, 0.0]), np.array([1e-9, 0.0, 0.0])
    offsets = section_offsets(start, end, np.array([1.0, 1.0, 1.0]), np.array([[0.0, 10.0, 0.0]]),
                              np.array([2.0]), per_segment=2)
    np.testing.assert_allclose(offsets[2], [3.0 + GAP, 0.0, 0.0], atol=1e-6)
    assert np.all(offsets[[0, -1]] == 0.0)  # the attachments stay put
    assert np.all(np.abs(offsets[:, 1:]) < 1e-12)  # within the sections' planes


def test_a_leaning_section_moves_sideways_just_clear_of_a_bone_in_its_way():
    # As above, turned a quarter round the muscle's axis (down): from forward (+x) to +z.
    points = np.column_stack([np.full(5, 1e-9), np.linspace(20.0, 0.0, 5), np.zeros(5)])
    axes = np.tile([0.0, -1.0, 0.0], (5, 1))
    offsets = path_offsets(points, axes, np.array([1.0, 1.0, 1.0]), np.array([[0.0, 10.0, 0.0]]),
                           np.array([2.0]), lean=np.pi / 2)
    np.testing.assert_allclose(offsets[2], [0.0, 0.0, 3.0 + GAP], atol=1e-6)


def _round_the_elbow(radius: float = 2.0, step: float = 0.25):
    """Sections down the back of an upper arm (x = -radius, from y = 10) and a quarter
    round the elbow's axis z at ``radius``: centres and unit axes (m, 3), and which are on
    the bend."""
    down = np.arange(10.0, 0.0, -step)
    straight = np.column_stack([np.full(len(down), -radius), down, np.zeros(len(down))])
    angles = np.linspace(np.pi, 1.5 * np.pi, round(0.5 * np.pi * radius / step) + 1)
    arc = radius * np.column_stack([np.cos(angles), np.sin(angles), np.zeros(len(angles))])
    ways = np.column_stack([-np.sin(angles), np.cos(angles), np.zeros(len(angles))])
    points = np.concatenate([straight, arc])
    axes = np.concatenate([np.tile([0.0, -1.0, 0.0], (len(down), 1)), ways])
    return points, axes, np.arange(len(points)) > len(down)


def test_a_leaning_muscle_moves_across_the_plane_of_a_bend_and_keeps_its_volume():
    # A ball on the bend: the sections there cannot move in the bend's plane (that would
    # change the tube's volume, Pappus), but across it, along z, they can, as far as clears.
    points, axes, bent = _round_the_elbow()
    ball = points[bent][len(points[bent]) // 2]
    offsets = path_offsets(points, axes, np.array([0.5, 0.5]), ball[None, :], np.array([0.5]),
                           lean=math.radians(40.0))
    assert np.abs(offsets[bent][:, :2]).max() < 1e-12
    assert np.abs(offsets[bent][:, 2]).max() == pytest.approx(0.5 + 0.5 + GAP, abs=1e-6)
    assert np.all(offsets[:, 2] >= 0.0)  # a positive lean turns to the arm's outside, +z
    upright = path_offsets(points, axes, np.array([0.5, 0.5]), ball[None, :], np.array([0.5]))
    assert np.all(upright[bent] == 0.0)  # not leaning, the bend stays where it is


def test_a_muscle_laid_over_others_bows_out_once_over_two_humps():
    # Two balls on the muscle's line, 10 cm apart: laid over others, the muscle does not
    # dip between them (an S seen from the side), it bows out once.
    points = np.column_stack([np.full(41, 1e-9), np.linspace(20.0, 0.0, 41), np.zeros(41)])
    axes = np.tile([0.0, -1.0, 0.0], (41, 1))
    balls, sizes = np.array([[0.0, 15.0, 0.0], [0.0, 5.0, 0.0]]), np.array([2.0, 1.5])
    radii = np.array([1.0, 1.0])
    dipping = path_offsets(points, axes, radii, balls, sizes)[:, 0]
    bowed = path_offsets(points, axes, radii, balls, sizes, one_bulge=True)[:, 0]
    middle = 20  # y = 10, halfway between the balls
    assert dipping[middle] < 1.0 + 1.5 + GAP - 0.5  # left alone, it dips between them
    assert bowed[middle] == pytest.approx(1.0 + 1.5 + GAP, abs=1e-6)
    assert np.all(bowed >= dipping - 1e-12)
    peak = int(np.argmax(bowed))
    assert np.all(np.diff(bowed[:peak + 1]) >= 0.0) and np.all(np.diff(bowed[peak:]) <= 0.0)


def test_tendons_are_the_nodes_that_do_not_grow(default_arm):
    parts = arm_parts(default_arm, SEGMENTS)
    share = tendon_share(default_arm.muscle, default_arm.paths[0], default_arm.flexion,
                         parts["muscle"])
    assert share[0] == share[-1] == 1.0  # the poles of the end caps
    assert share.min() == 0.0  # the belly
    growth = default_arm.muscle.growth
    assert growth[0] == growth[1] == 0.0 and share[1:1 + SEGMENTS].min() == 1.0
