"""Every bad configuration is refused by every command that reads one (the app too, before
it takes the terminal): exit code 2, one message that names the file, the field and what
is allowed, no traceback, nothing written."""

import os
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from biceps.cli import main
from biceps.engine.bounds import MUSCLES, NODES
from biceps.engine.config import LARGEST_FILE

INVALID = Path(__file__).resolve().parents[1] / "invalid_configs"

# Each broken file in tests/invalid_configs, and what the message must say about it.
INVALID_CASES = {
    "arm26_beyond_its_range.toml": (":9: skeleton.flexion_range: arm26's elbow bends from 0 to "
                                    "130 degrees"),
    "arm26_companion_with_origin.toml": (":10: muscles.BRA: path = \"arm26\" gives the muscle "
                                         "its attachments and wraps: remove origin"),
    "arm26_driver_without_path.toml": (":1: muscle: with skeleton.model = \"arm26\" the "
                                       "[muscle] takes arm26's path: add path = \"arm26\""),
    "arm26_extensor_drives.toml": (":3: muscle.path: TRIlong lengthens as the elbow bends at 0 "
                                   "degrees: the [muscle] drives the elbow by its length, so it "
                                   "must be a flexor"),
    "arm26_path_without_arm26.toml": (":3: muscle.path: path = \"arm26\" needs arm26's bones: "
                                      "add model = \"arm26\" under [skeleton]"),
    "arm26_unknown_muscle.toml": (":3: muscle.path: arm26 has no muscle 'biceps': a muscle on "
                                  "arm26's path is named as arm26 names it, one of BIClong, "
                                  "BICshort, BRA, TRIlong, TRIlat, TRImed"),
    "arm26_with_bone_lengths.toml": (":7: skeleton: model = \"arm26\" brings arm26's own bones "
                                     "and attachments: remove upper_arm"),
    "after_a_list_of_nodes.toml": ":9: muscle.max_length: must be a finite number above 0 cm "
                                  "(found 'long')",
    "all_zero_growth.toml": ":3: muscle.nodes: at least one node needs a growth of 1e-06 or "
                            "more",
    "bad_colour.toml": ":6: render.muscle_colour: should be a colour written #rrggbb (found 'red')",
    "bad_graphics.toml": (":6: render.graphics: Input should be 'halfblocks', 'auto', 'kitty',"
                          " 'sixel', 'iterm', 'sextants' or 'quadrants' (found 'png')"),
    "bad_shading.toml": ":6: render.shading: Input should be 'gouraud' or 'phong' (found 'flat')",
    "companion_bad_name.toml": ("muscles.long head: a muscle's name is 1 to 40 letters, digits, "
                                "'_' or '-' (found 'long head')"),
    "companion_inside_wrap.toml": (":9: muscles.brachialis.insertion: lies 1.05 cm from the "
                                   "elbow's axis, inside the wrapping cylinder"),
    "companion_no_growth.toml": ":7: muscles.brachialis.nodes: at least one node needs a growth",
    "companion_same_name.toml": ":5: muscles.muscle: 'muscle' is the [muscle]'s name already",
    "companion_short_origin.toml": ":8: muscles.brachialis.origin[2]: required, but missing",
    "companion_too_thin.toml": (":7: muscles.brachialis.nodes: brachialis would have to stretch "
                                "to"),
    "companion_unknown_key.toml": (":10: muscles.brachialis.warp: unknown key 'warp' (did you "
                                   "mean 'wrap'?); allowed here: volume, length, flexion, nodes, "
                                   "radius, growth, path, origin, insertion, wrap, wrap_radius, colour"),
    "companion_wrap_without_radius.toml": ":5: muscles.brachialis: wrap and wrap_radius go together",
    "bones_out_of_proportion.toml": (":6: skeleton.upper_arm: 1e+06 cm is more than 4 times "
                                     "the forearm's 25.4 cm"),
    "companion_at_the_elbow.toml": (":9: muscles.brachialis.insertion: origin and insertion "
                                    "come within 0.5 cm of each other"),
    "companion_off_its_bone.toml": (":8: muscles.brachialis.origin: 1e+07 cm along the upper "
                                    "arm is off the bone, 29.1 cm long: an attachment lies "
                                    "from -7.275 to 36.375 cm along it"),
    "companion_past_the_hand.toml": (":9: muscles.brachialis.insertion: 525.4 cm along the "
                                     "forearm is off the bone, 25.4 cm long"),
    "companions_on_one_path.toml": (":15: muscles.brachialis2.origin: runs where brachialis "
                                    "runs, from the same origin to the same insertion"),
    "flexion_range_a_hair_wide.toml": (":6: skeleton.flexion_range: 60 to 60.000000001 degrees "
                                       "is 1e-09 degrees wide; the elbow needs at least 1"),
    "huge_yaw.toml": ":6: view.yaw: must be a finite number from -360 to 360 degrees (found "
                     "1e+308)",
    "limits_a_hair_apart.toml": (":2: muscle.min_length: the limits leave no length: "
                                 "min_length, max_length and the joint's range intersect to "
                                 "nothing (31 > 30.999 cm)"),
    "muscle_name_with_a_space.toml": (":2: muscle.name: a muscle's name is 1 to 40 letters, "
                                      "digits, '_' or '-' (found 'long head')"),
    "origin_off_the_humerus.toml": (":6: skeleton.origin_to_elbow: 100 cm along the upper arm "
                                    "is off the bone"),
    "too_many_vertices.toml": (":6: render.segments: 1,000 nodes at 1,024 segments round each "
                               "make 1,024,000 vertices; at most 1,000,000 are drawn"),
    "binary_junk.toml": "not a text file (byte 0 is not UTF-8); a configuration is a TOML text",
    "boolean_scale.toml": ":6: view.scale: must be a finite number from 0.01 to 100 (found True)",
    "broken_toml.toml": "not valid TOML",
    "byte_order_mark.toml": ": starts with a byte-order mark (bytes EF BB BF), which TOML does "
                            "not allow: save it as UTF-8 without a byte-order mark",
    "deep_arrays.toml": ":3: muscle.nodes: arrays or tables nested more than 64 deep; a "
                        "configuration needs at most 2",
    "deep_inline_tables.toml": ":6: view.offset: arrays or tables nested more than 64 deep",
    "dotted_key_in_another_table.toml": ":5: muscle.skeleton: unknown key 'skeleton' ([skeleton] "
                                        "is a table of its own: write its keys under a "
                                        "[skeleton] header); allowed here: volume, length,",
    "dotted_key_table.toml": ":4: muscle.nodes: Input should be a valid list (found a table)",
    "dotted_keys_bad_growth.toml": ":3: muscle.nodes[1][1]: must be a finite number from 0 to "
                                   "10000 (found -1.0)",
    "empty.toml": "the [muscle] table is required, but missing",
    "escape_in_a_key.toml": r": muscle.\x1b]52;c;UFdORUQ=\x07\x1b[2J: unknown key "
                            r"'\x1b]52;c;UFdORUQ=\x07\x1b[2J'; allowed here: volume,",
    "far_light.toml": ":6: light.position[1]: must be a finite number from -1e+08 to 1e+08 cm "
                      "(found 1e+308)",
    "far_offset.toml": ":6: view.offset[0]: must be a finite number from -1e+08 to 1e+08 cm "
                       "(found 1e+308)",
    "flexion_outside_range.toml": ":2: muscle.flexion: 150 degrees is outside "
                                  "skeleton.flexion_range, 0 to 130",
    "forces_for_no_muscle.toml": (":5: forces.BRA: no muscle is named 'BRA' in this file; its "
                                  "muscles are muscle"),
    "forces_missing_for_a_new_muscle.toml": (
        ":13: forces.brachialis: max_isometric_force, optimal_fibre_length and "
        "tendon_slack_length are required: arm26 has no muscle named 'brachialis' to take "
        "them from (its six: BIClong, BICshort, BRA, TRIlong, TRIlat, TRImed)"),
    "forces_negative_force.toml": (":6: forces.muscle.max_isometric_force: must be a finite "
                                   "number from 0.001 to 100000 N (found -3)"),
    "fractional_segments.toml": ":6: render.segments: must be a whole number from 3 to 1024 "
                                "(found 48.5)",
    "huge_bones.toml": ":6: skeleton.upper_arm: must be a finite number from 1e-06 to 1e+06 cm "
                       "(found 1e+300)",
    "huge_integer.toml": ":3: muscle.nodes[1][0]: must be a finite number from 1e-06 to 10000 cm "
                         "(found a 400-digit integer)",
    "huge_radius.toml": ":4: muscle.nodes[1][0]: must be a finite number from 1e-06 to 10000 cm "
                        "(found 1e+300)",
    "huge_scale.toml": ":6: view.scale: must be a finite number from 0.01 to 100 (found 1e+300)",
    "infinite_length.toml": ":2: muscle.length: must be a finite number above 0 cm (found inf)",
    "insertion_past_the_hand.toml": ":7: skeleton.elbow_to_insertion: must be at most the "
                                    "forearm's length, 25.4 cm, not 30",
    "length_and_flexion.toml": "give exactly one of length (cm) and flexion (degrees)",
    "length_outside_range.toml": ":3: muscle.length: length 50.00 cm is outside what the "
                                 "skeleton and limits allow: ",
    "light_position_short.toml": ":6: light.position[2]: required",
    "limits_leave_nothing.toml": "muscle.min_length: the limits leave no length",
    "many_bad_nodes.toml": ":4: muscle.nodes[0][0]: must be a finite number from 1e-06 to "
                           "10000 cm (found -1)",
    "markup_in_a_key.toml": ": muscle.[@click=app.quit]q: unknown key '[@click=app.quit]q'; "
                            "allowed here: volume,",
    "mismatched_lists.toml": "radius has 3 values but growth has 2",
    "missing_muscle.toml": "the [muscle] table is required, but missing",
    "muscle_not_a_table.toml": ":1: muscle: Input should be a valid dictionary",
    "nan_radius.toml": ":3: muscle.radius[1]: must be a finite number from 1e-06 to 10000 cm "
                       "(found nan)",
    "negative_bone.toml": ":6: skeleton.forearm: must be a finite number from 1e-06 to 1e+06 cm "
                          "(found -3.0)",
    "negative_growth.toml": ":3: muscle.nodes[1][1]: must be a finite number from 0 to 10000 "
                            "(found -1.0)",
    "negative_radius.toml": ":3: muscle.nodes[2][0]: must be a finite number from 1e-06 to "
                            "10000 cm (found -0.5)",
    "no_length.toml": "give exactly one of length (cm) and flexion (degrees)",
    "nodes_and_lists.toml": "either as nodes or as radius and growth, not both",
    "one_node.toml": "muscle.nodes: a muscle needs at least 2 nodes, got 1",
    "reversed_flexion_range.toml": ":6: skeleton.flexion_range: flexion range must satisfy 0 <= "
                                   "min_flexion < max_flexion <= 180 degrees, got 120.0 to 10.0",
    "string_radius.toml": ":3: muscle.radius[0]: must be a finite number from 1e-06 to 10000 cm "
                          "(found '0.5')",
    "three_value_node.toml": "muscle.nodes[1]: Tuple should have at most 2 items",
    "tiny_growth.toml": ":4: muscle.nodes: at least one node needs a growth of 1e-06 or more, "
                        "or the muscle cannot change length at constant volume (the largest "
                        "here is 1e-160)",
    "tiny_radii.toml": ":4: muscle.nodes[0][0]: must be a finite number from 1e-06 to 10000 cm "
                       "(found 1e-162)",
    "unknown_key.toml": ":2: muscle.lenght: unknown key 'lenght' (did you mean 'length'?)",
    "unknown_table.toml": ":5: camera: unknown key 'camera'",
    "wrong_type_length.toml": ":2: muscle.length: must be a finite number above 0 cm (found "
                              "'thirty')",
    "wrong_volume_mode.toml": ":2: muscle.volume: Input should be 'closed' or 'frusta' (found "
                              "'open')",
    "zero_radius.toml": ":3: muscle.radius[1]: must be a finite number from 1e-06 to 10000 cm "
                        "(found 0.0)",
}


