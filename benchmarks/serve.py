"""``biceps serve`` under a class: N visitors at once, as websocket clients that answer the
terminal's questions as the page's terminal (xterm.js) does.

For each visitor: the time from opening its websocket to its first picture (the first
output with half-block cells, upper or lower), the median time from a key (``]`` and ``[`` in turn, rolling
the model) to the first output of a picture after it, and its processes' memory (RSS, and
PSS, which splits shared pages among their users), read from /proc once every visitor has
its picture. All visitors connect at once and press their keys at the same time.

    python benchmarks/serve.py [--visitors 10] [--keys 20] [--config FILE] [--public]
                               [--python PYTHON]

``--python``: the interpreter whose ``biceps`` serves, e.g. another worktree's venv, to compare.

Prints one row per visitor and the medians, with the load average before and after.
Needs the serve extra (textual-serve, which brings aiohttp).
"""

from __future__ import annotations

import argparse
import asyncio
import os
import re
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import aiohttp

from biceps.engine.config import DEFAULT_CONFIG

HALF_BLOCKS = ("\u2580".encode(), "\u2584".encode())  # upper and lower
CURSOR_QUESTION = re.compile(rb"\x1b\[(\d+);(\d+)H\x1b\[6n")
QUIET = 0.3  # seconds without output before a key, so its answer is not the last key's


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


class Visitor:
    """One page's terminal: reads the app's output, answers its cursor questions."""

    def __init__(self, websocket: aiohttp.ClientWebSocketResponse) -> None:
        self.websocket = websocket
        self.pictures = asyncio.Queue()  # arrival time of each output with half-blocks
        self.last_output = time.monotonic()

    async def read(self) -> None:
        async for message in self.websocket:
            if message.type != aiohttp.WSMsgType.BINARY:
                continue
            now = self.last_output = time.monotonic()
            for found in CURSOR_QUESTION.finditer(message.data):  # as xterm.js answers
                row, column = found.groups()
                await self.websocket.send_json(
                    ["stdin", f"\x1b[{row.decode()};{column.decode()}R"])
            if any(block in message.data for block in HALF_BLOCKS):
                self.pictures.put_nowait(now)

    async def first_picture(self, since: float) -> float:
        return await asyncio.wait_for(self.pictures.get(), 120) - since

    async def key(self, key: str) -> float:
        while time.monotonic() - self.last_output < QUIET:
            await asyncio.sleep(0.05)
        while not self.pictures.empty():
            self.pictures.get_nowait()
        sent = time.monotonic()
        await self.websocket.send_json(["stdin", key])
        return await asyncio.wait_for(self.pictures.get(), 30) - sent


async def visit(url: str, keys: int, everyone_up: asyncio.Barrier,
                measured: asyncio.Event) -> tuple[float, list[float]]:
    async with aiohttp.ClientSession() as session:
        opened = time.monotonic()
        async with session.ws_connect(f"{url}?width=120&height=36", max_msg_size=0) as socket_:
            visitor = Visitor(socket_)
            reader = asyncio.create_task(visitor.read())
            first = await visitor.first_picture(opened)
            await everyone_up.wait()
            await measured.wait()  # the memory, read while every visitor is idle
            latencies = [await visitor.key("]" if index % 2 == 0 else "[")
                         for index in range(keys)]
            reader.cancel()
            return first, latencies


