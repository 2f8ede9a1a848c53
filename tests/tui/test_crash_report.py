"""The crash report: an unexpected error's traceback kept in a file, whatever the terminal
could show of it."""

from __future__ import annotations

import os
from pathlib import Path

from rich.traceback import Traceback

from biceps.tui.crash_report import KEPT, crash_folder, text_of, traceback_of, write_crash_report


def _raised() -> BaseException:
    def deep(count: int) -> None:
        if count:
            deep(count - 1)
        raise ValueError("a fault put there by the test")

    try:
        deep(3)
    except ValueError as error:
        return error


def test_a_report_keeps_the_traceback_with_what_explains_it(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    monkeypatch.setenv("TERM", "xterm-kitty")
    path = write_crash_report(traceback_of(_raised()), Path("/models/elbow.toml"),
                              graphics="kitty")
    assert path is not None and path.parent == tmp_path / "state" / "biceps"
    report = path.read_text()
    assert report.startswith("biceps crash report, ")
    assert "Textual " in report and "Python " in report
    assert "TERM='xterm-kitty'" in report
    assert "model: /models/elbow.toml" in report
    assert "graphics: kitty" in report
    assert "in deep" in report  # the frames, not only the message
    assert report.rstrip().endswith("ValueError: a fault put there by the test")
    assert not [name for name in os.listdir(path.parent) if not name.startswith("crash-")]


def test_a_relative_state_home_is_ignored_as_the_specification_says(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setenv("XDG_STATE_HOME", "relative/state")
    assert crash_folder() == tmp_path / ".local" / "state" / "biceps"
    monkeypatch.delenv("XDG_STATE_HOME")
    assert crash_folder() == tmp_path / ".local" / "state" / "biceps"


def test_a_report_that_cannot_be_written_is_none(tmp_path, monkeypatch):
    blocker = tmp_path / "a file"
    blocker.write_text("")
    monkeypatch.setenv("XDG_STATE_HOME", str(blocker))  # a folder cannot be made in it
    assert write_crash_report("details", None) is None


def test_only_the_newest_reports_are_kept(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path))
    folder = tmp_path / "biceps"
    folder.mkdir()
    old = [folder / f"crash-20200101-{day:06d}-1.txt" for day in range(KEPT + 5)]
    for path in old:
        path.write_text("old")
    newest = write_crash_report("details", None)
    kept = sorted(folder.iterdir())
    assert len(kept) == KEPT and kept[-1] == newest
    assert kept[:-1] == sorted(old)[-(KEPT - 1):]


def test_a_panic_s_renderables_become_plain_text():
    # What Textual's input thread hands to App.panic: a rich traceback of its error.
    error = _raised()
    try:
        raise error
    except ValueError:
        rendered = text_of((Traceback(),))
    assert "a fault put there by the test" in rendered
    assert "\x1b[" not in rendered
