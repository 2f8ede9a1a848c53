"""Whole-process time of ``biceps snapshot`` at 1920x1080, with a cold and a warm numba cache.

    .venv/bin/python benchmarks/snapshot.py [--runs N]

Cold: every run compiles the kernels into a fresh, empty NUMBA_CACHE_DIR. Warm: the cache
is filled once, then reused. The baselines, measured in the same run, are the interpreter
starting and importing numpy, so the ratios stay meaningful on a noisy machine.
Goals (issue 3): 0.6 s or less warm, 2 s or less cold.
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
        snapshot = [python, "-m", "biceps.cli", "snapshot", str(CONFIG), "-o", output,
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
            "python -c 'import numpy'": lambda: seconds([python, "-c", "import numpy"], base),
            "biceps snapshot, warm cache": lambda: seconds(snapshot, warm),
            "biceps snapshot, cold cache": cold_run,
        }
        print(f"{'command':<32} {'median s':>9} {'min s':>7} {'vs numpy':>9}")
        medians = {}
        for name, run in rows.items():
            times = [run() for _ in range(args.runs)]
            medians[name] = statistics.median(times)
            ratio = medians[name] / medians.get("python -c 'import numpy'", medians[name])
            print(f"{name:<32} {medians[name]:>9.3f} {min(times):>7.3f} {ratio:>9.1f}")


if __name__ == "__main__":
    main()
