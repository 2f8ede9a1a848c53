"""The real app in a pseudo-terminal: the colour codes it writes, and the question after a frame."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

from biceps.engine.config import load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.changes import TURN_STEP
from pty_app import UPPER_HALF, first_picture, shown_after
from vt import Screen

ROOT = Path(__file__).resolve().parents[2]


def _first_picture(config: Path, *options: str, **variables: str) -> bytes:
    """What ``biceps app`` writes to a 100x30 terminal until its first picture is out;
    ``variables`` are added to its environment."""
    command = [sys.executable, "-m", "biceps", "app", str(config), *options]
    return first_picture(command, cwd=ROOT, **variables).output


def _colour_codes(output: bytes) -> list[str]:
    return [code.decode() for code in re.findall(rb"\x1b\[([0-9;]*)m", output)]


def test_a_256_colour_terminal_gets_palette_codes_only(private_path, config_path):
    codes = _colour_codes(_first_picture(config_path, "--colors", "256"))
    assert any("48;5;" in code for code in codes)
    assert not any(re.search(r"(^|;)[34]8;2;", code) for code in codes)
    # The picture's background, #12161c, in its nearest entry, #121212, not pure black.
    backgrounds = [int(number) for code in codes for number in re.findall(r"48;5;(\d+)", code)]
    assert 233 in backgrounds and 16 not in backgrounds


def test_a_terminal_named_plain_xterm_gets_256_colours_not_16(private_path, config_path):
    # TERM=xterm, Debian's xterm's own, which Rich reads as 16 colours.
    codes = _colour_codes(_first_picture(config_path, TERM="xterm", COLORTERM=""))
    assert any("48;5;" in code for code in codes)
    sixteen = [code for code in codes
               if re.search(r"(^|;)(3[0-7]|4[0-7]|9[0-7]|10[0-7])(;|$)", code)
               and not re.search(r"[34]8;[25];", code)]
    assert not sixteen, sixteen[:5]


def test_a_truecolor_terminal_gets_the_picture_in_rgb(config_path):
    codes = _colour_codes(_first_picture(config_path, "--colors", "truecolor"))
    assert any(re.search(r"(^|;)38;2;\d+;\d+;\d+;48;2;", code) for code in codes)


def test_the_picture_on_the_terminal_is_the_frame_exactly(config_path):
    # (On a cold cache too: tests/system/test_first_run.py.)
    output = _first_picture(config_path, "--colors", "truecolor").decode()
    shown = Screen(100, 30).feed(output).picture()
    frame = SceneRenderer().render(Scene.of(load_config(config_path)), shown.shape[1],
                                   shown.shape[0])
    np.testing.assert_array_equal(shown, frame)


def test_the_picture_and_its_caption_on_the_terminal_follow_the_keys(config_path):
    # The viewport writes its frames itself, between Textual's own updates
    # (tui/widgets/viewport.py): what the terminal makes of both is the latest frame,
    # exactly, with the caption of its view.
    scene = Scene.of(load_config(config_path))
    scene = scene.with_view(yaw=scene.view.yaw + 3 * TURN_STEP)
    caption = f"yaw {scene.view.yaw:g}°"
    output = shown_after([sys.executable, "-m", "biceps", "app", str(config_path)], cwd=ROOT,
                         keys=b"\x1b[C" * 3, expected=caption.encode()).decode()
    screen = Screen(100, 30).feed(output)
    assert screen.text(0).startswith(f"╭─ {caption} ")
    shown = screen.picture()
    frame = SceneRenderer().render(scene, shown.shape[1], shown.shape[0])
    np.testing.assert_array_equal(shown, frame)


def test_after_its_frame_the_app_asks_where_the_cursor_is(private_path, config_path):
    output = _first_picture(config_path)
    picture = output.index(UPPER_HALF)
    assert re.search(rb"\x1b7\x1b\[1;\d+H\x1b\[6n\x1b8", output[picture:])
