"""The app on the oldest Textual the pin allows, installed from the package index in a fresh
venv beside the wheel's: the seam (tui/textual_private.py) takes the private path there, and
the app runs."""

from __future__ import annotations

import subprocess
from importlib.metadata import requires

import pytest
from packaging.requirements import Requirement

from biceps.tui import textual_private
from installs import shared_venv, site_folder
from pty_app import converse


def oldest_allowed(name: str) -> str:
    """The lowest version of ``name`` that biceps's requirements allow."""
    (requirement,) = [Requirement(text) for text in requires("biceps")
                      if Requirement(text).name == name and not Requirement(text).marker]
    (lowest,) = [spec.version for spec in requirement.specifier if spec.operator == ">="]
    return lowest


OLDEST = oldest_allowed("textual")


@pytest.fixture(scope="module")
def oldest(tmp_path_factory, installed) -> list[str]:
    """The command in a fresh venv holding the oldest Textual allowed, beside the wheel's
    (``installed``): biceps and its compiled kernels come from there."""
    bin_folder = shared_venv(tmp_path_factory, "oldest-textual", None, f"textual=={OLDEST}",
                             beside=[site_folder(installed)])
    return [str(bin_folder / "python"), "-m", "biceps"]


def test_the_pin_allows_no_textual_older_than_the_seam_knows():
    assert textual_private._version(OLDEST) == textual_private.OLDEST


def test_the_app_runs_on_the_oldest_textual_the_pin_allows(private_path, oldest, tmp_path):
    doctor = subprocess.run([*oldest, "doctor"], capture_output=True, text=True,
                            cwd=tmp_path, timeout=300)
    assert doctor.returncode == 0, doctor.stderr
    assert f"the private path (Textual {OLDEST}'s internals" in doctor.stdout
    # The picture (drawn through the private path's strips), help opened and closed, the
    # model contracted, then quit without saving it.
    run = converse(oldest, cwd=tmp_path, script=[
        ("▀".encode(), b"?"),
        (b"Turn, move and scale", b"\x1b"),
        (b"", b"cc"),
        (b"", b"q"),
        (b"Don't save", b"n"),
    ], again=5, timeout=300)
    assert run.exit_code == 0, run.output[-2000:]
