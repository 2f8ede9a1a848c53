"""Waiting, in a pilot test, for something the app does in its own time."""

from __future__ import annotations

from typing import Callable

from textual.pilot import Pilot


async def until(pilot: Pilot, condition: Callable[[], object]) -> None:
    """Let the app run until ``condition()`` holds (ten seconds at most)."""
    for _ in range(1000):
        if condition():
            return
        await pilot.pause(0.01)
    raise AssertionError("never happened")
