"""The headless commands: info, snapshot and export-mesh, as a script would use them."""

import importlib.metadata
import json
import re
from pathlib import Path

import numpy as np
import pytest
import trimesh
from click.testing import CliRunner
from PIL import Image

from biceps.cli import main
from biceps.engine.config import BUNDLED, DEFAULT_CONFIG



def run(*args: str):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.mark.parametrize("command", [["info", DEFAULT_CONFIG], ["snapshot", DEFAULT_CONFIG,
                                                                  "-o", "x.png"]])
def test_a_bad_thread_count_in_the_environment_is_refused_before_any_command(
        command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, [str(a) for a in command],
                                env={"BICEPS_THREADS": "many\x1b[2J"})
    assert result.exit_code == 2
    assert "biceps: BICEPS_THREADS is 'many\\x1b[2J': it takes a whole number" in result.output
    assert not (tmp_path / "x.png").exists()


def test_info_json_reports_the_pose_and_the_volume():
    result = run("info", DEFAULT_CONFIG, "--flexion", "90", "--json")
    assert result.exit_code == 0, result.output
    facts = json.loads(result.stdout)
    assert facts["flexion_deg"] == pytest.approx(90.0)
    assert facts["volume_relative_error"] < 1e-12
    assert facts["nodes"] == len(facts["radii_cm"]) == 15
    assert facts["girth_cm"] == pytest.approx(2 * np.pi * max(facts["radii_cm"]))
    assert facts["moment_arm_cm"] == pytest.approx(4.989, abs=0.001)  # arm26: 4.875


def test_info_shows_the_moment_arm():
    result = run("info", DEFAULT_CONFIG, "--flexion", "0")
    assert "elbow flexion  0.00 degrees, moment arm 0.641 cm" in result.stdout


def test_info_refuses_an_unreachable_length():
    result = run("info", DEFAULT_CONFIG, "--length", "50")
    assert result.exit_code == 2
    assert "26.94 to 35.42 cm" in result.stderr


def test_snapshot_writes_a_png_of_the_asked_size(tmp_path):
    out = tmp_path / "arm.png"
    result = run("snapshot", DEFAULT_CONFIG, "-o", out, "--size", "320x200", "--flexion", "45")
    assert result.exit_code == 0, result.output
    with Image.open(out) as picture:
        assert picture.size == (320, 200)
        pixels = np.asarray(picture.convert("RGB"))
    background = np.array([0x12, 0x16, 0x1C])
    assert (np.abs(pixels.astype(int) - background).sum(axis=2) > 30).any()  # something drawn


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--size", "0x0"], "each side must be 1 to 8192"),
        (["--size", "20000x100"], "each side must be 1 to 8192"),
        (["--size", "abc"], "'abc' is not a size: write it as 1920x1080"),
        (["--size", "12x"], "'12x' is not a size"),
        (["--light", "1,2"], "give X,Y,Z"),
        (["--light", "1,nan,2"], "finite"),
        (["--ssaa", "9"], "--ssaa"),
        (["--shading", "flat"], "--shading"),
        (["--length", "30", "--flexion", "20"], "not both"),
        (["--flexion", "170"], "outside the joint's range"),
        (["--flexion", "nan"], "--flexion"),
        (["--yaw", "inf"], "--yaw"),
        (["--scale", "nan"], "--scale"),
        (["--scale", "0"], "0.01 to 100"),
        (["--scale", "1e300"], "0.01 to 100"),
        (["--light", "1e308,0,0"], "each coordinate must be a finite number from -1e+08 to "
                                   "1e+08 cm, not 1e+308"),
    ],
)
def test_snapshot_refuses_bad_arguments_and_writes_nothing(tmp_path, args, message):
    out = tmp_path / "arm.png"
    result = run("snapshot", DEFAULT_CONFIG, "-o", out, *args)
    assert result.exit_code == 2
    assert message in result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("output", "message"),
    [("no/such/dir/arm.png", "there is no directory"), ("arm.jpg", "must end in .png")],
)
def test_snapshot_refuses_an_unwritable_output(tmp_path, output, message):
    result = run("snapshot", DEFAULT_CONFIG, "-o", tmp_path / output)
    assert result.exit_code == 2
    assert message in result.stderr
    assert list(tmp_path.iterdir()) == []


PARTS = {"muscle", "scapula", "humerus", "radius", "ulna"}


def test_export_mesh_writes_named_parts_to_gltf(tmp_path):
    out = tmp_path / "arm.glb"
    result = run("export-mesh", DEFAULT_CONFIG, "-o", out, "--flexion", "90")
    assert result.exit_code == 0, result.output
    scene = trimesh.load(out, force="scene")
    assert set(scene.geometry) == PARTS
    assert scene.geometry["muscle"].is_watertight


