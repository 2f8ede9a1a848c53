"""How long the app takes to show itself and its first picture, with a cold and a warm cache.

    .venv/bin/python benchmarks/first_run.py [--runs N]

The app runs in a pseudo-terminal of 100x30 cells. "UI" is the first screen with the side
panel (the model's file name in its title), "picture" the first half-block pixel. Cold:
every run starts with a fresh, empty NUMBA_CACHE_DIR, as the first run after installing
does. Runs of the two kinds alternate, with the interpreter importing numpy as the
baseline measured in the same run.
Goal (issue 15): the picture within 3.5 s cold.
"""

from __future__ import annotations

import argparse
import fcntl
import os
import select
import statistics
import struct
import subprocess
import sys
import tempfile
import termios
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "configs" / "biceps.toml"
UPPER_HALF = "▀".encode()


def first_run(cache: str) -> tuple[float, float]:
    """Seconds from start to the UI and to the first picture."""
    master, slave = os.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    environment = {**os.environ, "TERM": "xterm-256color", "COLORTERM": "truecolor",
                   "NUMBA_CACHE_DIR": cache}
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, "-m", "biceps", str(CONFIG)], stdin=slave,
                               stdout=slave, stderr=slave, env=environment,
                               start_new_session=True)
    os.close(slave)
    output, ui = bytearray(), None
    try:
        while time.perf_counter() - start < 180:
            if select.select([master], [], [], 0.01)[0]:
                output += os.read(master, 1 << 16)
                if ui is None and CONFIG.name.encode() in output:
                    ui = time.perf_counter() - start
                if UPPER_HALF in output:
                    return ui or time.perf_counter() - start, time.perf_counter() - start
        raise RuntimeError("no picture within 180 s")
    finally:
        process.kill()
        process.wait()
        os.close(master)


def seconds(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    rows: dict[str, list[float]] = {}
    with tempfile.TemporaryDirectory() as scratch:
        warm = str(Path(scratch) / "warm")
        first_run(warm)  # fill the warm cache
        for _ in range(args.runs):
            rows.setdefault("python -c 'import numpy'", []).append(
                seconds([sys.executable, "-c", "import numpy"]))
            with tempfile.TemporaryDirectory(dir=scratch) as empty:
                ui, picture = first_run(empty)
            rows.setdefault("cold cache: UI", []).append(ui)
            rows.setdefault("cold cache: picture", []).append(picture)
            ui, picture = first_run(warm)
            rows.setdefault("warm cache: UI", []).append(ui)
            rows.setdefault("warm cache: picture", []).append(picture)
    numpy = statistics.median(rows["python -c 'import numpy'"])
    print(f"{'the app at 100x30':<28} {'median s':>9} {'min s':>7} {'max s':>7} {'vs numpy':>9}")
    for name, times in rows.items():
        median = statistics.median(times)
        print(f"{name:<28} {median:>9.3f} {min(times):>7.3f} {max(times):>7.3f} "
              f"{median / numpy:>9.1f}")


if __name__ == "__main__":
    main()
