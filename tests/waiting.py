"""Waiting for something the app does in its own time: in a pilot test, or (in a system test)
in a process of its own."""

from __future__ import annotations

import time
from typing import Callable, TypeVar

from textual.pilot import Pilot

T = TypeVar("T")


async def until(pilot: Pilot, condition: Callable[[], object],
                what: str = "what the test waited for") -> None:
    """Let the app run until ``condition()`` holds (ten seconds at most); AssertionError
    naming ``what`` if it never did."""
    for _ in range(1000):
        if condition():
            return
        await pilot.pause(0.01)
    raise AssertionError(f"never happened: {what}")


def came(condition: Callable[[], T | None], what: str, timeout: float = 120.0,
         step: float = 0.3) -> T:
    """The first result of ``condition()`` that is not None, asked every ``step`` seconds
    for ``timeout`` seconds at most; AssertionError naming ``what`` if none came."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        found = condition()
        if found is not None:
            return found
        time.sleep(step)
    raise AssertionError(f"never came: {what}")