def test_export_mesh_gives_each_gltf_part_its_colour(tmp_path):
    out = tmp_path / "arm.glb"
    assert run("export-mesh", DEFAULT_CONFIG, "-o", out).exit_code == 0
    scene = trimesh.load(out, force="scene")
    colours = {name: tuple(geometry.visual.material.baseColorFactor[:3])
               for name, geometry in scene.geometry.items()}
    bone = (0xE3, 0xD9, 0xC0)
    assert colours == {part: (0xB4, 0x48, 0x3E) if part == "muscle" else bone
                       for part in PARTS}


def test_export_mesh_writes_named_objects_to_obj(tmp_path):
    out = tmp_path / "arm.obj"
    assert run("export-mesh", DEFAULT_CONFIG, "-o", out).exit_code == 0
    objects = {line[2:].strip() for line in out.read_text().splitlines() if line.startswith("o ")}
    assert objects == PARTS


@pytest.mark.parametrize("suffix", [".stl", ".ply"])
def test_export_mesh_merges_parts_for_single_mesh_formats(tmp_path, suffix):
    out = tmp_path / f"arm{suffix}"
    assert run("export-mesh", DEFAULT_CONFIG, "-o", out).exit_code == 0
    mesh = trimesh.load(out, force="mesh")
    assert len(mesh.faces) > 1000


def test_export_mesh_refuses_an_unknown_format(tmp_path):
    result = run("export-mesh", DEFAULT_CONFIG, "-o", tmp_path / "arm.fbx")
    assert result.exit_code == 2
    assert ".obj, .stl, .ply, .glb" in result.stderr


def _cells(ansi: str) -> list[str]:
    """The lines of ``ansi`` without their colour codes."""
    return re.sub(r"\x1b\[[0-9;]*m", "", ansi).splitlines()


def test_snapshot_ansi_prints_half_block_pixels_across_the_terminal(monkeypatch):
    monkeypatch.setenv("COLUMNS", "60")
    result = run("snapshot", DEFAULT_CONFIG, "--ansi", "--flexion", "90")
    assert result.exit_code == 0, result.output
    lines = _cells(result.stdout)
    assert len(lines) == round(60 * 9 / 16 / 2)  # two pixel rows per line, 16:9
    assert all(len(line) == 60 for line in lines)
    assert set("".join(lines)) <= {"▄", "▀", " "}


@pytest.mark.parametrize(("colors", "code"), [("truecolor", "48;2;18;22;28"),
                                              ("256", "48;5;233")])
def test_snapshot_ansi_into_a_pipe_is_in_colour(colors, code, monkeypatch):
    monkeypatch.delenv("COLORTERM", raising=False)
    result = run("snapshot", DEFAULT_CONFIG, "--ansi", "--size", "32x18", "--colors", colors)
    assert result.exit_code == 0, result.output
    codes = re.findall(r"\x1b\[([0-9;]*)m", result.stdout)
    assert code in " ".join(codes)  # the background, in its own colour
    other = "38;2;" if colors == "256" else "38;5;"
    assert not any(other in found for found in codes)


def test_snapshot_ansi_takes_the_asked_size():
    result = run("snapshot", DEFAULT_CONFIG, "--ansi", "--size", "100x31")
    assert result.exit_code == 0, result.output
    lines = _cells(result.stdout)
    assert len(lines) == 16  # 31 pixel rows, in whole cells of two
    assert all(len(line) == 100 for line in lines)  # wider than the 80 a pipe is given


def test_snapshot_needs_an_output_or_ansi():
    result = run("snapshot", DEFAULT_CONFIG)
    assert result.exit_code == 2
    assert "give -o FILE.png, or one of --ansi, --kitty, --sixel and --iterm" in result.stderr


def test_snapshot_with_an_output_and_ansi_says_both_were_given(tmp_path):
    result = run("snapshot", DEFAULT_CONFIG, "--ansi", "-o", tmp_path / "x.png")
    assert result.exit_code == 2
    assert "give -o FILE.png or --ansi, not both" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_the_elbow_s_range_in_a_refusal_reads_0_not_minus_0():
    result = run("info", BUNDLED / "elbow.toml", "--length", "5")
    assert result.exit_code == 2
    assert "34.07 to 42.46 cm (elbow flexion 0 to 130 degrees)" in result.stderr


