"""The command line's real pixels: snapshot --kitty, --sixel and --iterm, doctor, and
--graphics on its way to the app."""

from __future__ import annotations

import base64
import io
import re
import zlib

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from biceps.cli import main
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal import detect, printed
from biceps.terminal.cells import SEXTANTS
from biceps.tui.halfblocks import HalfBlocks, TextCells
from biceps.tui.pixels import KittyGraphics, Sixel

XTERM = detect.parse(b"\x1bP>|XTerm(379)\x1b\\\x1b[?1;0;256S\x1b[?63;4c", 0.002,
                     (80, 24, 560, 360))


def run(*args: str):
    return CliRunner().invoke(main, [str(a) for a in args])


def _frame(width: int, height: int) -> np.ndarray:
    scene = Scene.of(load_config(DEFAULT_CONFIG)).with_arm(
        Scene.of(load_config(DEFAULT_CONFIG)).arm.at_flexion(90))
    return SceneRenderer().render(scene, width, height)


def test_snapshot_kitty_prints_the_picture_across_the_terminal(monkeypatch):
    # No terminal to ask (the output is captured): cells of 10x20 pixels are assumed.
    monkeypatch.setenv("COLUMNS", "20")
    result = run("snapshot", DEFAULT_CONFIG, "--kitty", "--flexion", "90")
    assert result.exit_code == 0, result.output
    rows = round(20 * 10 * 9 / 16 / 20)
    # Room first, then the image from the top of it, then the cursor below it.
    assert result.stdout.startswith("\n" * rows + f"\x1b[{rows}A\x1b7\x1b_G")
    assert result.stdout.endswith(f"\x1b8\x1b[{rows}B\r")
    payload = "".join(re.findall(r"\x1b_G[^;]*;([^\x1b]*)\x1b\\", result.stdout))
    decoded = np.frombuffer(zlib.decompress(base64.b64decode(payload)), np.uint8)
    np.testing.assert_array_equal(decoded.reshape(rows * 20, 200, 3), _frame(200, rows * 20))


def test_snapshot_iterm_and_sixel(monkeypatch):
    monkeypatch.setenv("COLUMNS", "20")
    iterm = run("snapshot", DEFAULT_CONFIG, "--iterm", "--flexion", "90").stdout
    data = base64.b64decode(re.search(r"\x1b\]1337;File=[^:]*:([^\x07]*)\x07", iterm)[1])
    np.testing.assert_array_equal(np.asarray(Image.open(io.BytesIO(data))), _frame(200, 120))
    sixel = run("snapshot", DEFAULT_CONFIG, "--sixel", "--flexion", "90").stdout
    assert re.search(r'\x1bP0;1;0q"1;1;200;120#0;2;', sixel) and "\x1b\\\x1b8" in sixel


def test_snapshot_takes_one_way_to_print():
    result = run("snapshot", DEFAULT_CONFIG, "--kitty", "-o", "x.png")
    assert result.exit_code == 2 and "give -o FILE.png or --kitty, not both" in result.stderr


def test_doctor_says_what_it_found_and_why(monkeypatch):
    monkeypatch.setattr(detect, "ask", lambda: XTERM)
    monkeypatch.setenv("TERM", "xterm")
    monkeypatch.delenv("TMUX", raising=False)
    monkeypatch.delenv("STY", raising=False)
    result = run("doctor")
    assert result.exit_code == 0, result.output
    assert "terminal        XTerm(379) (TERM=xterm" in result.stdout
    assert "cell size       7x15 pixels" in result.stdout
    assert "graphics        sixel: auto: the terminal's device attributes include 4" in result.stdout


@pytest.fixture
def started(monkeypatch):
    """What run_app would start the app with: the encoder, the notice, and whether the
    terminal was asked."""
    seen: dict = {"asked": 0}

    def ask():
        seen["asked"] += 1
        return XTERM

    def run_app(self):
        seen["encoder"], seen["notice"] = self._encoder, self._notice

    monkeypatch.setattr(detect, "ask", ask)
    monkeypatch.setattr(detect.Place, "here", classmethod(lambda cls: detect.Place()))
    monkeypatch.setattr("biceps.tui.app.BicepsApp.run", run_app)
    monkeypatch.setattr("biceps.cli._check_terminal", lambda: None)  # the runner has none
    return seen


def test_half_blocks_by_default_with_a_word_about_real_pixels(started):
    assert run("app", DEFAULT_CONFIG).exit_code == 0
    assert isinstance(started["encoder"], HalfBlocks) and started["asked"] == 1
    assert "can show real pixels (sixel): start biceps with --graphics sixel" in started["notice"]