def _too_many_nodes(folder: Path) -> Path:
    path = folder / "too_many_nodes.toml"
    path.write_text("[muscle]\nlength = 33.0\nnodes = [\n" + "[1.0, 1.0],\n" * (NODES + 1) + "]\n")
    return path


def _companion(name: str, nodes: int = 3) -> str:
    return (f"[muscles.m{name}]\nflexion = 0.0\nnodes = [" + "[1.0, 1.0], " * nodes + "]\n"
            f"origin = [{10.0 + 0.1 * len(name)}, 1.0, 0.87]\ninsertion = [4.0, 1.0, 0.0]\n")


def _too_many_nodes_together(folder: Path) -> Path:
    path = folder / "too_many_nodes_together.toml"
    half = NODES // 2 + 1
    path.write_text("[muscle]\nlength = 33.0\nnodes = [" + "[1.0, 1.0], " * half + "]\n"
                    + _companion("1", half))
    return path


def _too_many_muscles(folder: Path) -> Path:
    path = folder / "too_many_muscles.toml"
    path.write_text("[muscle]\nlength = 33.0\nnodes = [[1.0, 1.0], [1.0, 1.0]]\n"
                    + "".join(_companion("x" * i) for i in range(1, MUSCLES + 1)))
    return path


def _too_large(folder: Path) -> Path:
    path = folder / "too_large.toml"
    with path.open("wb") as stream:  # sparse: the size without the disk
        stream.truncate(LARGEST_FILE + 1)
    return path


