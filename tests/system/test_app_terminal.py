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


def _first_picture(config: Path, *options: str, timeout: float = 120.0,
                   **variables: str) -> bytes:
    """What ``biceps app`` writes to a 100x30 terminal until its first picture is out, within
    ``timeout`` seconds; ``variables`` are added to its environment."""
    command = [sys.executable, "-m", "biceps", "app", str(config), *options]
    return first_picture(command, cwd=ROOT, timeout=timeout, **variables).output


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


@pytest.mark.parametrize("cache", ["warm", "cold"])
def test_the_picture_on_the_terminal_is_the_frame_exactly(config_path, tmp_path, cache):
    # Cold: an empty numba cache, as on a first run, where a child process compiles the
    # kernels for the first frame (engine/coldstart.py).
    # Compiling every kernel can take minutes on a loaded machine: the limit is then
    # test_first_run's.
    variables = {"NUMBA_CACHE_DIR": str(tmp_path / "cache")} if cache == "cold" else {}
    output = _first_picture(config_path, "--colors", "truecolor",
                            timeout=300.0 if cache == "cold" else 120.0, **variables).decode()
    screen = Screen(100, 30).feed(output)
    # The picture is inside the first rounded box from the top left.
    right = screen.text(0).index("╮")
    bottom = next(y for y in range(30) if screen.text(y).startswith("╰"))
    width, height = right - 1, bottom - 1
    shown = screen.pixels(1, 1, width, height)
    frame = SceneRenderer().render(Scene.of(load_config(config_path)), width, 2 * height)
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
    right = screen.text(0).index("╮")
    bottom = next(y for y in range(30) if screen.text(y).startswith("╰"))
    width, height = right - 1, bottom - 1
    frame = SceneRenderer().render(scene, width, 2 * height)
    np.testing.assert_array_equal(screen.pixels(1, 1, width, height), frame)


def test_after_its_frame_the_app_asks_where_the_cursor_is(private_path, config_path):
    output = _first_picture(config_path)
    picture = output.index(UPPER_HALF)
    assert re.search(rb"\x1b7\x1b\[1;\d+H\x1b\[6n\x1b8", output[picture:])