def descendants(pid: int) -> list[int]:
    """Every process under ``pid``."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                parent = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(parent, []).append(int(entry.name))
    found, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def memory(pid: int) -> tuple[float, float]:
    """RSS and PSS of ``pid`` in MB."""
    fields = dict(line.split(":", 1) for line in
                  Path(f"/proc/{pid}/smaps_rollup").read_text().splitlines()[1:])
    return tuple(int(fields[name].split()[0]) / 1024 for name in ("Rss", "Pss"))


def visitor_memory(server: int) -> list[tuple[float, float]]:
    """Each visitor's app process: RSS and PSS in MB. Forked from the zygote, it is named
    biceps-visitor; started afresh, its command is ``python -m biceps visit``."""
    found = []
    for pid in descendants(server):
        try:
            name = Path(f"/proc/{pid}/comm").read_text().strip()
            command = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if name == "biceps-visitor" or command[1:4] == [b"-m", b"biceps", b"visit"]:
            found.append(memory(pid))
    return found


def zygote_memory(server: int) -> tuple[float, float] | None:
    """The zygote's RSS and PSS in MB, if the server has one."""
    for pid in descendants(server):
        try:
            if Path(f"/proc/{pid}/comm").read_text().strip() == "biceps-zygote":
                return memory(pid)
        except OSError:
            continue
    return None


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--visitors", type=int, default=10)
    parser.add_argument("--keys", type=int, default=20)
    parser.add_argument("--config", default=str(DEFAULT_CONFIG))
    parser.add_argument("--settle", type=float, default=10.0,
                        help="seconds between the server listening and the visitors coming")
    parser.add_argument("--python", default=sys.executable,
                        help="the interpreter whose biceps serves (default: this one)")
    parser.add_argument("--public", action="store_true",
                        help="the app on Textual's public path (BICEPS_TEXTUAL_PRIVATE=0)")
    options = parser.parse_args()
    port = free_port()
    environment = {**os.environ, "BICEPS_TEXTUAL_PRIVATE": "0" if options.public else "1"}
    server = subprocess.Popen(
        [os.path.abspath(options.python), "-m", "biceps", "serve",
         str(Path(options.config).resolve()),
         "--port", str(port), "--max-visitors", str(options.visitors)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment,
        cwd=tempfile.gettempdir())  # not this folder: python -m biceps imports the venv's
    load_before = Path("/proc/loadavg").read_text().split()[:3]
    try:
        for _ in range(600):
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                await asyncio.sleep(0.1)
        await asyncio.sleep(options.settle)  # as in a class: the server up before the visitors
        everyone_up = asyncio.Barrier(options.visitors + 1)
        measured = asyncio.Event()
        visits = [asyncio.create_task(visit(f"ws://127.0.0.1:{port}/ws", options.keys,
                                            everyone_up, measured))
                  for _ in range(options.visitors)]
        await everyone_up.wait()
        await asyncio.sleep(2.0)  # settled: the first frames drawn, the panels filled
        sizes = visitor_memory(server.pid)
        server_rss = memory(server.pid)[0]
        zygote = zygote_memory(server.pid)
        measured.set()
        results = await asyncio.gather(*visits)
    finally:
        server.send_signal(signal.SIGINT)
        server.wait(timeout=60)
    load_after = Path("/proc/loadavg").read_text().split()[:3]
    path = "public" if options.public else "private"
    print(f"{options.python} -m biceps serve {Path(options.config).name}: "
          f"{options.visitors} visitors at once, "
          f"{options.keys} keys each, the {path} path; load average {' '.join(load_before)} "
          f"before, {' '.join(load_after)} after, on {os.cpu_count()} cores")
    print(f"{'visitor':>7}  {'first picture s':>15}  {'key median s':>12}  {'key max s':>9}")
    for index, (first, latencies) in enumerate(results, 1):
        print(f"{index:>7}  {first:>15.2f}  {statistics.median(latencies):>12.3f}  "
              f"{max(latencies):>9.3f}")
    firsts = [first for first, _ in results]
    every_key = [latency for _, latencies in results for latency in latencies]
    print(f"first picture: median {statistics.median(firsts):.2f} s, slowest {max(firsts):.2f} s")
    print(f"key to picture: median {statistics.median(every_key):.3f} s over {len(every_key)} "
          f"keys, 90th percentile {statistics.quantiles(every_key, n=10)[-1]:.3f} s")
    rss = [size[0] for size in sizes]
    pss = [size[1] for size in sizes]
    print(f"memory per visitor ({len(sizes)} processes): RSS median {statistics.median(rss):.0f} "
          f"MB, PSS median {statistics.median(pss):.0f} MB; the server {server_rss:.0f} MB RSS"
          + ("" if zygote is None else
             f"; the zygote {zygote[0]:.0f} MB RSS, {zygote[1]:.0f} MB PSS"))


if __name__ == "__main__":
    asyncio.run(main())
