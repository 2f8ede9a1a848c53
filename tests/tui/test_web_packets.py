"""Under ``biceps serve``, the web driver's packets reach the server whole, though two threads
write them (tui/web_packets.py)."""

from __future__ import annotations

import os
import sys
import threading
import time
from types import SimpleNamespace

from textual.drivers.linux_driver import LinuxDriver
from textual.drivers.web_driver import WebDriver

from biceps.tui.web_packets import one_packet_at_a_time

CHUNK = b"c" * 65_536  # a download's chunk, as textual-serve asks for them
UPDATE = "x" * 5_000  # a screen update, over PIPE_BUF as most are


def _read_packets(fd: int) -> list[tuple[bytes, bytes]]:
    """The packets on the pipe ``fd`` until it is closed, read slowly, as a loaded server
    does, so that the pipe is often full."""
    data = bytearray()
    while block := os.read(fd, 4_096):
        data += block
        time.sleep(0.0002)
    packets = []
    while data:
        size = int.from_bytes(data[1:5], "big")
        packets.append((bytes(data[:1]), bytes(data[5:5 + size])))
        del data[:5 + size]
    return packets


async def test_a_download_s_chunks_and_the_screen_s_updates_do_not_interleave(monkeypatch):
    driver_class = one_packet_at_a_time(WebDriver)
    output, output_end = os.pipe()
    quiet_input, quiet_input_end = os.pipe()
    monkeypatch.setattr(sys, "__stdout__", SimpleNamespace(fileno=lambda: output_end))
    monkeypatch.setattr(sys, "__stdin__", SimpleNamespace(fileno=lambda: quiet_input))
    driver = driver_class(SimpleNamespace())
    packets = []
    reader = threading.Thread(target=lambda: packets.extend(_read_packets(output)))
    reader.start()
    # The input thread answers the server's requests for chunks while the app updates.
    chunks = threading.Thread(target=lambda: [
        driver.write_binary_encoded(("deliver_chunk", "key", CHUNK)) for _ in range(20)])
    chunks.start()
    for _ in range(200):
        driver.write(UPDATE)
    chunks.join()
    os.close(output_end)
    reader.join()
    for fd in (output, quiet_input, quiet_input_end):
        os.close(fd)
    kinds = [kind for kind, _ in packets]
    assert kinds.count(b"D") == 200 and kinds.count(b"P") == 20 and len(kinds) == 220
    assert all(payload == UPDATE.encode() for kind, payload in packets if kind == b"D")
    assert all(CHUNK in payload and b"x" not in payload
               for kind, payload in packets if kind == b"P")


def test_a_terminal_s_driver_is_left_as_it_is():
    assert one_packet_at_a_time(LinuxDriver) is LinuxDriver