def test_info_gives_the_range_the_muscle_itself_allows(tmp_path):
    thin = tmp_path / "thin.toml"
    thin.write_text((BUNDLED / "toy.toml").read_text().replace("[1.0, 0.5],\n    [2.0",
                                                               "[0.2, 5.0],\n    [2.0", 1))
    result = run("info", thin)
    assert result.exit_code == 0, result.output
    assert "(allowed 6.16 to 10.63)" in result.stdout
    refused = run("info", thin, "--length", "11")
    assert refused.exit_code == 2
    assert "6.16 to 10.63 cm" in refused.stderr and "node 1's radius" in refused.stderr


@pytest.mark.parametrize(("word", "message"), [
    ("snaphsot", "No such command or file 'snaphsot'. Did you mean 'snapshot'?"),
    ("frobnicate", "No such command or file 'frobnicate'. Commands: animate, app, doctor, "),
    ("frobnicate", "or a bundled model's name (biceps, elbow, fine, toy), to open the app"),
])
def test_a_mistyped_command_is_not_taken_for_a_file(word, message):
    result = run(word, "-o", "x.png")
    assert result.exit_code == 2
    assert message in result.stderr
    assert "No such option" not in result.stderr


def test_a_first_word_too_long_for_a_file_name_is_refused_in_words():
    result = run("x" * 300)  # was a traceback: OSError, File name too long
    assert result.exit_code == 2
    assert "the name is 300 bytes long; a file name here has at most 255" in result.stderr


def test_a_config_file_that_is_not_there_is_still_said_so(tmp_path):
    result = run(tmp_path / "mine.toml")
    assert result.exit_code == 2
    assert "mine.toml: no such file" in result.stderr


@pytest.mark.parametrize("word", ["elbow", "elbow.toml", "configs/elbow.toml"])
def test_a_bundled_model_is_found_by_its_name_from_any_folder(word, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # as after pipx install: no repository here
    result = run("info", word)
    assert result.exit_code == 0, result.output
    assert result.stdout.splitlines()[0] == str(BUNDLED / "elbow.toml")
    assert "TRIlong" in result.stdout


def test_a_file_here_comes_before_a_bundled_model_of_the_same_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "elbow.toml").write_bytes((BUNDLED / "toy.toml").read_bytes())
    result = run("info", "elbow.toml")
    assert result.exit_code == 0, result.output
    assert result.stdout.splitlines()[0] == "elbow.toml"
    assert "TRIlong" not in result.stdout


def test_a_bundled_model_named_alone_opens_the_app_on_it(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("elbow", "--fps", "0")  # refused by the app's own options, so not opened
    assert result.exit_code == 2
    assert "must be 0.1 to 1000, got '0'" in result.stderr


@pytest.mark.parametrize("word", ["elbow.obj", "other/elbow.toml", "__init__", "elbows"])
def test_only_a_bundled_model_s_own_name_is_taken_for_it(word, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("info", word)
    assert result.exit_code == 2
    assert f"biceps: {word}: no such file" in result.stderr


def test_the_help_names_every_bundled_model():
    shown = run("--help").stdout
    for model in BUNDLED.glob("*.toml"):
        assert model.stem in shown


def test_version():
    result = run("--version")
    assert result.exit_code == 0
    assert result.stdout == f"biceps, version {importlib.metadata.version('biceps')}\n"


def test_the_top_help_says_each_command_whole():
    result = run("--help")
    assert result.exit_code == 0
    assert "[OPTIONS] [CONFIG | COMMAND [ARGS]...]" in result.stdout
    assert "..." not in result.stdout.split("Commands:")[1]
    assert "Open the terminal app (the command when none is given)." in result.stdout


def test_the_frame_rate_may_be_a_fraction():
    context = main.commands["app"].make_context("app", ["--fps", "2.5"])
    assert context.params["fps"] == 2.5
    result = run("app", "--fps", "0")
    assert result.exit_code == 2
    assert "must be 0.1 to 1000, got '0'" in result.stderr


ESCAPES = "x\x1b]52;c;UFdORUQ=\x07\x1b[2J"  # would set the clipboard and clear the screen
SHOWN = r"x\x1b]52;c;UFdORUQ=\x07\x1b[2J"
CONTROL = re.compile(r"[\x00-\x09\x0b-\x1f\x7f-\x9f]")  # all but the newline


@pytest.mark.parametrize("command, output", [
    ("info", None), ("snapshot", ".png"), ("export-mesh", ".obj"), ("animate", ".gif"),
])
def test_names_with_escape_sequences_are_printed_as_text(tmp_path, command, output):
    config = tmp_path / f"{ESCAPES}.toml"
    config.write_bytes(DEFAULT_CONFIG.read_bytes())
    args = [] if output is None else ["-o", tmp_path / f"{ESCAPES}{output}"]
    if command in ("snapshot", "animate"):
        args += ["--size", "64x48"] + (["--frames", "2"] if command == "animate" else [])
    result = run(command, config, *args)
    assert result.exit_code == 0, result.output
    assert not CONTROL.search(result.stdout + result.stderr)
    assert f"{SHOWN}.toml" in result.stdout if output is None else \
        f"wrote {tmp_path}/{SHOWN}{output}" in result.stderr


def test_a_missing_file_named_with_escape_sequences_is_refused_as_text(tmp_path):
    result = run("info", tmp_path / f"{ESCAPES}.toml")
    assert result.exit_code == 2
    assert result.stderr == f"biceps: {tmp_path}/{SHOWN}.toml: no such file\n"


@pytest.mark.parametrize("command, suffix", [("snapshot", ".png"), ("export-mesh", ".obj"),
                                             ("animate", ".gif")])
def test_an_output_name_too_long_is_refused_before_any_work(tmp_path, command, suffix):
    result = run(command, DEFAULT_CONFIG, "-o", tmp_path / ("x" * 300 + suffix))
    assert result.exit_code == 2
    assert f"the name is {300 + len(suffix)} bytes long; a file name here has at most 255" \
        in result.stderr
    assert "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command, suffix", [("snapshot", ".png"), ("export-mesh", ".obj"),
                                             ("animate", ".gif")])
def test_an_output_in_a_folder_named_too_long_is_refused_before_any_work(tmp_path, command,
                                                                         suffix):
    result = run(command, DEFAULT_CONFIG, "-o", tmp_path / ("x" * 256) / f"arm{suffix}")
    assert result.exit_code == 2
    assert f"the folder name {'x' * 20}... is 256 bytes long; a file name here has at most " \
        "255" in result.stderr
    assert "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command, suffix", [("snapshot", ".png"), ("export-mesh", ".obj"),
                                             ("animate", ".gif")])
