import math

import numpy as np
import pytest
import trimesh
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from biceps.engine.mesh import (
    DEFAULT_SEGMENTS,
    Mesh,
    cylinder_mesh,
    muscle_mesh,
    revolved_mesh,
    sphere_mesh,
)

# SPEC 5: the reference biceps, 15 nodes over 33 cm, closed volume 258.270257251792 cm^3.
REFERENCE_RADII = np.array(
    [0.5, 0.6, 0.8, 1.2, 1.7, 2.1, 2.35, 2.4, 2.3, 2.0, 1.6, 1.1, 0.7, 0.5, 0.45]
)
REFERENCE_VOLUME = 258.270257251792

radii_lists = st.lists(st.floats(0.1, 5.0), min_size=2, max_size=60).map(np.array)
points = st.tuples(*[st.floats(-20.0, 20.0)] * 3).map(np.array)
directions = (
    st.tuples(*[st.floats(-1.0, 1.0)] * 3)
    .map(np.array)
    .filter(lambda v: np.linalg.norm(v) > 0.1)
    .map(lambda v: v / np.linalg.norm(v))
)
lengths = st.floats(0.5, 50.0)
# A random profile, placed from a random start along a random axis: @given(**placed, ...).
placed = {"radii": radii_lists, "start": points, "axis": directions, "length": lengths}
slow = settings(deadline=None)


@st.composite
def ring_offsets(draw, nodes: int) -> np.ndarray:
    """Random sideways moves (m, 3) for rings 1 to 4 per segment (the mesh keeps only their
    part within the rings' planes), up to 5 cm each way."""
    per_segment = draw(st.integers(1, 4))
    count = (nodes - 1) * per_segment + 1
    values = draw(st.lists(st.floats(-5.0, 5.0), min_size=3 * count, max_size=3 * count))
    return np.array(values).reshape(count, 3)


def moved_sideways(data, radii):
    """Offsets drawn for ``radii``, or None (the straight muscle)."""
    return data.draw(st.none() | ring_offsets(len(radii)), label="offsets")


def as_trimesh(mesh: Mesh) -> trimesh.Trimesh:
    return trimesh.Trimesh(mesh.vertices, mesh.triangles, process=False)


def frusta_volume(radii: np.ndarray, length: float) -> float:
    """SPEC 2.1: pi dx Q(R)."""
    r0, r1 = radii[:-1], radii[1:]
    return math.pi * length / (len(radii) - 1) * np.sum(r0 * r0 + r0 * r1 + r1 * r1) / 3


def polygon_factor(segments: int) -> float:
    """Area of a regular k-gon over that of its circumscribed circle."""
    return segments * math.sin(2 * math.pi / segments) / (2 * math.pi)


def axial_and_radial(mesh: Mesh, start, axis):
    """Each vertex's distance along the axis (n,) and offset from it (n, 3)."""
    offsets = mesh.vertices - start
    along = offsets @ axis
    return along, offsets - np.outer(along, axis)


@slow
@given(
    **placed,
    segments=st.integers(3, 40),
    caps=st.sampled_from(["round", "flat"]),
    cap_rings=st.none() | st.integers(1, 8),
    data=st.data(),
)
def test_muscle_is_one_closed_outward_surface(
    radii, start, axis, length, segments, caps, cap_rings, data
):
    offsets = moved_sideways(data, radii)
    mesh = muscle_mesh(radii, length, start, start + length * axis, segments, caps, cap_rings,
                       offsets)
    closed = as_trimesh(mesh)
    assert closed.is_watertight
    assert closed.is_winding_consistent
    assert closed.euler_number == 2  # a sphere's topology: no seam split open
    assert len(np.unique(mesh.triangles)) == len(mesh.vertices)  # no stray vertices
    assert closed.volume > 0  # counter-clockwise from outside


@slow
@given(**placed, segments=st.integers(3, 64), data=st.data())
def test_flat_capped_volume_is_the_frusta_volume_of_the_polygon(
    radii, start, axis, length, segments, data
):
    # Each band between two aligned regular k-gons is a prismatoid: its volume is exactly
    # the frustum's times the k-gon's share of the circle, however far either k-gon is
    # moved within its plane (Cavalieri's principle: the muscle clear of the bones).
    offsets = moved_sideways(data, radii)
    mesh = muscle_mesh(radii, length, start, start + length * axis, segments, caps="flat",
                       offsets=offsets)
    expected = frusta_volume(radii, length) * polygon_factor(segments)
    assert as_trimesh(mesh).volume == pytest.approx(expected, rel=1e-9)


