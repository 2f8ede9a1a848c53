"""Fresh virtual environments holding the wheel, as a user installs it."""

from __future__ import annotations

import subprocess
import sys
import sysconfig
from pathlib import Path
from typing import Sequence

import pytest

from once import once_a_run


def fresh_venv(where: Path, wheel: Path | None, *requirements: str,
               beside: Sequence[Path] = ()) -> Path:
    """A fresh virtual environment in ``where`` holding ``wheel`` (if any) and
    ``requirements`` (from the package index), and the bin folder of it. What it does not
    hold it imports from the site folders ``beside`` (another venv's), then from the
    environment running the tests: each is added with a .pth line, which comes after the
    venv's own packages (and, unlike a site folder, runs none of that folder's .pth files,
    so the editable install there stays out)."""
    venv = where / "venv"
    # Without a pip of its own (installing one takes seconds): the tests' pip installs into
    # it, as it would into a venv with one.
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=300)
    pip = [sys.executable, "-m", "pip", "--python", str(venv / "bin" / "python"), "install",
           "-q", "--no-deps"]
    if wheel is not None:
        subprocess.run([*pip, "--no-index", wheel], check=True, timeout=300)
    if requirements:
        subprocess.run([*pip, *requirements], check=True, timeout=600)
    lines = [*beside, sysconfig.get_paths()["purelib"]]
    Path(site_folder(venv / "bin"), "dependencies.pth").write_text(
        "".join(f"{line}\n" for line in lines))
    return venv / "bin"


def site_folder(bin_folder: Path) -> Path:
    """Where the venv of ``bin_folder`` installs its packages."""
    return Path(subprocess.run(
        [bin_folder / "python", "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True, text=True, check=True).stdout.strip())


def shared_venv(tmp_path_factory: pytest.TempPathFactory, name: str, wheel: Path | None,
                *requirements: str, beside: Sequence[Path] = ()) -> Path:
    """The bin folder of :func:`fresh_venv`, made once a run under ``name``."""
    where = once_a_run(tmp_path_factory, name,
                       lambda folder: fresh_venv(folder, wheel, *requirements, beside=beside))
    return where / "venv" / "bin"
