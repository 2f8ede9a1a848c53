"""Whole-process time of the commands: ``biceps --help``, ``biceps info``, and ``biceps
snapshot`` at 1920x1080 with a cold and a warm numba cache.

    .venv/bin/python benchmarks/snapshot.py [--runs N]

Cold: every run compiles the kernels into a fresh, empty NUMBA_CACHE_DIR. Warm: the cache
is filled once, then reused. The baselines, measured in the same run and interleaved with
the commands (one round runs every row once), are the interpreter starting and importing
numpy, so the ratios stay meaningful on a noisy machine.
Goals: ``--help`` within 2.5x of importing numpy (issue 15); a snapshot 0.6 s or less
warm, 2 s or less cold (issue 3).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "configs" / "biceps.toml"
NUMPY = "python -c 'import numpy'"


def seconds(command: list[str], environment: dict[str, str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, env=environment, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    python = sys.executable
    with tempfile.TemporaryDirectory() as scratch:
        output = str(Path(scratch) / "arm.png")
        biceps = [python, "-m", "biceps"]
        snapshot = [*biceps, "snapshot", str(CONFIG), "-o", output,
                    "--size", "1920x1080"]
        warm_cache = Path(scratch) / "warm"
        base = dict(os.environ)
        warm = {**base, "NUMBA_CACHE_DIR": str(warm_cache)}
        subprocess.run(snapshot, env=warm, check=True, capture_output=True)  # fill the cache

        def cold_run() -> float:
            with tempfile.TemporaryDirectory(dir=scratch) as empty:
                return seconds(snapshot, {**base, "NUMBA_CACHE_DIR": empty})

        rows = {
            "python -c pass": lambda: seconds([python, "-c", "pass"], base),
            NUMPY: lambda: seconds([python, "-c", "import numpy"], base),
            "biceps --help": lambda: seconds([*biceps, "--help"], base),
            "biceps info": lambda: seconds([*biceps, "info", str(CONFIG)], base),
            "biceps snapshot, warm cache": lambda: seconds(snapshot, warm),
            "biceps snapshot, cold cache": cold_run,
        }
        times: dict[str, list[float]] = {name: [] for name in rows}
        for _ in range(args.runs):
            for name, run in rows.items():
                times[name].append(run())
        numpy = statistics.median(times[NUMPY])
        print(f"{'command':<32} {'median s':>9} {'min s':>7} {'vs numpy':>9}")
        for name, measured in times.items():
            median = statistics.median(measured)
            print(f"{name:<32} {median:>9.3f} {min(measured):>7.3f} {median / numpy:>9.2f}")


if __name__ == "__main__":
    main()
