"""Configuration files: the bundled ones load, saving is safe (bad files: tests/cli/test_invalid_configs.py)."""

import math
import stat
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from biceps.engine.config import load_config, save_config
from biceps.engine.errors import BicepsError, ConfigError, FileError
from biceps.engine.skeleton import Skeleton
from biceps.engine.config import BUNDLED


@pytest.mark.parametrize("name", ["biceps.toml", "toy.toml", "fine.toml"])
def test_bundled_configs_load(name):
    config = load_config(BUNDLED / name)
    assert config.arm.muscle.volume_error == 0.0


def test_default_config_is_a_realistic_biceps():
    arm = load_config(BUNDLED / "biceps.toml").arm
    assert 150 <= arm.muscle.volume <= 250
    assert arm.muscle.growth[0] == arm.muscle.growth[-1] == 0
    shortest, longest = arm.length_range()
    # SPEC 2.3: about 35.6 cm straight to 27.1 cm fully bent; arm26's BIClong shortens by
    # 8.39 cm over the range.
    assert shortest == pytest.approx(27.1, abs=0.2) and longest == pytest.approx(35.6, abs=0.3)
    assert longest - shortest == pytest.approx(8.39, abs=0.2)
    assert 12 <= np.pi * arm.muscle.max_radius**2 <= 15  # mid-arm cross-section, cm^2


def test_the_default_skeleton_is_the_bundled_files():
    # The file spells out every key of [skeleton], so a reader sees the model's values.
    assert load_config(BUNDLED / "biceps.toml").arm.skeleton == Skeleton()


def test_fine_config_has_60_nodes_and_toy_has_4():
    assert load_config(BUNDLED / "fine.toml").arm.muscle.node_count == 60
    assert load_config(BUNDLED / "toy.toml").arm.muscle.node_count == 4


def test_flexion_sets_the_length(tmp_path):
    path = tmp_path / "flexed.toml"
    path.write_text("[muscle]\nflexion = 90.0\nnodes = [[0.5, 0.0], [2.0, 1.0], [0.5, 0.0]]\n")
    arm = load_config(path).arm
    assert arm.flexion == pytest.approx(90.0)


def _save(config, arm=None, path=None, **settings):
    return save_config(
        config, arm or config.arm, settings.get("view", config.view),
        settings.get("light", config.light), settings.get("render", config.render), path,
    )


@pytest.fixture
def user_copy(tmp_path) -> Path:
    path = tmp_path / "mine.toml"
    path.write_text((BUNDLED / "biceps.toml").read_text())
    return path


def test_save_then_load_gives_the_same_model(user_copy):
    config = load_config(user_copy)
    edited = config.arm.at_length(30.0)
    edited = edited.with_muscle(edited.muscle.with_radius(7, 2.5).subdivided())
    saved = _save(config, edited)
    again = load_config(user_copy)
    assert np.array_equal(again.arm.muscle.radii, edited.muscle.radii)
    assert np.array_equal(again.arm.muscle.growth, edited.muscle.growth)
    assert again.arm.length == edited.length
    assert again.arm.muscle.volume == pytest.approx(edited.muscle.volume, rel=1e-12)
    assert saved.source == user_copy.read_text()


def test_saving_keeps_the_users_comments_and_layout(user_copy):
    config = load_config(user_copy)
    _save(config, config.arm.at_length(31.0), view=replace(config.view, yaw=40.0))
    text = user_copy.read_text()
    assert "# A human biceps brachii on the arm skeleton of OpenSim's arm26 model." in text
    assert "upper_arm = 29.1            # humerus, the elbow's centre to the humeral head's" in text
    assert "\nlength = 33.0\n" in text  # the shape as written
    assert "\npose_length = 31.0\n" in text  # the pose it is shown in
    assert "yaw = 40.0" in text
    assert "nodes = [\n" in text  # still one node per line
    assert "# proximal tendon" in text and "# distal tendon, on the radius" in text


def test_saving_unchanged_writes_the_same_text(user_copy):
    before = user_copy.read_text()
    _save(load_config(user_copy))
    assert user_copy.read_text() == before


def test_saving_writes_only_what_differs_from_the_defaults(tmp_path):
    path = tmp_path / "short.toml"
    path.write_text("[muscle]\nlength = 33.0\nradius = [0.5, 2.0, 0.5]\ngrowth = [0, 1, 0]\n")
    config = load_config(path)
    _save(config, light=replace(config.light, position=(1.0, 2.0, 3.0)))
    text = path.read_text()
    assert "[light]\nposition = [1.0, 2.0, 3.0]" in text
    assert "[view]" not in text and "[render]" not in text
    assert load_config(path).light.position == (1.0, 2.0, 3.0)


