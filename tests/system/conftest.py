"""Tests that start processes (the command, the app in a pseudo-terminal, a fresh venv):
slower, so they carry the ``system`` marker (``pytest -m "not system"`` leaves them out)."""

import pytest


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if "tests/system/" in item.nodeid:
            item.add_marker(pytest.mark.system)
