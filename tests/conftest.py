"""Shared fixtures: a private copy of the bundled model."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG, Config, load_config


@pytest.fixture
def config_path(tmp_path: Path) -> Path:
    """A copy of the bundled configs/biceps.toml that a test may save over."""
    path = tmp_path / "biceps.toml"
    shutil.copy(DEFAULT_CONFIG, path)
    return path


@pytest.fixture
def config(config_path: Path) -> Config:
    return load_config(config_path)
