"""Fresh virtual environments holding the wheel, as a user installs it."""

from __future__ import annotations

import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from once import once_a_run


def fresh_venv(where: Path, wheel: Path, *requirements: str) -> Path:
    """A fresh virtual environment in ``where`` holding ``wheel`` and ``requirements``
    (from the package index), and the bin folder of it. Its other dependencies come from
    the environment running the tests, added with a .pth line, which comes after the
    venv's own packages (and, unlike a site folder, runs none of that folder's .pth files,
    so the editable install there stays out)."""
    venv = where / "venv"
    # Without a pip of its own (installing one takes seconds): the tests' pip installs into
    # it, as it would into a venv with one.
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=300)
    python = venv / "bin" / "python"
    pip = [sys.executable, "-m", "pip", "--python", str(python), "install", "-q", "--no-deps"]
    subprocess.run([*pip, "--no-index", wheel], check=True, timeout=300)
    if requirements:
        subprocess.run([*pip, *requirements], check=True, timeout=600)
    purelib = subprocess.run(
        [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True, text=True, check=True).stdout.strip()
    Path(purelib, "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    return venv / "bin"


def shared_venv(tmp_path_factory: pytest.TempPathFactory, name: str, wheel: Path,
                *requirements: str) -> Path:
    """The bin folder of :func:`fresh_venv`, made once a run under ``name``."""
    where = once_a_run(tmp_path_factory, name,
                       lambda folder: fresh_venv(folder, wheel, *requirements))
    return where / "venv" / "bin"
