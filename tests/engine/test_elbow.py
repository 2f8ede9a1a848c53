"""The elbow's six muscles (configs/elbow.toml) on arm26's skeleton and paths: each at its own
constant volume at every pose, its length and moment arm arm26's, and laid in layers round
the humerus as an anatomist draws them, clear of the bones and of each other.

Measured on the exported meshes with libraries independent of ours (trimesh, manifold3d,
and plane sections of our own in tests/sections.py), at every 5 degrees from 0 to 130.
"""

import json
from pathlib import Path

import manifold3d
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from biceps.configs import FOLDER
from biceps.engine import arm26
from biceps.engine.anatomy import BONES, arm_parts
from biceps.engine.config import load_config
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import VOLUME_MODES
from sections import Sliced, area, centroid, hull_perimeter, thickness_along
from solids import distance, exported, solid, winding

# arm26's six muscles at every 5 degrees: benchmarks/arm26_reference.py --write made it.
REFERENCE = json.loads((Path(__file__).parent / "data" / "arm26_elbow.json").read_text())
FLEXORS = ("BIClong", "BICshort", "BRA")
EXTENSORS = ("TRIlong", "TRIlat", "TRImed")
BICEPS = ("BIClong", "BICshort")
FLEXIONS = REFERENCE["flexion_deg"]  # 0 to 130 by 5
SEGMENTS = 24


@pytest.fixture(scope="module")
def elbow():
    return load_config(FOLDER / "elbow.toml").arm


def in_mode(arm, mode):
    """The arm with every muscle's current shape conserving the ``mode`` volume."""
    for index, muscle in enumerate(arm.muscles):
        arm = arm.with_muscle_at(index, muscle.with_volume_mode(mode))
    return arm


def test_the_bundled_elbow_has_arm26s_six_muscles_the_biceps_driving(elbow):
    assert elbow.names == ("BIClong", "BRA", "BICshort", "TRImed", "TRIlat", "TRIlong")
    assert elbow.skeleton.model == "arm26"
    assert all(path is arm26.path(name) for name, path in zip(elbow.names, elbow.paths))
    heads = elbow.muscles[0].reference_volume + elbow.muscles[2].reference_volume
    assert 150 <= heads <= 250  # both heads of the biceps, cm^3 (SPEC 2.3)


@pytest.mark.parametrize("mode", VOLUME_MODES)
@settings(max_examples=1, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1))
def test_every_muscle_keeps_its_volume_over_10000_random_elbow_changes(elbow, mode, seed):
    arm = in_mode(elbow, mode)
    conserved = [muscle.reference_volume for muscle in arm.muscles]
    flexions = np.random.default_rng(seed).uniform(0.0, 130.0, 10_000)
    worst = 0.0
    for flexion in flexions:
        arm = arm.at_flexion(float(flexion))
        for muscle, volume in zip(arm.muscles, conserved):
            worst = max(worst, abs(muscle.volume - volume) / volume)
    assert worst < 1e-12
    assert {muscle.volume_mode for muscle in arm.muscles} == {mode}


@pytest.mark.parametrize("name", FLEXORS + EXTENSORS)
def test_each_muscles_length_and_moment_arm_are_arm26s(elbow, name):
    # The issue asks for 2 mm; the paths give a tenth of a millimetre and half of one.
    index = elbow.names.index(name)
    posed = [elbow.at_flexion(flexion) for flexion in FLEXIONS]
    lengths = np.array([10.0 * arm.lengths[index] for arm in posed])
    moment_arms = np.array([10.0 * arm.moment_arms[index] for arm in posed])
    assert np.abs(lengths - REFERENCE["length_mm"][name]).max() <= 0.1
    assert np.abs(moment_arms - REFERENCE["moment_arm_mm"][name]).max() <= 0.5


def test_the_driver_finds_the_flexion_its_length_puts_the_elbow_at_to_1e_12_degrees(elbow):
    for flexion in np.linspace(0.0, 130.0, 27):
        length = elbow.drive.length_at(float(flexion))
        assert elbow.at_length(length).flexion == pytest.approx(flexion, abs=1e-12)


