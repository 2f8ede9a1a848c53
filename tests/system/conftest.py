"""Tests that start processes (the command, the app in a pseudo-terminal, a fresh venv):
slower, so they carry the ``system`` marker (``pytest -m "not system"`` leaves them out)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from installs import fresh_venv
from once import once_a_run

ROOT = Path(__file__).resolve().parents[2]


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if "tests/system/" in item.nodeid:
            item.add_marker(pytest.mark.system)


@pytest.fixture(scope="session")
def wheel(tmp_path_factory) -> Path:
    """A wheel built from this repository, once a run (see tests/once.py)."""

    def build(where: Path) -> None:
        built = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(where),
             str(ROOT)],
            capture_output=True, text=True, timeout=600,
        )
        assert built.returncode == 0, built.stderr

    (built_wheel,) = once_a_run(tmp_path_factory, "wheel", build).glob("biceps-*.whl")
    return built_wheel


@pytest.fixture(scope="session")
def installed(tmp_path_factory, wheel) -> Path:
    """The bin folder of a fresh virtual environment holding the wheel, once a run. Its first
    command, a snapshot, compiles the kernels into the installed package's cache, as a
    user's first would: its other runs, on any worker, load them from there."""

    def install(where: Path) -> None:
        bin_folder = fresh_venv(where, wheel)
        first = subprocess.run([bin_folder / "biceps", "snapshot", "-o", where / "first.png",
                                "--size", "64x36"], capture_output=True, text=True,
                               cwd=where, timeout=300)
        assert first.returncode == 0, first.stderr

    return once_a_run(tmp_path_factory, "installed", install) / "venv" / "bin"