def test_save_as_writes_a_new_file_and_leaves_the_original(user_copy, tmp_path):
    before = user_copy.read_text()
    config = load_config(user_copy)
    other = tmp_path / "other.toml"
    saved = _save(config, config.arm.at_length(29.0), path=other)
    assert saved.path == other
    assert user_copy.read_text() == before
    assert load_config(other).arm.length == pytest.approx(29.0)


def test_a_failed_save_leaves_the_file_and_no_temporary(user_copy):
    before = user_copy.read_text()
    config = load_config(user_copy)
    missing_dir = user_copy.parent / "no" / "such" / "dir" / "x.toml"
    with pytest.raises(FileError, match="cannot write"):
        _save(config, config.arm.at_length(29.0), path=missing_dir)
    assert user_copy.read_text() == before
    assert [p.name for p in user_copy.parent.iterdir()] == [user_copy.name]


def _forged(setting, **fields):
    """``setting`` with ``fields`` set past its checks, as a bug elsewhere might leave it."""
    setting = replace(setting)
    for name, value in fields.items():
        object.__setattr__(setting, name, value)
    return setting


def _limits_lifted(config):
    """The arm at 28 cm, shorter than the file's min_length = 30 allows."""
    return replace(config.arm, min_length=None).at_length(28.0)


# What a save must refuse, and what it must say: settings that slipped past their checks,
# and arms the file cannot hold although each value in them is fine on its own.
INVALID_SAVES = {
    "fov 500": (lambda c: {"view": _forged(c.view, fov=500.0, scale=-3.0)},
                "view.fov: must be a finite number above 1 and below 170 degrees (found 500.0)"),
    "light at infinity": (lambda c: {"light": _forged(c.light, position=(0.0, 0.0, math.inf))},
                          "light.position[2]: must be a finite number from -1e+08 to 1e+08 cm"),
    "ssaa 9": (lambda c: {"render": _forged(c.render, ssaa=9)},
               "render.ssaa: must be a whole number from 1 to 4 (found 9)"),
    "unknown shading": (lambda c: {"render": _forged(c.render, shading="flat")},
                        "render.shading: Input should be 'gouraud' or 'phong' (found 'flat')"),
    "overdraw, a debugging view": (lambda c: {"render": replace(c.render, shading="overdraw")},
                                   "render.shading: Input should be 'gouraud' or 'phong'"),
    "colour": (lambda c: {"render": _forged(c.render, background="red")},
               "render.background: should be a colour written #rrggbb (found 'red')"),
    "negative bone": (lambda c: {"arm": replace(c.arm, skeleton=replace(c.arm.skeleton,
                                                                        forearm=-3.0))},
                      "skeleton.forearm: must be a finite number from 1e-06 to 1e+06 cm (found -3.0)"),
    "reversed joint range": (lambda c: {"arm": replace(c.arm, skeleton=replace(
                                 c.arm.skeleton, min_flexion=100.0, max_flexion=50.0))},
                             "skeleton.flexion_range: flexion range must satisfy"),
    "length below the file's min_length": (lambda c: {"arm": _limits_lifted(c)},
                                           "muscle.pose_length: length 28.00 cm is outside"),
}


@pytest.mark.parametrize("case", INVALID_SAVES)
@pytest.mark.parametrize("save_as", [False, True], ids=["save", "save as"])
def test_saving_anything_invalid_leaves_every_file_as_it_was(user_copy, case, save_as):
    user_copy.write_text(user_copy.read_text().replace("# min_length = 28.0",
                                                       "min_length = 30.0"))
    before = user_copy.read_bytes()
    config = load_config(user_copy)
    make_changes, message = INVALID_SAVES[case]
    changes = make_changes(config)
    target = user_copy.parent / "copy.toml" if save_as else None
    with pytest.raises(BicepsError) as refusal:
        _save(config, changes.pop("arm", None), target, **changes)
    assert str(refusal.value).startswith("not saved (nothing was written): ")
    assert message in str(refusal.value)
    assert user_copy.read_bytes() == before
    assert [p.name for p in user_copy.parent.iterdir()] == [user_copy.name]


def test_saving_keeps_the_files_permissions(user_copy):
    user_copy.chmod(0o640)
    config = load_config(user_copy)
    _save(config, config.arm.at_length(29.0))
    assert stat.S_IMODE(user_copy.stat().st_mode) == 0o640


def test_a_missing_file_is_refused(tmp_path):
    with pytest.raises(FileError, match="no such file"):
        load_config(tmp_path / "nope.toml")


def _with(path: Path, old: str, new: str) -> Path:
    path.write_text(path.read_text().replace(old, new))
    return path