def test_the_triceps_lengthens_while_the_flexors_shorten(elbow):
    lengths = np.array([elbow.at_flexion(f).lengths for f in FLEXIONS])
    steps = np.diff(lengths, axis=0)
    for index, name in enumerate(elbow.names):
        assert np.all(steps[:, index] < 0) if name in FLEXORS else np.all(steps[:, index] > 0)


@pytest.fixture(scope="module")
def posed(elbow, tmp_path_factory):
    """Every part at every 5 degrees, exported as glTF and read back: {flexion: {name:
    trimesh.Trimesh}}."""
    return exported(elbow, FLEXIONS, SEGMENTS, tmp_path_factory.mktemp("elbow"))


@pytest.fixture(scope="module")
def solids(posed):
    return {flexion: {name: solid(mesh) for name, mesh in parts.items()}
            for flexion, parts in posed.items()}


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_no_muscle_shares_more_than_1_percent_with_the_bones(elbow, solids, flexion):
    parts = solids[flexion]
    bones = manifold3d.Manifold.batch_boolean([parts[name] for name in BONES],
                                              manifold3d.OpType.Add)
    for name in elbow.names:
        assert (parts[name] ^ bones).volume() <= 0.01 * parts[name].volume(), name


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_muscles_share_at_most_3_percent_of_the_smaller(elbow, solids, flexion):
    parts = solids[flexion]
    names = elbow.names
    for i, first in enumerate(names):
        for second in names[i + 1:]:
            smaller = min(parts[first].volume(), parts[second].volume())
            assert (parts[first] ^ parts[second]).volume() <= 0.03 * smaller, (first, second)


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_every_muscles_mesh_is_closed_and_holds_its_volume(elbow, posed, flexion):
    # Each section is a polygon with its section's area exactly (the polygon's factor is
    # 1), so the mesh holds the muscle's volume but for its facets between sections that
    # turn and change their shape, and over its caps: 0.2 % at most.
    arm = elbow.at_flexion(flexion)
    for name, muscle in zip(arm.names, arm.muscles):
        mesh = posed[flexion][name]
        assert mesh.is_watertight and mesh.is_winding_consistent, name
        assert mesh.volume == pytest.approx(muscle.volume, rel=2e-3), name


def _humerus_frame(arm):
    """The humerus's axis, up from the elbow's centre, and its front and outside."""
    up = arm.skeleton.shoulder / np.linalg.norm(arm.skeleton.shoulder)
    front = np.array([1.0, 0.0, 0.0]) - up[0] * up
    front /= np.linalg.norm(front)
    return up, front, np.cross(front, up)


