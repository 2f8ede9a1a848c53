"""Under ``biceps serve``: Textual's web driver, writing one packet at a time.

The web driver frames everything it sends the server as packets on one pipe, and writes
them from two threads: the screen's updates from the app's event loop, and a download's
chunks from its input thread, which answers the server's requests for them. A write of more
than ``PIPE_BUF`` bytes to a pipe is not atomic: when the server reads slower than the app
writes (a loaded machine), a chunk and an update interleave, the server loses the framing,
and the visitor's page freezes with its download never coming. A lock keeps each packet
whole.
"""

from __future__ import annotations

import sys
import threading

from textual.driver import Driver


def one_packet_at_a_time(driver_class: type[Driver]) -> type[Driver]:
    """``driver_class``, its packets written one at a time if it is Textual's web driver;
    any other driver as it is."""
    # Imported already if the web driver was chosen: no import for a terminal's driver.
    web_driver = sys.modules.get("textual.drivers.web_driver")
    if web_driver is None or not issubclass(driver_class, web_driver.WebDriver):
        return driver_class

    class OnePacketAtATime(driver_class):
        def __init__(self, *args, **kwargs) -> None:
            super().__init__(*args, **kwargs)
            self.writing = threading.Lock()

        def write(self, data: str) -> None:
            with self.writing:
                super().write(data)

        def write_meta(self, data: dict[str, object]) -> None:
            with self.writing:
                super().write_meta(data)

        def write_binary_encoded(self, data: tuple[str | bytes, ...]) -> None:
            with self.writing:
                super().write_binary_encoded(data)

    OnePacketAtATime.__name__ = OnePacketAtATime.__qualname__ = driver_class.__name__
    return OnePacketAtATime