def test_the_pose_is_the_shape_contracted_or_stretched_at_constant_volume(user_copy):
    config = load_config(_with(user_copy, "pose_length = 33.0", "pose_length = 31.0"))
    muscle = config.arm.muscle
    assert (muscle.reference_length, muscle.length) == (33.0, 31.0)
    assert muscle.reference_radii[7] == 2.08  # the shape as written
    assert np.array_equal(muscle.radii, muscle.at_length(33.0).at_length(31.0).radii)


def test_a_pose_may_be_a_flexion(user_copy):
    config = load_config(_with(user_copy, "pose_length = 33.0", "pose_flexion = 90.0"))
    assert config.arm.flexion == pytest.approx(90.0)
    assert config.arm.muscle.reference_length == 33.0


@pytest.mark.parametrize(("pose", "message"), [
    ("pose_length = 50.0", ":19: muscle.pose_length: length 50.00 cm is outside"),
    ("pose_flexion = 150.0", ":19: muscle.pose_flexion: 150 degrees is outside"),
    ("pose_length = 31.0\npose_flexion = 90.0", "give at most one of pose_length (cm) and"),
])
def test_a_pose_the_arm_cannot_take_is_refused_where_it_is_written(user_copy, pose, message):
    with pytest.raises(ConfigError) as refusal:
        load_config(_with(user_copy, "pose_length = 33.0", pose))
    assert message in str(refusal.value)


def test_a_file_without_a_pose_shows_the_shape_as_written(user_copy):
    config = load_config(_with(user_copy, "pose_length = 33.0", ""))
    assert config.arm.length == config.arm.muscle.reference_length == 33.0


def test_saving_a_contraction_changes_the_pose_alone(user_copy):
    before = user_copy.read_text().splitlines()
    config = load_config(user_copy)
    _save(config, config.arm.at_length(31.0))
    after = user_copy.read_text().splitlines()
    assert [(a, b) for a, b in zip(before, after) if a != b] == [
        ("pose_length = 33.0", "pose_length = 31.0")]
    assert len(after) == len(before)


def test_saving_a_contraction_into_a_file_without_a_pose_adds_one_line(tmp_path):
    path = tmp_path / "toy.toml"
    path.write_text((BUNDLED / "toy.toml").read_text())
    before = path.read_text().splitlines()
    config = load_config(path)
    _save(config, config.arm.at_length(9.0))
    after = path.read_text().splitlines()
    added = [line for line in after if line not in before]
    assert len(after) == len(before) + 1
    assert added == ["pose_length = 9.0  # cm as shown: the shape above, contracted or "
                     "stretched at constant volume"]
    assert load_config(path).arm.length == 9.0


def test_a_node_edit_in_a_pose_saves_that_pose_as_the_new_shape(user_copy):
    config = load_config(user_copy)
    contracted = config.arm.at_length(31.0)
    edited = contracted.with_muscle(contracted.muscle.with_radius(7, 2.5))
    _save(config, edited)
    text = user_copy.read_text()
    assert "\nlength = 31.0\n" in text and "\npose_length = 31.0\n" in text
    again = load_config(user_copy).arm.muscle
    assert np.array_equal(again.radii, edited.muscle.radii)
    assert again.reference_length == 31.0


def test_a_shape_given_by_flexion_keeps_its_flexion_through_a_contraction(tmp_path):
    path = tmp_path / "flexed.toml"
    path.write_text("[muscle]\nflexion = 63.0\nnodes = [[0.5, 0.0], [2.0, 1.0], [0.5, 0.0]]\n")
    config = load_config(path)
    _save(config, config.arm.at_flexion(90.0))
    text = path.read_text()
    assert "\nflexion = 63.0\n" in text
    assert load_config(path).arm.flexion == pytest.approx(90.0)


def test_an_arm26_elbow_saves_its_edits_and_nothing_of_the_simple_skeleton(tmp_path):
    # arm26's skeleton brings its bones: saving writes back the muscles, never the simple
    # skeleton's lengths and attachments, which its [skeleton] may not hold.
    path = tmp_path / "elbow.toml"
    path.write_text((BUNDLED / "elbow.toml").read_text())
    config = load_config(path)
    arm, _ = config.arm.stepped(-2.0)
    arm = arm.with_muscle_at(1, arm.muscles[1].with_radius(4, 2.6))
    save_config(config, arm, config.view, config.light, config.render)
    saved = path.read_text()
    skeleton = saved[saved.index("[skeleton]"):saved.index("[render]")]
    assert "upper_arm" not in skeleton and "origin_to_elbow" not in skeleton
    again = load_config(path).arm
    assert again.skeleton.model == "arm26" and again.driver_path is arm.driver_path
    np.testing.assert_allclose(again.muscles[1].radii, arm.muscles[1].radii, rtol=1e-12)
    assert again.flexion == pytest.approx(arm.flexion, abs=1e-9)
