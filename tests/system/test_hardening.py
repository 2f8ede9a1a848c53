"""The real app in a pseudo-terminal, given what it must survive: bytes that are not UTF-8,
a file named like an escape sequence, the keys a terminal turns into signals, and an error
of its own that gets through."""

from __future__ import annotations

import os
import shutil
import signal
import sys
import textwrap
import time
from pathlib import Path

from biceps.engine.config import DEFAULT_CONFIG, load_config
from pty_app import UPPER_HALF, converse
from storm import RawTerminal, quit_app, wait_for

HELP_TITLE = b"keys and mouse"


def _app(config: Path) -> list[str]:
    return [sys.executable, "-m", "biceps", "app", str(config)]


def test_bytes_and_sequences_it_cannot_read_do_not_end_the_app(private_path, config_path):
    # A lone continuation byte, a character cut short, a lead byte before an ASCII one, a
    # Kitty key sequence with a colon in a field; then ? (help): the app has read past
    # them and still answers.
    run = converse(_app(config_path), cwd=config_path.parent, script=[
        (UPPER_HALF, b"\xff\xe2\x82\xc3\x1b[97:65;2u?"),
        (HELP_TITLE, b"\x1b"),
        (b"", b"q"),
    ])
    assert HELP_TITLE in run.output
    assert run.exit_code == 0


def test_a_file_named_with_escape_sequences_shows_them_as_text(tmp_path):
    name = "x\x1b]52;c;UFdORUQ=\x07\x1b[2J.toml"  # sets the clipboard, clears the screen
    config = tmp_path / name
    shutil.copy(DEFAULT_CONFIG, config)
    run = converse(_app(config), cwd=tmp_path, script=[(UPPER_HALF, b"q")])
    assert b"\x1b]52" not in run.output  # nothing sets the terminal's clipboard
    assert rb"x\x1b]52;c;UFdORUQ=\x07\x" in run.output  # the name as text (cut short: the
    # panel is narrower than it)
    assert run.exit_code == 0


def test_an_error_that_gets_through_offers_to_save_and_ends_with_status_1(private_path,
                                                                          config_path,
                                                                          tmp_path):
    # The app as installed, but with a fault in one of its keys (l: the light to the right).
    broken = textwrap.dedent(f"""
        import sys
        from biceps.tui.app import BicepsApp

        def broken(*args):
            raise RuntimeError("a fault put there by the test")

        BicepsApp.action_move_light = broken
        from biceps.cli import run
        sys.argv = ["biceps", "app", {str(config_path)!r}]
        run()
    """)
    run = converse([sys.executable, "-c", broken], cwd=config_path.parent, script=[
        (UPPER_HALF, b"c"),  # an edit, not saved
        (b"", b"l"),  # the fault
        (b"ran into an error", b"s"),  # the rescue: save, then quit
    ], XDG_STATE_HOME=str(tmp_path / "state"))
    assert b"RuntimeError: a fault put there by the test" in run.output
    assert b"biceps: stopped on an error it did not expect" in run.output
    assert run.exit_code == 1
    assert load_config(config_path).arm.length == 32.9  # the edit was saved
    # The traceback, kept in a crash report that the last line names.
    (report,) = (tmp_path / "state" / "biceps").iterdir()
    assert f"the details are in {report}".encode() in run.output.replace(b"\r\n", b"")
    text = report.read_text()
    assert "in broken" in text and "RuntimeError: a fault put there by the test" in text
    assert f"model: {config_path}" in text


def _ignores(pid: int, number: int) -> bool:
    """Whether process ``pid`` ignores signal ``number`` (its SigIgn mask in /proc)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("SigIgn:"):
            return bool(int(line.split()[1], 16) >> (number - 1) & 1)
    return False


def test_ctrl_backslash_and_ctrl_z_neither_end_nor_stop_the_app(config_path):
    # In its controlling terminal, as a shell starts it. While it loads, the terminal is in
    # its own mode and turns ctrl+\ into SIGQUIT (a core dump) and ctrl+z into SIGTSTP (a
    # stop, the app half started): both ignored from the moment the command line runs.
    # Once Textual has the terminal they are keys (ctrl+z undo, ctrl+\ nothing).
    before = config_path.read_bytes()
    terminal = RawTerminal(_app(config_path), config_path.parent, (100, 30))
    try:
        pid = terminal.process.pid
        deadline = time.monotonic() + 120
        while not (_ignores(pid, signal.SIGQUIT) and _ignores(pid, signal.SIGTSTP)):
            assert terminal.running() and time.monotonic() < deadline
            time.sleep(0.005)
        terminal.type(b"\x1c\x1a")  # before its first picture, most likely: signals
        assert wait_for(terminal, "\u2580", 120.0)
        terminal.type(b"\x1c\x1a")  # keys
        time.sleep(1.0)
        assert terminal.running()
        assert _state(pid) != "T"  # not stopped
        # Nor by the signal itself, which a ctrl+z raises once Textual has given the
        # terminal back, as the app closes: Textual's own handler stopped it then.
        os.kill(pid, signal.SIGTSTP)
        time.sleep(1.0)
        assert _state(pid) != "T"
        assert quit_app(terminal, (100, 30)) is not None
        assert terminal.exit_status() == 0
    finally:
        terminal.close()
    assert config_path.read_bytes() == before


def _state(pid: int) -> str:
    """A process's state letter (R, S, T for stopped, ...)."""
    return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