@pytest.fixture(scope="module")
def sections(elbow, posed):
    """Each muscle's and the humerus's mesh, ready to cut square to the humerus, by
    flexion and name."""
    up = _humerus_frame(elbow)[0]
    return {flexion: {name: Sliced(mesh.vertices, mesh.faces, up)
                      for name, mesh in parts.items() if name in (*elbow.names, "humerus")}
            for flexion, parts in posed.items()}


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_at_mid_humerus_the_muscles_pack_within_an_arms_size(elbow, sections, flexion):
    # An adult's mid-arm is 25 to 35 cm round, fat and skin included, its muscle 4.5 to
    # 5.5 cm from the humerus's axis at most (NHANES, Fryar et al. 2021); the biceps and
    # brachialis make at least 3 cm of muscle in front of the bone.
    up, front, outside = _humerus_frame(elbow)
    middle = 0.5 * float(np.linalg.norm(elbow.skeleton.shoulder))
    cut = {name: sliced.at(middle) for name, sliced in sections[flexion].items()}
    points = np.concatenate([segments.reshape(-1, 3) for segments in cut.values()])
    across = points - np.outer(points @ up, up)
    muscle = np.concatenate([cut[name].reshape(-1, 3) for name in elbow.names])
    muscle -= np.outer(muscle @ up, up)
    assert np.linalg.norm(muscle, axis=1).max() <= 5.0
    assert hull_perimeter(np.column_stack([across @ front, across @ outside])) <= 28.0
    in_front = sum(thickness_along(cut[name], middle * up, front, up)
                   for name in elbow.names if len(cut[name]))
    assert in_front >= 3.0


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_the_biceps_lies_in_front_as_one_belly_over_a_smaller_brachialis(elbow, sections,
                                                                       flexion):
    up, front, _ = _humerus_frame(elbow)
    parts = sections[flexion]
    middle = 0.5 * float(np.linalg.norm(elbow.skeleton.shoulder))
    for level in np.arange(4.0, 20.01, 1.0):
        cut = {name: parts[name].at(level) for name in elbow.names}
        frontmost = max((name for name in elbow.names if len(cut[name])),
                        key=lambda name: (cut[name].reshape(-1, 3) @ front).max())
        assert frontmost in BICEPS, (level, frontmost)
        if level <= middle:  # the lower half: the two heads one belly
            apart = centroid(cut["BIClong"], up) - centroid(cut["BICshort"], up)
            assert np.linalg.norm(apart) <= 2.5, level
    largest = {"BRA": 0.0, "biceps": 0.0}
    for level in np.arange(0.25, 30.0, 0.5):
        cut = {name: parts[name].at(level) for name in (*BICEPS, "BRA")}
        areas = {name: area(segments, up) if len(segments) else 0.0
                 for name, segments in cut.items()}
        largest["BRA"] = max(largest["BRA"], areas["BRA"])
        largest["biceps"] = max(largest["biceps"], areas["BIClong"] + areas["BICshort"])
    assert largest["BRA"] <= largest["biceps"]


@pytest.mark.parametrize("flexion", FLEXIONS)
def test_every_tendon_ends_on_its_own_bone_and_inside_no_other(elbow, posed, flexion):
    arm = elbow.at_flexion(flexion)
    parts = posed[flexion]
    for name, muscle, path in zip(arm.names, arm.muscles, arm.paths):
        for point, bone, radius in zip(path.ends(flexion), arm26.BONES[name],
                                       muscle.radii[[0, -1]]):
            assert winding(point, parts[bone]) > 0.5 or distance(point, parts[bone]) <= 0.1, \
                (name, bone)
            for other in BONES:
                if other != bone:
                    assert winding(point, parts[other]) < 0.5, (name, other)
            # The muscle's drawn tendon ends there, not elsewhere.
            nearest = np.linalg.norm(parts[name].vertices - point, axis=1).min()
            assert nearest <= radius + 0.1, (name, bone)


@pytest.mark.parametrize("flexion", [0.0, 60.0, 130.0])
def test_each_muscle_lies_on_its_own_side_of_the_humerus(elbow, flexion):
    # The brachialis on the front of the humerus, the biceps over it; the triceps' medial
    # head on its back, the lateral head outside, the long head inside.
    arm = elbow.at_flexion(flexion)
    parts = arm_parts(arm, SEGMENTS)
    up, front, outside = _humerus_frame(arm)
    middle = {name: parts[name].vertices.mean(axis=0) for name in arm.names}
    x = {name: float(point @ front) for name, point in middle.items()}
    z = {name: float(point @ outside) for name, point in middle.items()}
    assert x["BRA"] > 0.0 and x["BICshort"] > 0.0 and x["BIClong"] > 0.0
    assert max(x["TRImed"], x["TRIlat"], x["TRIlong"]) < 0.0
    assert z["TRIlong"] < z["TRImed"] < z["TRIlat"]


def test_no_muscle_jumps_as_the_elbow_bends_a_degree(elbow):
    before = None
    for flexion in np.arange(0.0, 130.5, 1.0):
        parts = arm_parts(elbow.at_flexion(float(flexion)), SEGMENTS)
        centres = {name: parts[name].vertices[1:-1].reshape(-1, SEGMENTS, 3).mean(axis=1)
                   for name in elbow.names}
        for name in elbow.names if before else ():
            step = np.linalg.norm(centres[name] - before[name], axis=1).max()
            assert step <= 0.75, (name, flexion, step)
        before = centres


