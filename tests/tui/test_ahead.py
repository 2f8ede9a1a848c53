"""The app's output, minimized once the minimizer's kernel is ready (tui/ahead.py)."""

import threading

from biceps.tui import ahead
from biceps.tui.sgr import minimized

TEXT = "\x1b[1m\x1b[31mA\x1b[0m\x1b[1m\x1b[31mB\x1b[0m"


class Recording:
    """A driver that keeps what it is given to write."""

    def __init__(self) -> None:
        self.written: list[str] = []

    def write(self, data: str) -> None:
        self.written.append(data)


def test_output_goes_as_it_is_until_the_minimizer_is_ready(monkeypatch):
    ready = threading.Event()
    monkeypatch.setattr(ahead, "_minimizer_ready", ready)
    driver = ahead.lean_once_ready(Recording)()
    driver.write(TEXT)
    ready.set()
    driver.write(TEXT)
    assert minimized(TEXT) != TEXT
    assert driver.written == [TEXT, minimized(TEXT)]
