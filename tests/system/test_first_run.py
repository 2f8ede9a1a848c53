"""A first run (an empty numba cache) says so from the app's first screen, with its
progress, until the first picture; the keys work meanwhile, and the picture is the frame."""

from __future__ import annotations

import os
import select
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

from biceps.engine import coldstart
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.changes import FINE_STEP, length_changed
from pty_app import UPPER_HALF, _terminal
from vt import Screen

ROOT = Path(__file__).resolve().parents[2]
MESSAGE = b"Preparing the renderer: first run only"


def _read_until(master: int, output: bytearray, condition, timeout: float = 300) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"not there before the time limit:\n{bytes(output[-2000:])!r}")
        if select.select([master], [], [], 0.05)[0]:
            output += os.read(master, 1 << 16)


@pytest.mark.skipif(coldstart._cores() < 2, reason="a first run compiles aside on two cores")
def test_a_first_run_says_so_on_the_first_screen_and_the_keys_work_meanwhile(tmp_path):
    # The children compile the first frame's kernels (engine/coldstart.py), and the app
    # loads them from the cache.
    command = [sys.executable, "-m", "biceps", "--graphics", "halfblocks", "--colors",
               "truecolor"]  # (nothing to ask the terminal)
    with _terminal(command, ROOT, (100, 30), {"NUMBA_CACHE_DIR": str(tmp_path)}) as (
            _, master):
        output = bytearray()
        _read_until(master, output, lambda: b"Quit" in output)  # the footer: a first screen
        # Textual writes a screen top to bottom: the message came with the first one.
        assert MESSAGE in output[:output.index(b"Quit")]
        assert b"0 of 3 parts done" in output and b"compiling the rasterizer" in output
        os.write(master, b"x")  # stretch: the numbers change while the picture is prepared
        _read_until(master, output, lambda: b"33.10 cm" in output)
        assert UPPER_HALF not in output
        _read_until(master, output, lambda: b"1 s" in output[output.index(MESSAGE):])
        _read_until(master, output, lambda: UPPER_HALF in output)
        # Then the frame of the model stretched, exactly, as on a warm start
        # (tests/system/test_app_terminal.py): the first may be of the model before.
        scene = Scene.of(load_config(DEFAULT_CONFIG))
        stretched = scene.with_arm(length_changed(scene.arm, FINE_STEP)[0])
        _read_until(master, output, _frame_shown(output, stretched))
    screen = _screen(output)
    assert "Preparing" not in "\n".join(screen.text(y) for y in range(30))


def _frame_shown(output: bytearray, scene: Scene) -> Callable[[], bool]:
    """A condition for :func:`_read_until`: whether the app's picture is ``scene``'s frame,
    looked at again only once more output has come."""
    looked_at = 0

    def shown() -> bool:
        nonlocal looked_at
        if len(output) == looked_at:
            return False
        looked_at = len(output)
        return _shows(_screen(output), scene)

    return shown


def _screen(output: bytearray) -> Screen:
    return Screen(100, 30).feed(output.decode(errors="replace"))


def _shows(screen: Screen, scene: Scene) -> bool:
    """Whether the app's picture on ``screen`` is ``scene``'s frame, exactly."""
    try:
        picture = screen.picture()
    except AssertionError:  # not all of it a picture yet (the message was there)
        return False
    frame = SceneRenderer().render(scene, picture.shape[1], picture.shape[0])
    return np.array_equal(picture, frame)
