"""Shared fixtures: a private copy of the bundled model, and a state folder of the run's own."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG, Config, load_config


@pytest.fixture(autouse=True, scope="session")
def _state_home(tmp_path_factory: pytest.TempPathFactory) -> None:
    # Crash reports (tui/crash_report.py) of the apps the tests break on purpose go here,
    # not into the home folder of whoever runs the tests; the apps they start inherit it.
    os.environ["XDG_STATE_HOME"] = str(tmp_path_factory.mktemp("state"))


@pytest.fixture
def config_path(tmp_path: Path) -> Path:
    """A copy of the bundled configs/biceps.toml that a test may save over."""
    path = tmp_path / "biceps.toml"
    shutil.copy(DEFAULT_CONFIG, path)
    return path


@pytest.fixture
def config(config_path: Path) -> Config:
    return load_config(config_path)
