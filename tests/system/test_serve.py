"""``biceps serve`` from outside, through websocket clients as a browser's page would connect:
the extra it needs, where it listens, its cap on visitors, and every visitor's process and
folder gone when its page closes."""

from __future__ import annotations

import asyncio
import os
import re
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from biceps.engine.config import DEFAULT_CONFIG
from biceps.zygote import VISITOR_NAME, ZYGOTE_NAME
from browser import free_port, served
from waiting import came

pytest.importorskip("aiohttp", reason="comes with textual-serve, the serve extra")
import aiohttp  # noqa: E402

HALF_BLOCKS = ("\u2580".encode(), "\u2584".encode())  # upper and lower
CONTROL_SEQUENCE = re.compile(rb"\x1b\[[0-9;?]*[A-Za-z]")  # colours, cursor moves
CURSOR_AT = re.compile(rb"\x1b\[\d+;(\d+)H")


def _visitors() -> list[int]:
    """The ids of the processes running a visitor's app now: ``biceps visit`` started
    afresh, or forked from the zygote (biceps/zygote.py), and the small process that
    stands for it."""
    found = []
    for pattern in (["-f", r"biceps visit|biceps\.zygote .* visit "], ["-x", VISITOR_NAME]):
        run = subprocess.run(["pgrep", *pattern], capture_output=True, text=True)
        found += [int(line) for line in run.stdout.split()]
    return found


def _until(condition, what: str, timeout: float = 60.0) -> None:
    came(lambda: condition() or None, what, timeout, step=0.2)


async def _first_picture(websocket) -> bytes:
    """Read the visitor's terminal until the picture's half-blocks come; what it read."""
    seen = b""
    while True:
        message = await asyncio.wait_for(websocket.receive(), 120)
        assert message.type == aiohttp.WSMsgType.BINARY, message
        seen += message.data
        if any(block in message.data for block in HALF_BLOCKS):
            return seen


async def test_a_download_waits_for_a_chunk_longer_than_textual_serve_would(tmp_path):
    # textual-serve gave up on a visitor's app that took over 4 s to send a chunk (a loaded
    # server), and the download never came.
    from biceps.serve import Limits, make_server

    manager = make_server(DEFAULT_CONFIG, "localhost", free_port(), 1, tmp_path,
                          Limits(memory=500, minutes=1)).download_manager

    received = []

    class App:  # answers the request for the chunk late, then the end of the file
        app_service_id = "app"

        async def send_meta(self, meta: dict) -> bool:
            delay = 4.3 if not received else 0.0  # textual-serve waited 4 s
            asyncio.get_running_loop().call_later(delay, lambda: asyncio.ensure_future(
                manager.chunk_received("key", b"" if received else b"chunk")))
            return True

    await manager.create_download(app_service=App(), delivery_key="key", file_name="a.png",
                                  open_method="download", mime_type="image/png")
    async for chunk in manager.download("key"):
        received.append(chunk)
    assert received == [b"chunk"]


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


def _scratch_of(pids: set[int]) -> set[Path]:
    """The scratch folders named on the command lines of ``pids``."""
    found = set()
    for pid in pids:
        try:
            words = Path(f"/proc/{pid}/cmdline").read_bytes().decode().split("\0")
        except OSError:
            continue
        if "--scratch" in words:
            found.add(Path(words[words.index("--scratch") + 1]))
    return found


