"""``biceps serve`` from outside, through websocket clients as a browser's page would connect:
the extra it needs, where it listens, its cap on visitors, and every visitor's process and
folder gone when its page closes."""

from __future__ import annotations

import asyncio
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG
from biceps.zygote import VISITOR_NAME
from browser import free_port, served

pytest.importorskip("aiohttp", reason="comes with textual-serve, the serve extra")
import aiohttp  # noqa: E402

HALF_BLOCKS = ("\u2580".encode(), "\u2584".encode())  # upper and lower


def _visitors() -> list[int]:
    """The ids of the processes running a visitor's app now: ``biceps visit`` started
    afresh, or forked from the zygote (biceps/zygote.py), and the small process that
    stands for it."""
    found = []
    for pattern in (["-f", r"biceps visit|biceps\.zygote .* visit "], ["-x", VISITOR_NAME]):
        run = subprocess.run(["pgrep", *pattern], capture_output=True, text=True)
        found += [int(line) for line in run.stdout.split()]
    return found


def _until(condition, what: str, timeout: float = 60.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.2)
    raise AssertionError(f"never came: {what}")


async def _first_picture(websocket) -> None:
    """Read the visitor's terminal until the picture's half-blocks come."""
    while True:
        message = await asyncio.wait_for(websocket.receive(), 120)
        assert message.type == aiohttp.WSMsgType.BINARY, message
        if any(block in message.data for block in HALF_BLOCKS):
            return


def test_without_the_extra_the_message_names_it(tmp_path):
    hidden = tmp_path / "textual_serve"
    hidden.mkdir()
    (hidden / "__init__.py").write_text("raise ImportError('not installed')\n")
    run = subprocess.run([sys.executable, "-m", "biceps", "serve", "--port", str(free_port())],
                         capture_output=True, text=True, timeout=60,
                         env={**os.environ, "PYTHONPATH": str(tmp_path)})
    assert run.returncode == 2
    assert "pip install 'biceps[serve]'" in run.stderr
    assert "Traceback" not in run.stderr


def test_a_bad_configuration_is_refused_before_serving(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[muscle\n")
    run = subprocess.run([sys.executable, "-m", "biceps", "serve", str(bad)],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert "bad.toml" in run.stderr and "Traceback" not in run.stderr


def _other_address() -> str | None:
    """An address of this machine's other than loopback, if it has one."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect(("192.0.2.1", 9))  # TEST-NET-1: nothing is sent
        except OSError:
            return None
        address = probe.getsockname()[0]
    return None if address.startswith("127.") else address


def test_it_listens_on_localhost_only_unless_told(tmp_path):
    other = _other_address()
    if other is None:
        pytest.skip("this machine has no address but loopback to try")
    with served(DEFAULT_CONFIG) as url:
        port = int(url.rsplit(":", 1)[1].strip("/"))
        socket.create_connection(("127.0.0.1", port), timeout=5).close()
        with pytest.raises(OSError):
            socket.create_connection((other, port), timeout=5).close()


def test_another_host_is_served_with_a_warning_and_the_page_uses_the_browsers_address():
    port = free_port()
    server = subprocess.Popen(
        [sys.executable, "-m", "biceps", "serve", "--host", "0.0.0.0", "--port", str(port)],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        warning = server.stderr.readline()
        assert "anyone who can reach this machine on port" in warning
        _until(lambda: _listening(port), "the server")

        async def page() -> str:
            async with aiohttp.ClientSession() as session:
                async with session.get(f"http://127.0.0.1:{port}/") as response:
                    return await response.text()

        assert f"ws://127.0.0.1:{port}/ws" in asyncio.run(page())
    finally:
        server.terminate()
        server.wait(timeout=20)


def _listening(port: int) -> bool:
    try:
        socket.create_connection(("127.0.0.1", port), timeout=1).close()
        return True
    except OSError:
        return False


def test_a_full_server_says_so_and_a_closed_page_ends_its_visitors_process(tmp_path):
    before = set(_visitors())
    folders = set(Path(tempfile.gettempdir()).glob("biceps-serve-*/visitor-*"))
    with served(DEFAULT_CONFIG, "--max-visitors", "1") as url:
        socket_url = url.replace("http", "ws") + "ws?width=100&height=30"

        async def visit() -> tuple[set[int], int, str, bool]:
            async with aiohttp.ClientSession() as session:
                async with session.ws_connect(socket_url) as first:
                    await _first_picture(first)
                    own = set(_visitors()) - before  # its shell, and the app
                    assert own
                    async with session.get(url) as response:
                        status, page = response.status, await response.text()
                    async with session.ws_connect(socket_url) as second:
                        message = await asyncio.wait_for(second.receive(), 60)
                        turned_away = b"full" in message.data
                return own, status, page, turned_away

        own, status, page, turned_away = asyncio.run(visit())
        assert status == 503 and "All 1 places are taken" in page
        assert turned_away
        _until(lambda: not own & set(_visitors()), "the visitor's process ending")
        left = set(Path(tempfile.gettempdir()).glob("biceps-serve-*/visitor-*")) - folders
        assert not left, left

        async def page_again() -> int:
            async with aiohttp.ClientSession() as session:
                async with session.get(url) as response:
                    return response.status

        assert asyncio.run(page_again()) == 200
