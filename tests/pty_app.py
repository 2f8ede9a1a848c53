"""The real app in a pseudo-terminal, as a person would start it."""

from __future__ import annotations

import fcntl
import os
import select
import struct
import subprocess
import termios
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterator

import pytest

UPPER_HALF = "▀".encode()
DEVICE_ATTRIBUTES_QUERY = b"\x1b[c"
DEVICE_ATTRIBUTES_ANSWER = b"\x1b[?62;22c"  # a VT220's


def app_environment(**variables: str) -> dict[str, str]:
    """The environment for the app in a terminal: this one, less Textual's settings, as an
    xterm with truecolour sets it, and ``variables``."""
    environment = {key: value for key, value in os.environ.items()
                   if not key.startswith("TEXTUAL")}
    environment.update({"TERM": "xterm-256color", "COLORTERM": "truecolor", **variables})
    return environment


def set_size(fd: int, columns: int, rows: int) -> None:
    """Give the terminal of ``fd`` (either side) a size; the app is sent SIGWINCH."""
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", rows, columns, 0, 0))


@dataclass
class Run:
    output: bytes  # what the app wrote, up to its first picture (and its exit, if keys quit it)
    exit_code: int | None  # None: still running when the test was done with it


@contextmanager
def _terminal(command: list[str], cwd: Path, size: tuple[int, int],
              variables: dict[str, str]) -> Iterator[tuple[subprocess.Popen, int]]:
    """``command`` running in a new terminal of ``size`` (columns, rows), and the terminal's
    side (the pty's master) to read it and type to it; killed, if still running, after."""
    master, slave = os.openpty()
    set_size(slave, *size)
    process = subprocess.Popen(command, stdin=slave, stdout=slave, stderr=slave,
                               env=app_environment(**variables), cwd=cwd,
                               start_new_session=True)
    os.close(slave)
    try:
        yield process, master
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
        os.close(master)


def first_picture(command: list[str], *, cwd: Path, size: tuple[int, int] = (100, 30),
                  keys: bytes = b"", timeout: float = 120.0, **variables: str) -> Run:
    """Start ``command`` in a terminal of ``size`` (columns, rows) and read until its first
    picture is out; then type ``keys`` and wait for it to end. ``variables`` are added to
    its environment."""
    with _terminal(command, cwd, size, variables) as (process, master):
        output = bytearray()
        deadline = time.monotonic() + timeout
        _read_until_picture(master, output, deadline)
        if not keys:
            return Run(bytes(output), None)
        os.write(master, keys)
        while process.poll() is None and time.monotonic() < deadline:
            if select.select([master], [], [], 0.05)[0]:
                try:
                    output += os.read(master, 1 << 16)
                except OSError:  # the terminal's other side has closed: the app is gone
                    break
        return Run(bytes(output), process.wait(timeout=max(deadline - time.monotonic(), 1)))


def _read_until_picture(master: int, output: bytearray, deadline: float) -> None:
    quiet_since = None
    while time.monotonic() < deadline:
        if select.select([master], [], [], 0.05)[0]:
            asked = output.count(DEVICE_ATTRIBUTES_QUERY)
            output += os.read(master, 1 << 16)
            # The app asks what the terminal can show (terminal/detect.py), in rounds that end
            # with the device attributes: a VT220's answer to each.
            os.write(master, DEVICE_ATTRIBUTES_ANSWER
                     * (output.count(DEVICE_ATTRIBUTES_QUERY) - asked))
            quiet_since = None
        elif UPPER_HALF in output:
            # The picture has begun: the frame is whole once the output pauses.
            quiet_since = quiet_since or time.monotonic()
            if time.monotonic() - quiet_since > 0.5:
                return
    pytest.fail(f"no picture before the time limit:\n{output[-2000:]!r}")


def shown_after(command: list[str], *, cwd: Path, keys: bytes, expected: bytes,
                size: tuple[int, int] = (100, 30), timeout: float = 120.0) -> bytes:
    """Start ``command`` in a terminal of ``size``, type ``keys`` once its first picture is
    out, and return all it wrote until ``expected`` has been written since (and the output
    has paused); the command is then killed."""
    with _terminal(command, cwd, size, {}) as (_, master):
        output = bytearray()
        deadline = time.monotonic() + timeout
        _read_until_picture(master, output, deadline)
        since = len(output)
        os.write(master, keys)
        _read_until(master, output, deadline, lambda: expected in output[since:])
        return bytes(output)


def converse(command: list[str], *, cwd: Path, script: list[tuple[bytes, bytes]],
             size: tuple[int, int] = (100, 30), timeout: float = 120.0,
             again: float | None = None, **variables: str) -> Run:
    """Start ``command`` in a terminal of ``size`` (with the environment ``variables``);
    for each ``(expected, keys)`` of ``script``, read until ``expected`` has been written
    since the last keys (and the output has paused), then type ``keys``; then wait for the
    command to end. With ``again``, keys whose answer has not come within ``again``
    seconds are typed again, as a person would (on a loaded machine the app leaves out
    keys that waited too long while it started, tui/behind.py)."""
    with _terminal(command, cwd, size, variables) as (process, master):
        output = bytearray()
        deadline = time.monotonic() + timeout
        keys = b""
        for expected, next_keys in script:
            since = len(output)
            _read_until(master, output, deadline, lambda: expected in output[since:],
                        _typing(master, keys, again))
            os.write(master, next_keys)
            keys = next_keys
        _read_until(master, output, deadline, lambda: process.poll() is not None,
                    _typing(master, keys, again))
        return Run(bytes(output), process.wait(timeout=max(deadline - time.monotonic(), 1)))


def _typing(master: int, keys: bytes, again: float | None) -> Callable[[], None] | None:
    """What types ``keys`` again each ``again`` seconds, or None."""
    if again is None or not keys:
        return None
    typed = time.monotonic()

    def retype() -> None:
        nonlocal typed
        if time.monotonic() - typed > again:
            try:
                os.write(master, keys)
            except OSError:  # the app is gone
                return
            typed = time.monotonic()

    return retype


def _read_until(master: int, output: bytearray, deadline: float, done,
                waiting: Callable[[], None] | None = None) -> None:
    """Read into ``output`` until ``done()`` and a pause of 0.3 s, or the other side closes;
    ``waiting()`` is called while ``done()`` is not."""
    quiet_since = None
    while time.monotonic() < deadline:
        if waiting is not None and not done():
            waiting()
        if select.select([master], [], [], 0.05)[0]:
            try:
                output += os.read(master, 1 << 16)
            except OSError:  # the terminal's other side has closed: the app is gone
                return
            quiet_since = None
        elif done():
            quiet_since = quiet_since or time.monotonic()
            if time.monotonic() - quiet_since > 0.3:
                return
    pytest.fail(f"not there before the time limit:\n{output[-2000:]!r}")