def test_half_blocks_and_colours_asked_on_the_command_line_ask_the_terminal_nothing(started):
    assert run("app", DEFAULT_CONFIG, "--graphics", "halfblocks", "--colors", "256").exit_code == 0
    assert isinstance(started["encoder"], HalfBlocks) and started["asked"] == 0
    assert started["notice"] is None
    # The colours left to the terminal, it is asked about them.
    assert run("app", DEFAULT_CONFIG, "--graphics", "halfblocks").exit_code == 0
    assert started["asked"] == 1


def test_the_config_may_choose_real_pixels(private_path, started, tmp_path):
    path = tmp_path / "sixel.toml"
    path.write_text(DEFAULT_CONFIG.read_text().replace('graphics = "halfblocks"',
                                                       'graphics = "sixel"'))
    assert run("app", path).exit_code == 0
    assert isinstance(started["encoder"], Sixel) and started["encoder"].cell == (7, 15)
    assert started["notice"] is None
    # The command line wins over the file, and may draw a fraction of the pixels.
    assert run("app", path, "--graphics", "kitty", "--pixel-scale", "0.5").exit_code == 0
    assert isinstance(started["encoder"], KittyGraphics)
    assert started["encoder"].cell == (4, 8)  # 3.5 x 7.5, rounded half to even


def test_a_protocol_the_place_cannot_take_falls_back_and_says_why(started, monkeypatch):
    monkeypatch.setattr(detect.Place, "here",
                        classmethod(lambda cls: detect.Place(multiplexer="screen")))
    assert run("app", DEFAULT_CONFIG, "--graphics", "kitty").exit_code == 0
    assert isinstance(started["encoder"], HalfBlocks)
    assert "Half-blocks: kitty was asked, but inside GNU screen" in started["notice"]


def test_auto_says_why_it_came_to_text(started, monkeypatch):
    monkeypatch.setattr(detect, "ask", lambda: detect.parse(b"\x1b[?1;2c", 0.01))  # tmux's
    monkeypatch.setattr(detect.Place, "here", classmethod(
        lambda cls: detect.Place(multiplexer="tmux", outer_terminal="xterm-kitty")))
    assert run("app", DEFAULT_CONFIG, "--graphics", "auto").exit_code == 0
    # No images through tmux, but kitty draws sextants itself.
    assert isinstance(started["encoder"], TextCells) and started["encoder"].shape == SEXTANTS
    assert started["notice"].startswith("Sextants: auto: inside tmux in xterm-kitty")
    assert "tmux set -g allow-passthrough on" in started["notice"]


def test_a_bad_pixel_scale_is_refused():
    result = run("app", DEFAULT_CONFIG, "--pixel-scale", "2")
    assert result.exit_code == 2 and "must be 0.1 to 1" in result.stderr


def test_snapshot_kitty_fits_a_wide_window_by_its_rows(monkeypatch):
    # 16:9 across 160 columns of 10x20 would be 45 rows: the window has 20, and the prompt
    # takes one after the picture.
    monkeypatch.setenv("COLUMNS", "160")
    monkeypatch.setenv("LINES", "20")
    result = run("snapshot", DEFAULT_CONFIG, "--kitty")
    assert result.exit_code == 0, result.output
    columns = round(19 * 20 * 16 / 9 / 10)
    assert f"s={columns * 10},v={19 * 20}," in result.stdout
    assert f",c={columns},r=19," in result.stdout


def test_snapshot_sixel_where_the_terminal_has_none_says_so(monkeypatch):
    monkeypatch.setattr(printed, "terminal_answers", lambda: detect.parse(
        b"\x1bP>|XTerm(379)\x1b\\\x1b[?64;1;2;6;9;15;16;17;18;21;22;28c", 0.001))
    result = run("snapshot", DEFAULT_CONFIG, "--sixel")
    assert result.exit_code == 2 and result.stdout == ""
    assert ("biceps: cannot print --sixel here: sixel was asked, but the terminal's device "
            "attributes (64;1;2;6;9;15;16;17;18;21;22;28) do not include 4, sixel (xterm "
            "draws sixel as a VT340: xterm -ti vt340); --ansi prints the picture in text, "
            "which every terminal shows") in result.stderr


def test_snapshot_sixel_within_the_terminals_largest_image(monkeypatch):
    monkeypatch.setenv("COLUMNS", "100")
    monkeypatch.setenv("LINES", "40")
    monkeypatch.setattr(printed, "terminal_answers", lambda: detect.parse(
        b"\x1b[?2;0;400;300S\x1b[6;20;10t\x1b[?63;1;4c", 0.001, (100, 40, 0, 0)))
    sixel = run("snapshot", DEFAULT_CONFIG, "--sixel").stdout
    # 100 columns of 10 at 16:9 would be 1000x560 pixels: scaled to 400x224, moved into
    # the middle of its 28 rows of cells, 60 columns of 40 to the right.
    assert re.search(r'\x1b7\x1b\[8B\x1b\[30C\x1bP0;1;0q"1;1;400;224#', sixel), sixel[:80]
