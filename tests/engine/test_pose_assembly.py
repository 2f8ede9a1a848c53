"""A pose's meshes and colours, assembled with whole-array numpy, hold the very values the
plain formulas give (the pictures depend on them to the bit)."""

from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from biceps.engine.anatomy import arm_parts, tendon_share
from biceps.engine.appearance import companion_segments, scene_mesh, strain_colour
from biceps.engine.config import load_config, rgb
from biceps.engine.mesh import _lengths, _spokes, _spokes_along

ELBOW = load_config(Path(__file__).resolve().parents[2] / "configs" / "elbow.toml")


@given(arrays(np.float64, st.tuples(st.integers(1, 5), st.integers(1, 7), st.just(3)),
              elements=st.floats(-1e6, 1e6)))
def test_lengths_are_numpys_norms_to_the_bit(vectors):
    np.testing.assert_array_equal(_lengths(vectors),
                                  np.linalg.norm(vectors, axis=-1, keepdims=True))


def test_spokes_along_a_wrapped_path_are_each_rings_own():
    # The triceps' long head wraps round the back of the elbow at 130 degrees: its axes
    # repeat along the straight stretches and turn round the arc.
    index = ELBOW.arm.names.index("TRIlong")
    path = ELBOW.arm.paths[index]
    assert path.wraps(130.0)
    _, axes = path.centreline(130.0, 57)
    assert 2 < len(np.unique(axes, axis=0)) < len(axes)
    expected = np.stack([_spokes(axis, 48) for axis in axes])
    np.testing.assert_array_equal(_spokes_along(axes, 48), expected)


def test_each_muscle_blends_from_its_belly_into_its_tendons_the_rest_bone():
    arm = ELBOW.arm.at_flexion(45.0)
    hidden = frozenset({"BRA"})
    for colour_by in ("muscle", "strain"):
        render = ELBOW.render.__class__(**{**vars(ELBOW.render), "colour_by": colour_by})
        _, albedo, _ = scene_mesh(arm, render, hidden)
        parts = arm_parts(arm, render.segments, hidden, companion_segments(render.segments))
        bone = np.array(rgb(render.bone_colour), np.float32) / 255
        tendon_colour = np.array(rgb(render.tendon_colour), np.float32) / 255
        colours = (render.muscle_colour, *(c.colour for c in arm.companions))
        expected = {name: np.broadcast_to(bone, (len(mesh.vertices), 3))
                    for name, mesh in parts.items()}
        for name, muscle, path, colour in zip(arm.names, arm.muscles, arm.paths, colours):
            if name in hidden:
                continue
            belly = (strain_colour(muscle.length / muscle.reference_length - 1.0)
                     if colour_by == "strain" else np.array(rgb(colour), np.float32) / 255)
            tendon = tendon_share(muscle, path, arm.flexion, parts[name])[:, None]
            assert tendon.min() == 0.0 and tendon.max() == 1.0, name  # belly and tendon
            expected[name] = (1.0 - tendon) * belly + tendon * tendon_colour
        assert albedo.dtype == np.float32
        np.testing.assert_array_equal(albedo, np.concatenate(list(expected.values())))


def test_the_picture_draws_the_companions_with_fewer_segments_and_exports_keep_them_all():
    arm = ELBOW.arm.at_flexion(60.0)
    render = ELBOW.render
    around = companion_segments(render.segments)
    assert render.segments == 48 and around == 32
    mesh, _, _ = scene_mesh(arm, render)
    full = arm_parts(arm, render.segments)  # what export-mesh writes
    light = arm_parts(arm, render.segments, companion_segments=around)
    assert len(mesh.vertices) == sum(len(part.vertices) for part in light.values())
    assert len(mesh.vertices) < sum(len(part.vertices) for part in full.values())
    for name, part in light.items():  # the driver and the bones as before, the rest lighter
        same = name not in arm.names[1:]
        assert (len(part.vertices) == len(full[name].vertices)) == same, name
        if same:
            np.testing.assert_array_equal(part.vertices, full[name].vertices)
    # The same muscles, only more coarsely round: the same poles (where the tendons end on
    # bone; over an end section lying on the humerus, its 32-gon's centre is a hair from
    # its 48-gon's), the same extent to within how far a ring of 32 misses its section's
    # outline (a 2.5 cm circle's by 0.012 cm, a slice's tighter bends by up to 0.02 cm).
    for name in arm.names[1:]:
        np.testing.assert_allclose(light[name].vertices[[0, -1]], full[name].vertices[[0, -1]],
                                   atol=0.002)
        for bound in (np.min, np.max):
            np.testing.assert_allclose(bound(light[name].vertices, axis=0),
                                       bound(full[name].vertices, axis=0), atol=0.02)