def test_a_full_server_says_so_and_a_closed_page_ends_its_visitors_process(tmp_path):
    with served(DEFAULT_CONFIG, "--max-visitors", "1") as url:
        socket_url = url.replace("http", "ws") + "ws?width=100&height=30"

        async def visit() -> tuple[set[int], int, str, bool]:
            async with aiohttp.ClientSession() as session:
                async with session.ws_connect(socket_url) as first:
                    await _first_picture(first)
                    own = _visitors_of(url)  # its shell, and the app
                    assert own
                    # This server's scratch folder (another's, on a shared machine, has
                    # visitors of its own).
                    scratch.extend(_scratch_of(own))
                    assert list(scratch[0].glob("visitor-*"))
                    async with session.get(url) as response:
                        status, page = response.status, await response.text()
                    async with session.ws_connect(socket_url) as second:
                        message = await asyncio.wait_for(second.receive(), 60)
                        turned_away = b"full" in message.data
                return own, status, page, turned_away

        scratch: list[Path] = []
        own, status, page, turned_away = asyncio.run(visit())
        assert status == 503 and "All 1 places are taken" in page
        assert turned_away
        _until(lambda: not own & set(_visitors()), "the visitor's process ending")
        left = list(scratch[0].glob("visitor-*"))
        assert not left, left

        async def page_again() -> int:
            async with aiohttp.ClientSession() as session:
                async with session.get(url) as response:
                    return response.status

        assert asyncio.run(page_again()) == 200


def _named(name: str) -> dict[int, int]:
    """The processes named ``name`` now (``ps``'s name, not the command line): pid: parent."""
    found = {}
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and (entry / "comm").read_text().strip() == name:
                found[int(entry.name)] = _parent(entry)
        except (OSError, IndexError, ValueError):
            continue
    return found


