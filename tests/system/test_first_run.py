"""A first run (an empty numba cache) says so from the app's first screen, with its
progress, until the first picture; the keys work meanwhile."""

from __future__ import annotations

import os
import select
import sys
import time
from pathlib import Path

import pytest

from biceps.engine import coldstart
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
        time.sleep(1)  # (the rest of the frame)
        while select.select([master], [], [], 0.2)[0]:
            output += os.read(master, 1 << 16)
    screen = Screen(100, 30).feed(output.decode(errors="replace"))
    shown = "\n".join(screen.text(y) for y in range(30))
    assert "Preparing" not in shown and "▀" in shown
