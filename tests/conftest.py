"""Shared fixtures: a private copy of the bundled model, a state folder of the run's own, and no
terminal size in the environment; and the run's workers (pytest-xdist): two a core, the
kernels they load, compiled once as they start, and each set up as the command sets up its
own process."""

from __future__ import annotations

import fcntl
import gc
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG, Config, load_config


def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """``-n auto``: two workers a core this process may run on: a test that starts the app
    waits on it about half of the time."""
    return 2 * len(os.sched_getaffinity(0))


# A frame's kernels, compiled (or loaded from the cache) by a child of the run's.
PREPARE_KERNELS = """
from biceps.engine.coldstart import prepare_kernels
from biceps.engine.settings import SHADINGS
for shading in SHADINGS:
    prepare_kernels(shading)
"""
KERNELS_LOCK = "BICEPS_TESTS_KERNELS_LOCK"  # the file the workers wait on, held by the child
_preparing: list[subprocess.Popen] = []


def pytest_xdist_setupnodes(config: pytest.Config, specs: list) -> None:
    """As the workers start: a frame's kernels compiled once, by a child, while they import
    and collect. Every worker draws, and on a cold cache (a fresh clone) each would compile
    them at the same time; each waits for the child before its first test instead
    (:func:`_kernels_prepared`), and loads them from the cache."""
    lock = tempfile.NamedTemporaryFile(prefix="biceps-kernels-", delete=False)
    with lock:
        # Locked until the child ends: the lock is on the open file, which it inherits.
        fcntl.flock(lock, fcntl.LOCK_EX)
        _preparing.append(subprocess.Popen([sys.executable, "-c", PREPARE_KERNELS],
                                           pass_fds=(lock.fileno(),)))
    os.environ[KERNELS_LOCK] = lock.name  # the workers, started next, inherit it


def pytest_unconfigure(config: pytest.Config) -> None:
    for child in _preparing:
        child.wait()
        os.unlink(os.environ.pop(KERNELS_LOCK))


def pytest_collection_finish(session: pytest.Session) -> None:
    """Set the test process up as the command sets up its own (biceps/cli.py): Textual's
    cache that kept the lines of widgets gone mended, and the heap frozen once loaded, so
    that Python's collections of the oldest generation walk only what the tests make since.
    They walked every module and kernel loaded, and the lines kept, about a third of the
    time of the tests that drive the app."""
    from biceps.tui.textual_private import release_styles_caches

    release_styles_caches()
    gc.collect()
    gc.freeze()


@pytest.fixture(autouse=True, scope="session")
def _kernels_prepared() -> None:
    lock = os.environ.get(KERNELS_LOCK)
    if lock is not None:  # on a worker of a run in parallel
        with open(lock) as prepared:
            fcntl.flock(prepared, fcntl.LOCK_SH)  # once the child preparing them has ended


@pytest.fixture(autouse=True, scope="session")
def _state_home(tmp_path_factory: pytest.TempPathFactory) -> None:
    # Crash reports (tui/crash_report.py) of the apps the tests break on purpose go here,
    # not into the home folder of whoever runs the tests; the apps they start inherit it.
    os.environ["XDG_STATE_HOME"] = str(tmp_path_factory.mktemp("state"))


# What says which terminal a process runs in (terminal/detect.py reads them, and the
# command's choices follow): the tests' own, not those of the terminal the suite is run in.
RUNNERS_TERMINAL = ("TMUX", "STY", "COLORTERM", "TERM_PROGRAM", "TERM_PROGRAM_VERSION",
                    "LC_TERMINAL", "VTE_VERSION", "WT_SESSION")


@pytest.fixture(autouse=True, scope="session")
def _not_the_runners_terminal() -> None:
    # The apps the tests start in ptys and real terminals must take their size from the
    # terminal, as a user's do. Textual takes COLUMNS and LINES over it, and pytest-xdist's
    # workers have them set (80x24).
    for name in ("COLUMNS", "LINES"):
        os.environ.pop(name, None)
    # Run inside tmux, the apps the tests build chose 256 colours and the commands asked
    # tmux to pass images through: 26 tests failed there that pass without a terminal.
    for name in RUNNERS_TERMINAL:
        os.environ.pop(name, None)
    os.environ["TERM"] = "xterm"


@pytest.fixture
def config_path(tmp_path: Path) -> Path:
    """A copy of the bundled configs/biceps.toml that a test may save over."""
    path = tmp_path / "biceps.toml"
    shutil.copy(DEFAULT_CONFIG, path)
    return path


@pytest.fixture
def config(config_path: Path) -> Config:
    return load_config(config_path)


@pytest.fixture
def private_path(monkeypatch: pytest.MonkeyPatch) -> None:
    """The viewport and the app on Textual's internals (tui/textual_private.py), which the
    Textual the tests run on has, even under BICEPS_TEXTUAL_PRIVATE=0: for tests of what
    only that path does (lines written straight to the terminal, images, lines that carry
    their text, the colours and the pacing of a process of its own). The palette's guards
    are chosen once, on import, and stay as they are. A process the test starts (the app
    in a pty) is told so too."""
    from biceps.tui import textual_private

    assert not textual_private._missing(), "the Textual under test lacks what the app uses"
    monkeypatch.setattr(textual_private, "ENABLED", True)
    monkeypatch.setenv(textual_private.SWITCH, "1")