def test_flat_capped_square_rod_has_hand_checked_volume():
    # A 4-gon inscribed in a unit circle is a square of area 2; 2 cm long: 4 cm^3.
    mesh = cylinder_mesh([0.0, 0.0, 0.0], [0.0, 2.0, 0.0], 1.0, segments=4, caps="flat")
    assert as_trimesh(mesh).volume == pytest.approx(4.0, rel=1e-12)


def test_round_capped_reference_muscle_holds_the_closed_volume_within_one_percent():
    mesh = muscle_mesh(REFERENCE_RADII, 33.0, [0.0, 30.2, 0.0], [0.0, -2.8, 0.0])
    volume = as_trimesh(mesh).volume
    # Every face is a chord of the true surface, so the mesh is a little smaller.
    assert 0.99 * REFERENCE_VOLUME < volume < REFERENCE_VOLUME


@slow
@given(**placed, data=st.data())
def test_round_capped_volume_is_within_one_percent_at_the_default_segments(
    radii, start, axis, length, data
):
    offsets = moved_sideways(data, radii)
    mesh = muscle_mesh(radii, length, start, start + length * axis, DEFAULT_SEGMENTS,
                       offsets=offsets)
    caps = 2 / 3 * math.pi * (radii[0] ** 3 + radii[-1] ** 3)
    expected = frusta_volume(radii, length) + caps
    assert as_trimesh(mesh).volume == pytest.approx(expected, rel=0.01)


def test_triangle_count_is_two_per_segment_per_ring():
    round_caps = muscle_mesh(REFERENCE_RADII, 33.0, [0, 0, 0], [0, 33, 0], segments=64)
    flat_caps = muscle_mesh(REFERENCE_RADII, 33.0, [0, 0, 0], [0, 33, 0], 64, caps="flat")
    # 15 node rings, and 16 - 1 more in each cap (cap_rings defaults to 64 / 4).
    assert round_caps.triangles.shape == (2 * 64 * 45, 3)
    assert flat_caps.triangles.shape == (2 * 64 * 15, 3)
    assert round_caps.triangles.dtype == np.int32


@slow
@given(**placed, caps=st.sampled_from(["round", "flat"]))
def test_normals_are_unit_and_point_away_from_the_axis(radii, start, axis, length, caps):
    mesh = muscle_mesh(radii, length, start, start + length * axis, 24, caps)
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-12)
    _, radial = axial_and_radial(mesh, start, axis)
    rings = slice(1, -1)  # the poles lie on the axis
    assert np.all(np.sum(mesh.normals[rings] * radial[rings], axis=1) > 0)


def test_cylinder_normals_are_radial():
    start, axis = np.array([1.0, 2.0, 3.0]), np.array([0.6, 0.0, 0.8])
    mesh = muscle_mesh(np.full(5, 1.5), 8.0, start, start + 8.0 * axis, 32)
    along, radial = axial_and_radial(mesh, start, axis)
    side = (along > -1e-9) & (along < 8.0 + 1e-9)
    assert side.sum() == 5 * 32
    np.testing.assert_allclose(mesh.normals[side], radial[side] / 1.5, atol=1e-12)