def test_an_output_that_is_the_configuration_itself_is_refused(tmp_path, command, suffix):
    config = tmp_path / f"arm{suffix}"  # a configuration may have any name
    config.write_bytes(DEFAULT_CONFIG.read_bytes())
    link = tmp_path / f"link{suffix}"
    link.symlink_to(config)
    for output in (config, link):
        result = run(command, config, "-o", output, "--size", "64x48") if command != \
            "export-mesh" else run(command, config, "-o", output)
        assert result.exit_code == 2
        assert f"{output}: is the configuration it is made from" in result.stderr
        assert config.read_bytes() == DEFAULT_CONFIG.read_bytes()


def test_info_json_is_strict_json_at_the_bounds(tmp_path):
    path = tmp_path / "extreme.toml"
    path.write_text("[muscle]\nlength = 33.0\nnodes = [[1e-6, 0.0], [1e4, 1e4], [1e-6, 0.0]]\n")
    result = run("info", path, "--json")
    assert result.exit_code == 0, result.output

    def refuse(constant: str):
        raise AssertionError(f"{constant} is not JSON")

    facts = json.loads(result.stdout, parse_constant=refuse)
    assert facts["max_radius_cm"] == 1e4



@pytest.mark.parametrize("args, words", [
    (["snapshot", "-o", "{out}/big.png", "--size", "8192x8192", "--ssaa", "2"],
     "a picture of 8192x8192 with 2x2 supersampling needs 1.94 GiB of memory, more than the "
     "1.50 GiB allowed"),
    (["animate", "-o", "{out}/flex.gif", "--frames", "10000", "--size", "640x360"],
     "5,001 different frames of 640x360 need 7.51 GiB of memory to encode, more than the "
     "1.50 GiB allowed: at this size at most 998 different frames"),
    (["export-mesh", "{model}", "-o", "{out}/arm.obj", "--segments", "1001"],
     "1,000 nodes at 1,001 segments round each make 1,001,000 vertices; at most 1,000,000"),
], ids=["snapshot", "animate", "export-mesh"])
def test_work_beyond_the_memory_bounds_is_refused_before_it_starts(tmp_path, args, words):
    model = tmp_path / "model" / "fine.toml"  # 1,000 nodes: at 1,000 segments, the most
    model.parent.mkdir()
    model.write_text("[muscle]\nlength = 33.0\nnodes = [" + "[1.0, 1.0], " * 1000 + "]\n")
    out = tmp_path / "out"
    out.mkdir()
    result = run(*[arg.replace("{out}", str(out)).replace("{model}", str(model))
                   for arg in args])
    assert result.exit_code == 2
    assert words in result.stderr
    assert list(out.iterdir()) == []
