"""``biceps animate``: the flex cycle written as an animation and read back frame by frame."""

import sys

import numpy as np
import pytest
from click.testing import CliRunner

from biceps.cli import main
from biceps.engine.animate import FlexCycle, render_cycle
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.export import parse_size
from biceps.engine.scene import Scene
from biceps.engine.sweep import flexion_range
from decode import decoded, off

SIZE = "320x180"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def cycle(start: float, end: float, frames: int, bounce: bool, size: str = SIZE,
          **view) -> list[np.ndarray]:
    """The frames the engine renders for this cycle of the default model, seen as ``view``
    says: what the command's file must hold, decoded."""
    scene = Scene.of(load_config(DEFAULT_CONFIG))
    if view:
        scene = scene.with_view(**view)
    width, height = parse_size(size)
    return render_cycle(scene, FlexCycle(start, end, frames, bounce), width, height)


# The share of pixels a frame may have more than 40 levels off the engine's: none where
# the format keeps every pixel, a few edge pixels where it is lossy. The other end of the
# cycle is 1.7 % off.
TOLERANCE = {".gif": 0.0, ".apng": 0.0, ".webp": 0.002, ".mp4": 0.002}


@pytest.mark.parametrize("suffix", list(TOLERANCE))
def test_a_loop_holds_the_engine_s_frames_from_one_angle_to_the_other(tmp_path, suffix):
    out = tmp_path / f"cycle{suffix}"
    result = run("animate", DEFAULT_CONFIG, "-o", out, "--size", SIZE, "--frames", 6,
                 "--loop", "--from", 20, "--to", 120)
    assert result.exit_code == 0, result.output
    frames = decoded(out)
    expected = cycle(20, 120, 6, bounce=False)
    assert len(frames) == 6
    assert frames[0].shape == (180, 320, 3)
    for frame, wanted in zip(frames, expected):
        assert off(frame, wanted, 40) <= TOLERANCE[suffix]
    assert off(frames[0], frames[-1], 40) > 0.01  # the arm did move
    if suffix == ".apng":
        assert all(map(np.array_equal, frames, expected))


def test_a_bounce_comes_back_through_the_same_pictures(tmp_path):
    out = tmp_path / "bounce.apng"
    result = run("animate", DEFAULT_CONFIG, "-o", out, "--size", SIZE, "--frames", 8,
                 "--from", 20, "--to", 120)
    assert result.exit_code == 0, result.output
    frames = decoded(out)
    assert len(frames) == 8
    assert np.array_equal(frames[4], cycle(20, 120, 8, bounce=True)[4])  # the far end, half way
    for k in range(1, 4):
        assert np.array_equal(frames[k], frames[8 - k])
    assert not np.array_equal(frames[1], frames[2])


def test_the_view_options_turn_the_cycle_as_they_turn_a_snapshot(tmp_path):
    views = {}
    for name, args, view in (("plain", [], {}), ("turned", ["--yaw", "90"], {"yaw": 90.0})):
        out = tmp_path / f"{name}.apng"
        assert run("animate", DEFAULT_CONFIG, "-o", out, "--size", "160x90", "--frames", 2,
                   "--loop", *args).exit_code == 0
        views[name] = decoded(out)[0]
        wanted = cycle(*flexion_range(load_config(DEFAULT_CONFIG).arm), 2, bounce=False,
                       size="160x90", **view)[0]
        assert np.array_equal(views[name], wanted)
    assert not np.array_equal(views["plain"], views["turned"])


@pytest.mark.parametrize(("args", "message"), [
    (["-o", "cycle.gif", "--frames", "7"], "needs an even number of frames, not 7"),
    (["-o", "cycle.gif", "--fps", "60"], "a GIF plays at most 50 frames a second"),
    (["-o", "cycle.gif", "--to", "150"], "outside the joint's range"),
    (["-o", "cycle.gif", "--from", "40", "--to", "40"], "nothing would move"),
    (["-o", "cycle.mp4", "--size", "321x180"], "even width and height, not 321x180"),
    (["-o", "cycle.avi"], "must end in .gif, .apng, .webp, .mp4"),
    (["-o", "cycle.gif", "--size", "8192x8192", "--frames", "200", "--loop"],
     "ask for fewer frames or a smaller size"),
    (["-o", "cycle.gif", "--fps", "nan"], "--fps"),
    (["-o", "no/such/dir/cycle.gif"], "there is no directory"),
])
def test_a_refusal_exits_2_with_one_line_and_writes_nothing(tmp_path, monkeypatch, args,
                                                           message):
    monkeypatch.chdir(tmp_path)
    result = run("animate", DEFAULT_CONFIG, "--size", "64x36", *args)
    assert result.exit_code == 2
    assert message in result.stderr
    assert result.stderr.count("\n") <= 4  # click's usage lines for an option it refused
    assert list(tmp_path.iterdir()) == []


def test_mp4_without_pyav_says_which_extra_to_install(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "av", None)  # as if it were not installed
    result = run("animate", DEFAULT_CONFIG, "-o", tmp_path / "cycle.mp4", "--size", "64x36")
    assert result.exit_code == 2
    assert "pip install 'biceps[video]'" in result.stderr
    assert result.stderr.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_no_progress_bar_when_stderr_is_not_a_terminal(tmp_path):
    result = run("animate", DEFAULT_CONFIG, "-o", tmp_path / "cycle.gif", "--size", "64x36",
                 "--frames", 4)
    assert result.exit_code == 0
    assert result.stderr == f"wrote {tmp_path / 'cycle.gif'} (64x36, 4 frames at 25 a second)\n"
