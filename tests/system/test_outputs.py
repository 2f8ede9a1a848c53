"""Every command with nowhere good to write: stdout closed, on a full device, ASCII only or
read by a program that stops after one byte; an output in a folder named too long, or the
configuration itself; the app with no terminal; ctrl+c in the middle of long work. Never a
traceback, the configuration untouched, and the exit status the README documents: 2 for a
refusal, 141 for a reader gone, 130 for ctrl+c, 0 only for output written whole."""

from __future__ import annotations

import fcntl
import os
import select
import signal
import shutil
import subprocess
import sys
import termios
import time
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG

BICEPS = [sys.executable, "-m", "biceps"]

# Commands that print, each with enough output to fill a pipe where one stopped reading
# would be noticed (a reader gone is only seen by a write after it has gone).
PRINTING = {
    "info": ["info"],
    "info --json": ["info", "--json"],
    "sweep --json": ["sweep", "--json", "--step", "0.05"],
    "snapshot --ansi": ["snapshot", "--ansi", "--size", "400x300"],
    "snapshot --kitty": ["snapshot", "--kitty", "--size", "1600x1200"],
    "doctor": ["doctor"],
}

# How stdout is spoilt, and the status and words each command must end with. Where the
# output is all ASCII, ASCII only is no problem.
CLOSED = ("closed", 2, "stdout is closed, and this command writes there")
FULL = ("full", 2, "cannot write to stdout: No space left on device")
READER_GONE = ("head -c1", 141, "")
ASCII = ("ascii", 0, "")
HALF_BLOCKS_IN_ASCII = ("ascii", 2, "stdout takes only ascii, and the picture is made of "
                                    "half blocks (U+2584)")


def _cases():
    for name in PRINTING:
        for spoilt in (CLOSED, FULL, READER_GONE):
            if not (name in ("info", "info --json", "doctor") and spoilt is READER_GONE):
                yield name, spoilt  # (their output fits in the pipe before head reads it)
        yield name, HALF_BLOCKS_IN_ASCII if name == "snapshot --ansi" else ASCII


def _start(argv: list[str], how: str, cwd: Path) -> subprocess.Popen:
    environment = dict(os.environ, PYTHONIOENCODING="ascii") if how == "ascii" else None
    if how == "closed":
        stdout, before = None, lambda: os.close(1)
    elif how == "full":
        stdout, before = open("/dev/full", "wb"), None
    else:
        stdout, before = subprocess.PIPE, None
    return subprocess.Popen([*BICEPS, *argv], stdin=subprocess.DEVNULL, stdout=stdout,
                            stderr=subprocess.PIPE, env=environment, cwd=cwd,
                            preexec_fn=before)


def test_every_printing_command_with_stdout_spoilt_ends_as_documented(tmp_path):
    config = tmp_path / "arm.toml"
    shutil.copy(DEFAULT_CONFIG, config)
    # All at once: each is a process of its own, mostly waiting.
    runs = {(name, how): (_start([*PRINTING[name], str(config)] if name != "doctor"
                                 else PRINTING[name], how, tmp_path), status, words)
            for name, (how, status, words) in _cases()}
    problems = []
    for (name, how), (process, status, words) in runs.items():
        if how == "head -c1":
            process.stdout.read(1)
            process.stdout.close()
        elif process.stdout is not None:
            process.stdout.read()
        stderr = process.stderr.read().decode()
        code = process.wait(timeout=300)
        if code != status or words not in stderr or "Traceback" in stderr:
            problems.append(f"{name}, stdout {how}: status {code}, stderr {stderr[-300:]!r}")
    assert problems == []
    assert config.read_bytes() == DEFAULT_CONFIG.read_bytes()


WRITING = {
    "snapshot": (".png", ["--size", "64x48"]),
    "export-mesh": (".obj", []),
    "animate": (".gif", ["--size", "64x48", "--frames", "2"]),
}


@pytest.mark.parametrize("command", WRITING)
def test_a_command_writing_a_file_needs_no_stdout(tmp_path, command):
    suffix, options = WRITING[command]
    process = _start([command, "-o", str(tmp_path / f"arm{suffix}"), *options], "closed",
                     tmp_path)
    stderr = process.communicate(timeout=300)[1].decode()
    assert process.returncode == 0, stderr
    assert (tmp_path / f"arm{suffix}").stat().st_size > 0


def test_the_app_with_no_terminal_says_it_needs_one(tmp_path):
    process = subprocess.run([*BICEPS, str(DEFAULT_CONFIG)], stdin=subprocess.DEVNULL,
                             capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert process.returncode == 2
    assert process.stderr == ("biceps: the app needs a terminal, and its stdin is not one; "
                              "for a picture without a terminal: biceps snapshot -o arm.png\n")
    assert process.stdout == ""  # no escape codes


@pytest.mark.parametrize("argv, busy", [
    (["animate", "-o", "flex.gif", "--frames", "2000", "--size", "320x180"], b"rendering"),
    (["sweep", "--step", "0.0015"], b"sweeping"),
], ids=["animate", "sweep"])
def test_ctrl_c_in_long_work_stops_it_cleanly(tmp_path, argv, busy):
    # On a terminal the work shows its progress; ctrl+c once it has: a line saying so,
    # status 130, no file, no traceback.
    master, slave = os.openpty()

    def in_the_terminal():  # its controlling terminal, as a shell's job has: ctrl+c is SIGINT
        os.setsid()
        fcntl.ioctl(0, termios.TIOCSCTTY, 0)
        # As a shell starts a job in the foreground: a suite started in the background
        # (`pytest &`) ignores SIGINT, and its children would inherit that.
        signal.signal(signal.SIGINT, signal.SIG_DFL)

    process = subprocess.Popen([*BICEPS, *argv], stdin=slave, stdout=slave, stderr=slave,
                               cwd=tmp_path, preexec_fn=in_the_terminal)
    os.close(slave)
    try:
        output = _read(master, until=busy)
        os.write(master, b"\x03")
        output += _read(master, until=None)
        assert process.wait(timeout=60) == 130
    finally:
        if process.poll() is None:
            process.kill()
        os.close(master)
    assert b"biceps: interrupted; no file was written" in output
    assert b"Traceback" not in output
    assert list(tmp_path.iterdir()) == []


def _read(master: int, until: bytes | None) -> bytes:
    """What the terminal shows until ``until`` has been (or, if None, until it closes)."""
    output = bytearray()
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and (until is None or until not in output):
        if select.select([master], [], [], 0.1)[0]:
            try:
                chunk = os.read(master, 1 << 16)
            except OSError:  # closed: the process is gone
                break
            if not chunk:
                break
            output += chunk
    return bytes(output)