def test_cone_normals_tilt_back_by_the_slope():
    # Radius 1 to 3 over 8 cm: slope 1/4, so the side normal leans atan(1/4) towards the
    # narrow end: axial component -sin(atan(1/4)) = -1/sqrt(17).
    start, axis = np.array([0.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    mesh = muscle_mesh(np.linspace(1.0, 3.0, 5), 8.0, start, 8.0 * axis, 16, caps="flat")
    np.testing.assert_allclose(mesh.normals[1:-1] @ axis, -1 / math.sqrt(17), atol=1e-12)


def test_round_cap_seam_normal_splits_the_crease_between_cap_and_side():
    # The cap's equator normal is radial and the cone's leans atan(1/4): the shared ring
    # leans half that.
    axis = np.array([0.0, 0.0, 1.0])
    mesh = muscle_mesh(np.linspace(1.0, 3.0, 5), 8.0, [0, 0, 0], 8.0 * axis, 16)
    along = mesh.vertices @ axis
    seam = np.abs(along) < 1e-12
    assert seam.sum() == 16
    half_tilt = math.atan(0.25) / 2
    np.testing.assert_allclose(mesh.normals[seam] @ axis, -math.sin(half_tilt), atol=1e-12)


def test_poles_face_along_the_axis():
    axis = np.array([0.0, -1.0, 0.0])
    mesh = muscle_mesh([0.5, 2.0, 0.4], 10.0, [0, 5, 0], [0, -5, 0], 16)
    np.testing.assert_allclose(mesh.vertices[[0, -1]], [[0, 5.5, 0], [0, -5.4, 0]], atol=1e-12)
    np.testing.assert_allclose(mesh.normals[[0, -1]], [-axis, axis])


@slow
@given(radii=radii_lists, start=points, end=points, segments=st.integers(3, 40))
def test_end_rings_sit_on_start_and_end_at_the_end_radii(radii, start, end, segments):
    length = np.linalg.norm(end - start)
    assume(length > 0.1)
    axis = (end - start) / length
    mesh = muscle_mesh(radii, length, start, end, segments)
    along, radial = axial_and_radial(mesh, start, axis)
    for position, radius in ((0.0, radii[0]), (length, radii[-1])):
        ring = np.abs(along - position) < 1e-9 * (1 + length)
        assert ring.sum() == segments
        centre = mesh.vertices[ring].mean(axis=0)
        np.testing.assert_allclose(centre, start + position * axis, atol=1e-9)
        np.testing.assert_allclose(np.linalg.norm(radial[ring], axis=1), radius, rtol=1e-12)


@pytest.mark.parametrize("angle", np.radians([0.0, 40.0, 90.0, 130.0]))
def test_rings_do_not_twist_as_the_elbow_bends(angle):
    # A quarter of the way round every ring, the vertex sits on +z (facing the camera),
    # whatever the direction of the muscle in the bending plane.
    end = np.array([5.4 * math.sin(angle), 5.4 * math.cos(angle), 0.0])
    start = np.array([0.0, 30.2, 0.0])
    mesh = muscle_mesh([1.0, 2.0], np.linalg.norm(end - start), start, end, 16, caps="flat")
    np.testing.assert_allclose(mesh.vertices[1 + 4], start + [0.0, 0.0, 1.0], atol=1e-12)


@slow
@given(axis=directions.filter(lambda a: a[0] > -0.9), nudge=directions)
def test_a_small_turn_of_the_axis_moves_the_mesh_a_little(axis, nudge):
    turned = axis + 1e-6 * nudge
    turned /= np.linalg.norm(turned)
    before = muscle_mesh([1.0, 2.0, 1.0], 10.0, [0, 0, 0], 10.0 * axis, 32)
    after = muscle_mesh([1.0, 2.0, 1.0], 10.0, [0, 0, 0], 10.0 * turned, 32)
    assert np.abs(after.vertices - before.vertices).max() < 1e-4


@pytest.mark.parametrize(
    "arguments, message",
    [
        (dict(segments=2), "segments"),
        (dict(radii=[1.0]), "2 nodes"),
        (dict(radii=[1.0, 0.0]), "positive"),
        (dict(radii=[1.0, np.nan]), "positive"),
        (dict(length=0.0), "length"),
        (dict(end=[0.0, 0.0, 0.0]), "distinct"),
        (dict(caps="pointy"), "caps"),
        (dict(cap_rings=0), "cap_rings"),
    ],
)
def test_muscle_refuses_degenerate_input(arguments, message):
    valid = dict(radii=[1.0, 2.0], length=5.0, start=[0, 0, 0], end=[0, 5, 0], segments=8)
    with pytest.raises(ValueError, match=message):
        muscle_mesh(**(valid | arguments))


def test_two_nodes_and_three_segments_make_a_closed_muscle():
    mesh = muscle_mesh([1.0, 2.0], 3.0, [0, 0, 0], [3, 0, 0], 3)
    assert as_trimesh(mesh).is_watertight


@pytest.mark.parametrize("caps", ["round", "flat"])
@pytest.mark.parametrize("segments", [3, 16, 48])
def test_rods_are_closed_and_outward(caps, segments):
    closed = as_trimesh(cylinder_mesh([1, 2, 3], [4, -2, 3], 0.8, segments, caps))
    assert closed.is_watertight and closed.is_winding_consistent and closed.volume > 0


@pytest.mark.parametrize("segments", [3, 4, 16, 48])
def test_spheres_are_closed_and_outward(segments):
    closed = as_trimesh(sphere_mesh([1, 2, 3], 1.4, segments))
    assert closed.is_watertight and closed.is_winding_consistent and closed.volume > 0


def test_sphere_normals_are_radial_and_volume_near_the_ball():
    center = np.array([1.0, 2.0, 3.0])
    mesh = sphere_mesh(center, 1.4)
    np.testing.assert_allclose(mesh.normals, (mesh.vertices - center) / 1.4, atol=1e-12)
    ball = 4 / 3 * math.pi * 1.4**3
    assert as_trimesh(mesh).volume == pytest.approx(ball, rel=0.01)


def test_rings_moved_sideways_tilt_their_normals_by_the_move():
    # A rod of radius 1 whose rings move 1 cm along +x for every 2 cm along the axis: on the
    # side facing +x the surface leans back by atan(1/2), on the side facing +y not at all.
    axis = np.array([0.0, 0.0, 1.0])
    offsets = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    mesh = muscle_mesh([1.0, 1.0, 1.0], 4.0, [0, 0, 0], 4.0 * axis, 4, "flat", offsets=offsets)
    middle = mesh.vertices[:, 2] == 2.0
    towards_x = middle & np.isclose(mesh.vertices[:, 0], 2.0)
    towards_y = middle & np.isclose(mesh.vertices[:, 1], 1.0)
    np.testing.assert_allclose(mesh.normals[towards_x], [[2 / math.sqrt(5), 0, -1 / math.sqrt(5)]],
                               atol=1e-12)
    np.testing.assert_allclose(mesh.normals[towards_y], [[0.0, 1.0, 0.0]], atol=1e-12)


def test_offsets_along_the_axis_are_dropped():
    axis = np.array([0.0, 0.0, 1.0])
    along = np.array([[0.0, 0.0, 3.0], [0.0, 0.0, -2.0]])
    moved = muscle_mesh([1.0, 2.0], 5.0, [0, 0, 0], 5.0 * axis, 8, offsets=along)
    straight = muscle_mesh([1.0, 2.0], 5.0, [0, 0, 0], 5.0 * axis, 8)
    np.testing.assert_allclose(moved.vertices, straight.vertices, atol=1e-12)


@pytest.mark.parametrize("offsets", [np.zeros((4, 3)), np.zeros((3, 2)), np.full((3, 3), np.nan)])
def test_offsets_that_do_not_fit_are_refused(offsets):
    with pytest.raises(ValueError, match="offsets"):
        muscle_mesh([1.0, 2.0, 1.0], 5.0, [0, 0, 0], [0, 0, 5], 8, offsets=offsets)


def test_a_revolved_profile_is_closed_with_its_hand_checked_volume():
    # A cylinder of radius 1, 2 long, as a profile with flat ends: a square (the 4-gon in
    # the unit circle, area 2) times 2.
    profile = [[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]]
    mesh = revolved_mesh(profile, [1.0, 2.0, 3.0], [0.0, 0.0, 5.0], segments=4)
    closed = as_trimesh(mesh)
    assert closed.is_watertight and closed.is_winding_consistent
    assert closed.volume == pytest.approx(4.0, rel=1e-12)


def test_a_revolved_profile_must_run_from_pole_to_pole():
    with pytest.raises(ValueError, match="pole"):
        revolved_mesh([[0.0, 1.0], [1.0, 1.0], [2.0, 0.0]], [0, 0, 0], [0, 1, 0])


def triangle(offset):
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]) + offset
    return Mesh(vertices, np.tile([0.0, 0.0, 1.0], (3, 1)), np.array([[0, 1, 2]]))


def test_concatenate_offsets_the_second_mesh_indices():
    joined = Mesh.concatenate([triangle(0.0), triangle(5.0)])
    assert joined.vertices.shape == (6, 3)
    np.testing.assert_array_equal(joined.triangles, [[0, 1, 2], [3, 4, 5]])
    np.testing.assert_array_equal(joined.vertices[3], [5.0, 5.0, 5.0])


def test_mesh_arrays_are_read_only():
    mesh = triangle(0.0)
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 1.0