def _parent(process: Path) -> int:
    """The parent's pid of the process whose /proc folder is ``process``."""
    return int((process / "stat").read_text().rsplit(")", 1)[1].split()[1])


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, ended but not yet reaped, does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _tree(root: int) -> set[int]:
    """``root`` and every process under it now."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit():
                children.setdefault(_parent(entry), []).append(int(entry.name))
        except (OSError, IndexError, ValueError):
            continue
    found, todo = {root}, [root]
    while todo:
        for child in children.get(todo.pop(), []):
            found.add(child)
            todo.append(child)
    return found


async def _read_until(websocket, wanted: bytes, timeout: float = 120) -> bytes:
    """The visitor's terminal's output until ``wanted`` comes in its text: a line of text may
    come in pieces, written where they go (a note over the picture's edge, say)."""
    seen = b""
    deadline = time.monotonic() + timeout
    while wanted not in CONTROL_SEQUENCE.sub(b"", seen):
        message = await asyncio.wait_for(websocket.receive(), deadline - time.monotonic())
        if message.type in (aiohttp.WSMsgType.CLOSE, aiohttp.WSMsgType.CLOSED):
            raise AssertionError(f"closed before {wanted!r} came: {seen[-400:]!r}")
        if message.type == aiohttp.WSMsgType.BINARY:
            seen += message.data
    return seen


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM])
def test_visitors_are_forked_from_the_zygote_and_none_outlives_the_server(stop):
    port = free_port()
    server = subprocess.Popen(
        [sys.executable, "-m", "biceps", "serve", str(DEFAULT_CONFIG), "--port", str(port)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        _until(lambda: _listening(port), "the server")
        _until(lambda: any(parent == server.pid for parent in _named(ZYGOTE_NAME).values()),
               "the zygote")
        zygote = next(pid for pid, parent in _named(ZYGOTE_NAME).items()
                      if parent == server.pid)

        async def two_visitors() -> set[int]:
            async with aiohttp.ClientSession() as session:
                sockets = [await session.ws_connect(
                    f"ws://127.0.0.1:{port}/ws?width={width}&height=30") for width in (60, 100)]
                for websocket, width in zip(sockets, (60, 100)):
                    drawn = await _first_picture(websocket)
                    # Each on a terminal of its own size: the cursor sent to column 60 at
                    # most in the first, farther in the second.
                    farthest = max(int(column) for column in CURSOR_AT.findall(drawn))
                    assert farthest <= width
                    assert farthest > 60 or width == 60
                everyone = _tree(server.pid)
                apps = {pid for pid, parent in _named(VISITOR_NAME).items() if parent == zygote}
                assert len(apps) == 2, apps  # each a child of the zygote, not started afresh
                # With both pages still open. (The session drops them as it closes: a
                # websocket's close would wait 10 s for an answer from a server ending.)
                server.send_signal(stop)
                return everyone

        everyone = asyncio.run(two_visitors())
        server.wait(timeout=60)
        _until(lambda: not any(_alive(pid) for pid in everyone), "every process ending", 30)
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()


def test_without_the_zygote_visitors_still_get_the_app_and_the_server_says_so(tmp_path):
    log = tmp_path / "server.log"
    with served(DEFAULT_CONFIG, log=log) as url:
        _until(lambda: _named(ZYGOTE_NAME).keys() & _tree_of_server(url), "the zygote")
        for pid in _named(ZYGOTE_NAME).keys() & _tree_of_server(url):
            os.kill(pid, signal.SIGKILL)
        _until(lambda: b"each visitor's app now starts on its own" in log.read_bytes(),
               "the server saying the zygote ended")

        async def visit() -> None:
            async with aiohttp.ClientSession() as session:
                async with session.ws_connect(url.replace("http", "ws") + "ws") as websocket:
                    await _first_picture(websocket)

        asyncio.run(visit())


def _visitors_of(url: str) -> set[int]:
    """The visitors' processes of the server listening at ``url`` (the tests run side by
    side, and other servers have visitors of their own)."""
    return set(_visitors()) & _tree_of_server(url)


def _tree_of_server(url: str) -> set[int]:
    """The processes under the server listening at ``url``."""
    port = url.rsplit(":", 1)[1].strip("/")
    found = subprocess.run(["pgrep", "-f", f"biceps serve .*--port {port}"],
                           capture_output=True, text=True)
    return set().union(*(_tree(int(pid)) for pid in found.stdout.split()))


def test_a_visitor_over_its_memory_is_refused_the_export_and_goes_on(tmp_path):
    with served(DEFAULT_CONFIG, "--visitor-memory", "500") as url:
        socket_url = url.replace("http", "ws") + "ws?width=100&height=30"

        async def visit() -> None:
            async with aiohttp.ClientSession() as session:
                async with session.ws_connect(socket_url) as websocket, \
                        session.ws_connect(socket_url) as other:
                    await _first_picture(websocket)
                    await _first_picture(other)
                    # An 8000x6000 picture (over 300 MB more) is within what a command may
                    # draw, not within 500 MB.
                    await websocket.send_json(["stdin", "e"])
                    await _read_until(websocket, b"Export a PNG")
                    for key in ("\t", "\x7f" * 20, "8000x6000", "\r"):
                        await websocket.send_json(["stdin", key])
                        await asyncio.sleep(0.3)
                    await _read_until(websocket, b"not enough memory for a 8000x6000 picture")
                    for visitor in (websocket, other):  # both go on: a key, a new picture
                        await visitor.send_json(["stdin", "c"])
                        await _first_picture(visitor)

        asyncio.run(visit())


def test_a_visitor_is_told_when_its_time_is_up_and_its_place_is_freed():
    with served(DEFAULT_CONFIG, "--visitor-minutes", "0.2", "--max-visitors", "1") as url:
        socket_url = url.replace("http", "ws") + "ws"

        async def visit() -> bytes:
            async with aiohttp.ClientSession() as session:
                async with session.ws_connect(socket_url) as websocket:
                    said = await _read_until(websocket, b"minutes are up", 120)
                    # The page stays open with the note on it, its app gone, and the one
                    # place is free for the next visitor.
                    _until(lambda: not _visitors_of(url), "the visitor's process ending")
                    async with session.ws_connect(socket_url) as next_one:
                        await _first_picture(next_one)
                    assert not websocket.closed
                    return said

        said = asyncio.run(visit())
        assert b"Your 0.2 minutes are up" in said
        assert any(block in said for block in HALF_BLOCKS)  # the app, until then
