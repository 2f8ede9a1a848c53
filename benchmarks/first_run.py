"""How long the app takes to show itself and its first picture, with a cold and a warm cache.

    .venv/bin/python benchmarks/first_run.py [--runs N] [--python PY] [--baseline PY]

The app runs in a pseudo-terminal of 100x30 cells, from a scratch folder, so that
``PY -m biceps`` is the biceps that interpreter has installed: this repository's, through
the editable install, by default; a wheel's, in a venv of its own; or another worktree's
(a benchmark run from one tree with another tree's venv measures that venv's code).
"UI" is the first screen with the side panel (the model's file name in its title),
"message" the first run's message in the viewport (cold only: ``tui/ahead.py``), "picture"
the first half-block pixel. "CPU" is what the app's processes (the children it
forked and waited for too) spent by the first picture, which other work on the machine
disturbs less than the time. Cold: every run starts with a fresh, empty NUMBA_CACHE_DIR,
as the first run after installing does. Runs of the two kinds alternate (and with
``--baseline``, the two interpreters), with the interpreter importing numpy as the
baseline measured in the same run. The load is the machine's one-minute load average as
each run starts.
Goal (issue 15): the picture within 3.5 s cold.
"""

from __future__ import annotations

import argparse
import fcntl
import os
import resource
import select
import signal
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


MESSAGE = b"Preparing the renderer"


def first_run(python: str, cache: str, folder: str, linger: float = 0.0
              ) -> tuple[float, float | None, float, float]:
    """Seconds from start to the UI, to the first run's message (None if there was none)
    and to the first picture, and the CPU seconds spent; the app is left running
    ``linger`` seconds more (to fill the cache)."""
    master, slave = os.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    environment = {**os.environ, "TERM": "xterm-256color", "COLORTERM": "truecolor",
                   "NUMBA_CACHE_DIR": cache}
    used = _children_cpu()
    start = time.perf_counter()
    process = subprocess.Popen([python, "-m", "biceps", str(CONFIG)], stdin=slave,
                               stdout=slave, stderr=slave, env=environment, cwd=folder,
                               start_new_session=True)
    os.close(slave)
    output, ui, message = bytearray(), None, None
    try:
        while time.perf_counter() - start < 180:
            if select.select([master], [], [], 0.01)[0]:
                output += os.read(master, 1 << 16)
                if ui is None and CONFIG.name.encode() in output:
                    ui = time.perf_counter() - start
                if message is None and MESSAGE in output:
                    message = time.perf_counter() - start
                if UPPER_HALF in output:
                    picture = time.perf_counter() - start
                    time.sleep(linger)
                    os.killpg(process.pid, signal.SIGKILL)  # its children too, compiling
                    process.wait()
                    return ui or picture, message, picture, _children_cpu() - used
        raise RuntimeError("no picture within 180 s")
    finally:
        if process.returncode is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        os.close(master)


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def seconds(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--python", default=sys.executable,
                        help="the interpreter whose biceps runs (default: this one)")
    parser.add_argument("--baseline", help="another interpreter, measured in turn with it")
    args = parser.parse_args()
    pythons = {"": args.python} | ({"baseline ": args.baseline} if args.baseline else {})
    rows: dict[str, list[tuple[float, float]]] = {}

    def note(name: str, value: float, load: float) -> None:
        rows.setdefault(name, []).append((value, load))

    with tempfile.TemporaryDirectory() as scratch:
        for label, python in pythons.items():  # fill the warm caches, all they will hold
            first_run(python, str(Path(scratch) / f"warm {label}"), scratch, linger=10.0)
        for _ in range(args.runs):
            note("python -c 'import numpy'", seconds([sys.executable, "-c", "import numpy"]),
                 os.getloadavg()[0])
            for label, python in pythons.items():
                for cache in ("cold", "warm"):
                    load = os.getloadavg()[0]
                    if cache == "cold":
                        with tempfile.TemporaryDirectory(dir=scratch) as empty:
                            ui, message, picture, cpu = first_run(python, empty, scratch)
                    else:
                        warm = str(Path(scratch) / f"warm {label}")
                        ui, message, picture, cpu = first_run(python, warm, scratch)
                    note(f"{label}{cache} cache: UI", ui, load)
                    if message is not None:
                        note(f"{label}{cache} cache: message", message, load)
                    note(f"{label}{cache} cache: picture", picture, load)
                    note(f"{label}{cache} cache: CPU", cpu, load)
    numpy = statistics.median(value for value, _ in rows["python -c 'import numpy'"])
    print(f"{'the app at 100x30':<32} {'median s':>9} {'min s':>7} {'max s':>7} "
          f"{'vs numpy':>9} {'load':>9}")
    for name, measured in rows.items():
        times, loads = [value for value, _ in measured], [load for _, load in measured]
        median = statistics.median(times)
        print(f"{name:<32} {median:>9.3f} {min(times):>7.3f} {max(times):>7.3f} "
              f"{median / numpy:>9.1f} {min(loads):>4.1f}-{max(loads):<4.1f}")


if __name__ == "__main__":
    main()
