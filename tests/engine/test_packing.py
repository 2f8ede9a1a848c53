"""The muscles' leans round the humerus: chosen once when an arm is made with muscles of new
shapes, carried by its poses, so that a pose's mesh is built without posing anything
again."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from biceps.engine.appearance import scene_mesh
from biceps.engine.arm import Arm
from biceps.engine.companion import Companion
from biceps.engine.config import load_config
from biceps.engine.muscle import Muscle
from biceps.engine.packing import chosen_leans

# Three muscles on the simple skeleton: the two laid over others each turn to their side.
THREE = """\
[muscle]
length = 33.0
nodes = [[0.35, 0.0], [2.0, 2.0], [0.35, 0.0]]

[muscles.x]
length = 5.0
nodes = [[0.5, 0.0], [0.6, 0.5], [0.5, 0.0]]
origin = [15.0, 0.5, 0.0]
insertion = [3.0, 0.5, 0.0]

[muscles.y]
length = 20.0
nodes = [[0.4, 0.0], [1.5, 1.0], [1.2, 1.0], [0.4, 0.0]]
origin = [20.0, -1.0, 0.5]
insertion = [4.0, -0.5, 0.5]
"""


@pytest.fixture(scope="module")
def three(tmp_path_factory):
    path = tmp_path_factory.mktemp("three") / "three.toml"
    path.write_text(THREE)
    return load_config(path)


def test_a_pose_keeps_its_arm_s_leans_and_an_edit_chooses_them_anew(three):
    arm = three.arm
    assert arm.leans.each[0] is None and None not in arm.leans.each[1:]
    assert arm.at_flexion(90.0).leans is arm.leans
    edited = arm.with_muscle_at(1, arm.muscles[1].with_radius(1, 0.8))
    assert edited.leans is not arm.leans and edited.leans.fit(edited)
    # However the shapes change, leans of other shapes are not kept.
    companions = (replace(arm.companions[0], muscle=edited.muscles[1]), arm.companions[1])
    changed = replace(arm, companions=companions)
    assert changed.leans is not arm.leans
    assert changed.leans.each == chosen_leans(changed).each


def test_a_mesh_is_built_without_posing_anything_again(three, monkeypatch):
    # Shapes no mesh has been built for yet.
    arm = three.arm.with_muscle_at(2, three.arm.muscles[2].with_radius(1, 1.6)).at_flexion(70.0)

    def posing(*args):
        raise AssertionError("the mesh posed the model again")

    for kind, method in ((Arm, "at_length"), (Arm, "at_flexion"),
                         (Companion, "at_flexion"), (Muscle, "at_length")):
        monkeypatch.setattr(kind, method, posing)
    mesh, albedo, _ = scene_mesh(arm, three.render)
    monkeypatch.undo()
    # The very mesh of the same pose of an arm made afresh.
    fresh = load_config(three.path).arm
    fresh = fresh.with_muscle_at(2, fresh.muscles[2].with_radius(1, 1.6)).at_flexion(70.0)
    expected_mesh, expected_albedo, _ = scene_mesh(fresh, three.render)
    np.testing.assert_array_equal(mesh.vertices, expected_mesh.vertices)
    np.testing.assert_array_equal(mesh.triangles, expected_mesh.triangles)
    np.testing.assert_array_equal(albedo, expected_albedo)