def _pipe(folder: Path) -> Path:
    path = folder / "pipe.toml"
    os.mkfifo(path)  # reading it would wait for a writer for ever
    return path


def _endless_device(folder: Path) -> Path:
    path = folder / "zero.toml"
    path.symlink_to("/dev/zero")  # reading it would never end
    return path


def _folder(folder: Path) -> Path:
    path = folder / "folder.toml"
    path.mkdir()
    return path


def _name_too_long(folder: Path) -> Path:
    return folder / ("x" * 300 + ".toml")


def _long_lines_of_spaces(folder: Path) -> Path:
    # Lines the error locator reads on its way to the bad value: patterns that backtrack
    # take for ever over each (n^3 in its length).
    path = folder / "spaces.toml"
    spaces = " " * 100_000
    path.write_text(f"[muscle]\n{spaces}\n{spaces}# [{spaces}\n{spaces}#\nlength = 'thirty'\n"
                    "nodes = [[0.4, 0.0], [2.0, 2.0], [0.4, 0.0]]\n")
    return path


# Files made for each test, as they cannot be kept in the repository, and what the message
# must say about each.
MADE_CASES = {
    "too many nodes": (_too_many_nodes, f":3: muscle.nodes: {NODES + 1:,} nodes; a model has "
                                        f"at most {NODES:,}, all its muscles together"),
    "too many nodes together": (_too_many_nodes_together, f":3: muscle.nodes: {NODES + 2:,} "
                                                          f"nodes; a model has at most {NODES:,}"),
    "too many muscles": (_too_many_muscles, f":4: muscles: {MUSCLES + 1} muscles; a model has "
                                            f"at most {MUSCLES}"),
    "too large": (_too_large, ": is larger than 1 MiB, too large to be a configuration"),
    "a pipe": (_pipe, ": is a pipe (FIFO), not a regular file"),
    "a link to /dev/zero": (_endless_device, ": is a character device, not a regular file"),
    "a folder": (_folder, ": is a directory, not a regular file"),
    "a name too long": (_name_too_long, ": the name is 305 bytes long; a file name here has at "
                                        "most 255"),
    "lines of 100,000 spaces": (_long_lines_of_spaces, ":5: muscle.length: must be a finite "
                                                       "number above 0 cm (found 'thirty')"),
}

