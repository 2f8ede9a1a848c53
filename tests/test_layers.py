"""The layers hold: import-linter's contracts (pyproject.toml, [tool.importlinter])."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# Where each folder of the repository goes in the installed package (pyproject.toml).
LAYOUT = {"engine": "engine", "terminal": "terminal", "tui": "tui", "configs": "configs"}


def _laid_out(where: Path) -> Path:
    """A copy of the sources as they are installed, biceps/engine and all: import-linter
    reads a package's folder, and the repository keeps engine/, terminal/ and tui/ beside
    biceps/, not in it."""
    package = where / "biceps"
    shutil.copytree(ROOT / "biceps", package, ignore=shutil.ignore_patterns("__pycache__"))
    for folder, name in LAYOUT.items():
        shutil.copytree(ROOT / folder, package / name,
                        ignore=shutil.ignore_patterns("__pycache__", "*.toml", "*.json"))
    return where


def _lint_imports(where: Path) -> subprocess.CompletedProcess:
    lint = Path(sys.executable).with_name("lint-imports")
    return subprocess.run([str(lint), "--no-cache", str(ROOT / "pyproject.toml")],
                          capture_output=True, text=True, cwd=where, timeout=300)


def test_the_import_contracts_are_kept(tmp_path):
    where = _laid_out(tmp_path)
    process = _lint_imports(where)
    assert process.returncode == 0, process.stdout + process.stderr
    assert "4 kept, 0 broken" in process.stdout


def test_a_broken_contract_is_found(tmp_path):
    where = _laid_out(tmp_path)
    widget = where / "biceps" / "tui" / "widgets" / "stats.py"
    widget.write_text(widget.read_text() + "\nfrom biceps.tui.screens import prompt\n")
    process = _lint_imports(where)
    assert process.returncode == 1
    assert "biceps.tui.widgets.stats -> biceps.tui.screens.prompt" in process.stdout
