"""Things a test run makes once, however many pytest-xdist workers it has: each worker is a
process of its own with session fixtures of its own, and two building the same thing at once
get in each other's way (two wheel builds share the repository's build/ folder)."""

from __future__ import annotations

import fcntl
import os
import shutil
from pathlib import Path
from typing import Callable

import pytest


def once_a_run(tmp_path_factory: pytest.TempPathFactory, name: str,
               make: Callable[[Path], None]) -> Path:
    """A folder, ``name``, that ``make(folder)`` fills once a run: the first worker to ask
    makes it, while the others wait for it; a worker's later asks find it made."""
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # the run's, above the workers' own
    folder, made = base / name, base / f"{name}.made"
    with open(base / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if not made.exists():
            shutil.rmtree(folder, ignore_errors=True)  # what a failed try left
            folder.mkdir()
            make(folder)
            made.touch()
    return folder