COMMANDS = {
    "app": lambda out: ["app"],  # refused before the terminal is touched
    "info": lambda out: ["info"],
    "snapshot": lambda out: ["snapshot", "-o", out / "arm.png", "--size", "64x48"],
    "export-mesh": lambda out: ["export-mesh", "-o", out / "arm.obj"],
    "hold": lambda out: ["hold", "--mass", "1"],
}

# Every character a terminal acts on, but the newline that ends a line of the message.
CONTROL = re.compile(r"[\x00-\x09\x0b-\x1f\x7f-\x9f]")


def test_every_invalid_config_has_an_expected_message():
    assert sorted(INVALID_CASES) == sorted(p.name for p in INVALID.iterdir())


def _refused(command: str, path: Path, out: Path, expected: str) -> None:
    out.mkdir()
    result = CliRunner().invoke(main, [*map(str, COMMANDS[command](out)), str(path)])
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert result.stderr.startswith(f"biceps: {path}")
    assert expected in result.stderr
    assert len(result.stderr.splitlines()) <= 6  # one message, however many problems
    assert "Traceback" not in result.stderr
    assert not CONTROL.search(result.stderr)
    assert list(out.iterdir()) == []


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("name", sorted(INVALID_CASES))
def test_every_command_refuses_an_invalid_config(tmp_path, command, name):
    _refused(command, INVALID / name, tmp_path / "out", INVALID_CASES[name])


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("case", MADE_CASES)
def test_every_command_refuses_what_is_not_a_regular_file_of_sane_size(tmp_path, command,
                                                                         case):
    make, expected = MADE_CASES[case]
    _refused(command, make(tmp_path), tmp_path / "out", expected)


def test_thousands_of_bad_nodes_get_the_first_few_and_a_count():
    result = CliRunner().invoke(main, ["info", str(INVALID / "many_bad_nodes.toml")])
    lines = result.stderr.splitlines()
    assert len(lines) == 6
    assert [f"muscle.nodes[{i}][0]" in line for i, line in enumerate(lines[:5])] == [True] * 5
    assert lines[5].endswith("many_bad_nodes.toml: and 1,995 more problems like these")