def test_a_companion_follows_the_elbow_from_the_file_on(tmp_path):
    # Its nodes are its shape at 5 cm; loaded, it is where the elbow puts it.
    path = tmp_path / "two.toml"
    path.write_text("[muscle]\nlength = 33.0\nnodes = [[0.35, 0.0], [2.0, 2.0], [0.35, 0.0]]\n\n"
                    "[muscles.x]\nlength = 5.0\nnodes = [[0.5, 0.0], [0.6, 0.5], [0.5, 0.0]]\n"
                    "origin = [15.0, 0.5, 0.0]\ninsertion = [3.0, 0.5, 0.0]\n")
    arm = load_config(path).arm
    companion = arm.companions[0]
    assert companion.muscle.reference_length == 5.0
    assert companion.muscle.length == pytest.approx(companion.path.length_at(arm.flexion))
    assert companion.muscle.volume == pytest.approx(companion.muscle.reference_volume, rel=1e-12)


def test_an_edit_that_leaves_a_companion_unable_to_follow_the_elbow_is_refused(elbow):
    index = elbow.names.index("TRIlong")
    triceps = elbow.muscles[index]
    # Its belly all but gone, its tendons kept: stretched as far as the bent elbow takes it,
    # the belly would have to thin past nothing to keep the volume.
    thin = triceps
    for node in np.flatnonzero(triceps.growth > 0):
        thin = thin.with_radius(int(node), 0.05)
    with pytest.raises(RefusedChange, match="TRIlong would have to stretch"):
        elbow.with_muscle_at(index, thin)
    assert elbow.muscles[index] is triceps


def test_every_muscles_length_and_moment_arm_are_its_paths(elbow):
    arm = elbow.at_flexion(70.0)
    assert arm.lengths == tuple(muscle.length for muscle in arm.muscles)
    for path, length, moment_arm in zip(arm.paths, arm.lengths, arm.moment_arms):
        assert length == pytest.approx(path.length_at(70.0), rel=1e-12)
        assert moment_arm == pytest.approx(path.moment_arm_at(70.0), rel=1e-12)
    assert arm.moment_arms[0] == pytest.approx(arm.moment_arm, rel=1e-12)
    assert all(arm.moment_arms[arm.names.index(name)] > 0 for name in FLEXORS)
    assert all(arm.moment_arms[arm.names.index(name)] < 0 for name in EXTENSORS)


@pytest.mark.parametrize("flexion", [0.0, 30.0, 60.0, 90.0, 130.0])
def test_the_heads_tendons_end_flat_side_by_side_as_one(elbow, flexion):
    # Round cords would be as wide along the hinge as thick across it; the heads' parts of
    # one tendon are flat along it (BAND times, less where the last section still turns
    # from the round), and each side part lies against the part beside it.
    from biceps.engine.layers import CAP_RINGS, HINGE, SECTIONS

    arm = elbow.at_flexion(flexion)
    parts = arm_parts(arm, SEGMENTS)
    last = {}
    for name in (*BICEPS, *EXTENSORS):
        grid = parts[name].vertices[1:-1].reshape(-1, SEGMENTS, 3)
        ring, before = grid[CAP_RINGS - 1 + SECTIONS - 1], grid[CAP_RINGS - 1 + SECTIONS - 2]
        ahead = ring.mean(axis=0) - before.mean(axis=0)
        ahead /= np.linalg.norm(ahead)
        wide = HINGE - (ahead @ HINGE) * ahead
        wide /= np.linalg.norm(wide)
        flatness = np.ptp(ring @ wide) / np.ptp(ring @ np.cross(ahead, wide))
        assert flatness >= (1.05 if name == "TRImed" else 1.4), (name, flatness)
        last[name] = ring
    for side, middle in (("BIClong", "BICshort"), ("TRIlat", "TRImed"), ("TRIlong", "TRImed")):
        gaps = np.linalg.norm(last[side][:, None] - last[middle][None], axis=2).min()
        assert gaps <= 0.1, (side, middle, gaps)
