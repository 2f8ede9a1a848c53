"""Kitty images through tmux: the app inside tmux, in a terminal that tmux knows as
xterm-kitty (and, from its answer to XTVERSION, as kitty 0.28 or later), with
allow-passthrough on, sends its frames through tmux's passthrough as virtual placements,
and its picture's cells are Unicode placeholders that tmux draws as text; in an older kitty
it sends none, and draws sextants, which kitty draws itself. This test plays the outer
terminal in a pseudo-terminal and reads what tmux writes to it. (The image's deletion as
the app ends is not asserted: tmux passes it on or not, as the pane goes, and the
placeholders that showed it go with the pane.)"""

from __future__ import annotations

import fcntl
import os
import re
import select
import shutil
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PLACEHOLDER = "\U0010eeee".encode()
SEXTANT = re.compile("[\U0001fb00-\U0001fb3b]")
XTVERSION = b"\x1b[>q"  # tmux asks the outer terminal its name and version


def _read_until(master: int, output: bytearray, condition, timeout: float,
                version: bytes) -> bool:
    """Read what tmux writes until ``condition`` holds, answering tmux's XTVERSION question
    as kitty ``version``."""
    deadline = time.monotonic() + timeout
    answered = output.count(XTVERSION)
    while time.monotonic() < deadline:
        if condition(bytes(output)):
            return True
        if select.select([master], [], [], 0.1)[0]:
            try:
                output += os.read(master, 1 << 16)
            except OSError:
                return condition(bytes(output))
            # Counted in all that was read: a read may end in the middle of a question.
            for _ in range(output.count(XTVERSION) - answered):
                os.write(master, b"\x1bP>|kitty(" + version + b")\x1b\\")
                answered += 1
    return condition(bytes(output))


@pytest.mark.parametrize("version", [b"0.35.2", b"0.26.5"])
def test_kitty_images_go_through_tmux_placed_by_placeholders_from_kitty_028(private_path,
                                                                           tmp_path, version):
    if shutil.which("tmux") is None:
        if os.environ.get("CI"):
            pytest.fail("tmux is missing: .ci/run installs it")
        pytest.skip("needs tmux")
    config = tmp_path / "tmux.conf"
    config.write_text("set -g allow-passthrough on\nset -g status off\n")
    app = f"{sys.executable} -m biceps app --graphics auto --colors truecolor"
    master, slave = os.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 1000, 600))
    environment = {key: value for key, value in os.environ.items()
                   if not key.startswith(("TEXTUAL", "TMUX"))}
    environment.update(TERM="xterm-kitty")
    tmux = subprocess.Popen(["tmux", "-S", str(tmp_path / "socket"), "-f", str(config),
                             "new-session", app], stdin=slave, stdout=slave, stderr=slave,
                            env=environment, cwd=ROOT, start_new_session=True)
    os.close(slave)
    output = bytearray()
    try:
        if version == b"0.26.5":  # no placeholders: the picture in sextants, and no image
            assert _read_until(master, output, lambda out: SEXTANT.search(out.decode(
                errors="replace")), timeout=120, version=version), output[-3000:]
            assert b"\x1b_G" not in output and PLACEHOLDER not in output
            return
        # A virtual placement of the whole picture, and placeholders.
        assert _read_until(master, output, lambda out: re.search(
            rb"\x1b_Ga=T,f=24,o=z,s=\d+,v=\d+,i=(\d+),U=1,c=\d+,r=\d+,q=2", out)
            and PLACEHOLDER in out, timeout=120, version=version), output[-3000:]
        image_id = re.search(rb"\x1b_Ga=T,[^;]*,i=(\d+),U=1", output)[1]
        # The placeholders' colour is the image id, in the 256-colour palette. (tmux writes
        # a placeholder, then again with each diacritic, backing up over it.)
        assert re.search(rb"\x1b\[38;5;" + image_id + rb"m" + PLACEHOLDER, output)
    finally:
        # The client is all this process started: the server it forked lives on, with the
        # app, in a session of its own, until told to stop.
        subprocess.run(["tmux", "-S", str(tmp_path / "socket"), "kill-server"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if tmux.poll() is None:
            os.killpg(tmux.pid, 9)
        tmux.wait()
        os.close(master)
