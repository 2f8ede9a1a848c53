"""The headless commands on the elbow's six muscles: info lists each, export-mesh writes each
as a part of its own, in its own colour."""

import json

import numpy as np
import pytest
import trimesh
from click.testing import CliRunner

from biceps.cli import main
from biceps.configs import FOLDER
from biceps.engine.config import load_config, rgb

ELBOW = FOLDER / "elbow.toml"
NAMES = ["BIClong", "BRA", "BICshort", "TRImed", "TRIlat",
         "TRIlong"]


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_info_json_lists_every_muscle_at_its_own_volume():
    result = run("info", ELBOW, "--flexion", "90", "--json")
    assert result.exit_code == 0, result.output
    facts = json.loads(result.stdout)
    assert [each["name"] for each in facts["muscles"]] == NAMES
    assert facts["muscles"][0]["length_cm"] == facts["length_cm"]  # the driver first
    for each in facts["muscles"]:
        assert each["volume_relative_error"] < 1e-12
    lengths = {each["name"]: each["length_cm"] for each in facts["muscles"]}
    straight = {each["name"]: each["length_cm"] for each in
                json.loads(run("info", ELBOW, "--flexion", "0", "--json").stdout)["muscles"]}
    assert lengths["TRIlong"] > straight["TRIlong"]
    assert lengths["BRA"] < straight["BRA"]


def test_info_lists_one_muscle_for_a_single_muscle_file():
    facts = json.loads(run("info", FOLDER / "biceps.toml", "--json").stdout)
    assert [each["name"] for each in facts["muscles"]] == ["muscle"]
    assert "muscles" not in run("info", FOLDER / "biceps.toml").stdout  # the text as it was


def test_info_prints_a_line_for_each_muscle():
    text = run("info", ELBOW).stdout
    for name in NAMES:
        assert f"    {name} " in text


def test_export_mesh_writes_each_muscle_as_a_named_part_in_its_colour(tmp_path):
    out = tmp_path / "elbow.glb"
    result = run("export-mesh", ELBOW, "-o", out, "--flexion", "60")
    assert result.exit_code == 0, result.output
    scene = trimesh.load(out, force="scene")
    assert set(scene.geometry) == {*NAMES, "scapula", "humerus", "radius", "ulna"}
    config = load_config(ELBOW)
    wanted = {"BIClong": config.render.muscle_colour,
              **{c.name: c.colour for c in config.arm.companions}}
    for name, colour in wanted.items():
        assert scene.geometry[name].is_watertight, name
        assert tuple(scene.geometry[name].visual.material.baseColorFactor[:3]) == rgb(colour)
    assert len(set(wanted.values())) == len(NAMES)  # colours tell them apart


def test_info_json_gives_each_muscles_moment_arm_widest_section_and_path():
    facts = json.loads(run("info", ELBOW, "--flexion", "90", "--json").stdout)
    arm = load_config(ELBOW).arm.at_flexion(90.0)
    for each, muscle, path, moment_arm in zip(facts["muscles"], arm.muscles, arm.paths,
                                              arm.moment_arms):
        assert each["moment_arm_cm"] == pytest.approx(moment_arm, rel=1e-12)
        assert each["widest_section_cm2"] == pytest.approx(3.141592653589793
                                                           * muscle.max_radius**2)
        points = np.array(each["path_points_cm"])
        start, end = path.ends(90.0)
        np.testing.assert_allclose(points[[0, -1]], [start, end], atol=1e-12)
        # The line through them is the path, but for its arcs drawn as chords.
        along = np.linalg.norm(np.diff(points, axis=0), axis=1).sum()
        assert along == pytest.approx(each["length_cm"], rel=1e-3)
    moment_arms = {each["name"]: each["moment_arm_cm"] for each in facts["muscles"]}
    assert moment_arms["BIClong"] > 0 > moment_arms["TRIlong"]
