"""Asking a real (pseudo-)terminal what it can show: the answers are read and understood,
a terminal that never answers is given up on, and the terminal is left as it was."""

from __future__ import annotations

import fcntl
import os
import re
import select
import struct
import subprocess
import sys
import termios
import time

ASK = """
import termios
from biceps.terminal.detect import ask
answers = ask()
mode = termios.tcgetattr(0)[3]
print("answers", answers.answered, answers.kitty, answers.name, answers.cell, answers.sixel)
print("cooked", bool(mode & termios.ICANON), bool(mode & termios.ECHO))
"""
KITTY = b"\x1b_Gi=31;OK\x1b\\\x1bP>|kitty(0.35.2)\x1b\\\x1b[6;20;10t\x1b[?62;c"


def _ask_in_a_terminal(answer: bytes | None) -> str:
    """What the child prints after asking a terminal that answers ``answer`` to the device
    attributes' question (None: that never answers)."""
    master, slave = os.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    child = subprocess.Popen([sys.executable, "-c", ASK], stdin=slave, stdout=slave,
                             stderr=slave, start_new_session=True,
                             preexec_fn=lambda: fcntl.ioctl(0, termios.TIOCSCTTY, 0))
    os.close(slave)
    output = b""
    deadline = time.monotonic() + 60
    try:
        while not re.search(rb"cooked \w+ \w+\r?\n", output) and time.monotonic() < deadline:
            if select.select([master], [], [], 0.05)[0]:
                try:
                    data = os.read(master, 4096)
                except OSError:
                    break
                if answer is not None and b"\x1b[c" in output + data \
                        and b"\x1b[c" not in output:
                    os.write(master, answer)
                output += data
        while child.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        if child.poll() is None:
            child.kill()
        child.wait()
        os.close(master)
    return output.decode(errors="replace")


def test_a_kitty_is_understood_and_the_terminal_left_cooked():
    printed = _ask_in_a_terminal(KITTY)
    assert "answers True OK kitty(0.35.2) (10, 20) False" in printed
    assert "cooked True True" in printed


def test_a_terminal_that_never_answers_is_given_up_on():
    printed = _ask_in_a_terminal(None)
    assert "answers False None None None False" in printed
    assert "cooked True True" in printed
