"""What the app writes to the terminal, key by key, against another checkout's app: the
same bytes, or where they part.

    .venv/bin/python benchmarks/app_bytes.py --baseline ../main/.venv/bin/python
                                             [--config configs/elbow.toml] [--colors 256]
                                             [--keys right,up,c,l,g,tab,h,x] [--size 200x60]

Each app runs in a pseudo-terminal played by ``benchmarks/tui_pty.py``; after its first
picture, each key is pressed alone and everything the app writes in the next ``--settle``
seconds is kept, so that each key gives one frame (or a few, the same in both) whatever
the machine's load. Prints each key's bytes and their hash for both apps, and the keys
whose output differs (a key whose output depends on timing, such as the moment a
notification goes, can differ between two runs of one app: run again to tell).
"""

from __future__ import annotations

import argparse
import hashlib
import sys
import time
from pathlib import Path

from tui_pty import CONFIG, Terminal, started

KEYS = {"right": b"\x1b[C", "left": b"\x1b[D", "up": b"\x1b[A", "down": b"\x1b[B",
        "tab": b"\t", "enter": b"\r"}


def outputs(python: Path, config: Path, colors: str, keys: list[str], size: tuple[int, int],
            settle: float) -> list[bytes]:
    """What the app of ``python`` writes after each of ``keys``."""
    written = bytearray()

    class Recording(Terminal):
        def _take(self, data: bytes, now: float) -> None:
            written.extend(data)
            super()._take(data, now)

    argv = [str(python), "-m", "biceps.cli", "app", str(config), "--colors", colors]
    terminal = started(argv, *size, start=Recording.start)
    try:
        terminal.pump(time.monotonic() + settle)
        chunks = []
        for key in keys:
            written.clear()
            terminal.press(KEYS.get(key, key.encode()))
            terminal.pump(time.monotonic() + settle)
            chunks.append(bytes(written))
    finally:
        terminal.close()
    return chunks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", type=Path, required=True, metavar="PYTHON",
                        help="the Python of another checkout's environment (main's, say)")
    parser.add_argument("--config", type=Path, default=CONFIG)
    parser.add_argument("--colors", default="truecolor", choices=["truecolor", "256"])
    parser.add_argument("--keys", default="right,right,up,c,c,l,g,right,tab,right,h,right,h,x")
    parser.add_argument("--size", default="200x60")
    parser.add_argument("--settle", type=float, default=0.8, help="seconds after each key")
    arguments = parser.parse_args()
    keys = arguments.keys.split(",")
    size = tuple(map(int, arguments.size.split("x")))
    runs = {name: outputs(python, arguments.config.resolve(), arguments.colors, keys, size,
                          arguments.settle)
            for name, python in (("baseline", arguments.baseline),
                                 ("this", Path(sys.executable)))}
    print(f"model: {arguments.config}, {size[0]}x{size[1]}, {arguments.colors}")
    print(f"{'key':<8} {'baseline bytes':>15} {'hash':>13} {'this bytes':>11} {'hash':>13}")
    differ = []
    for key, ours, theirs in zip(keys, runs["this"], runs["baseline"]):
        print(f"{key:<8} {len(theirs):15d} {_hash(theirs):>13} {len(ours):11d} "
              f"{_hash(ours):>13}")
        if ours != theirs:
            differ.append(key)
    print(f"keys whose output differs: {', '.join(differ) or 'none'}")


def _hash(data: bytes) -> str:
    return hashlib.sha1(data).hexdigest()[:12]


if __name__ == "__main__":
    main()
