"""Whole-process time of ``biceps animate``: a 60-frame 640x360 GIF, beside the time of 60
single ``biceps snapshot`` commands of the same frames, in the same run.

    .venv/bin/python benchmarks/animate.py [--runs N]

Warm numba cache (filled once, then reused). The rows take turns, one round running each
once, so the ratio stays meaningful on a noisy machine. The snapshots are the cycle's own
poses: a bounce of 60 frames renders 31 poses and shows 29 of them twice, so the 60
snapshots are the 60 frames, each rendered and written on its own.
Goal (issue 10): the GIF in 3 s or less, warm, whole process.
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
FRAMES, SIZE = 60, "640x360"


def seconds(commands: list[list[str]], environment: dict[str, str]) -> float:
    start = time.perf_counter()
    for command in commands:
        subprocess.run(command, env=environment, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT))
    from biceps.engine.animate import FlexCycle

    biceps = [sys.executable, "-m", "biceps"]
    with tempfile.TemporaryDirectory() as scratch:
        warm = {**os.environ, "NUMBA_CACHE_DIR": str(Path(scratch) / "cache")}
        gif = [*biceps, "animate", str(CONFIG), "-o", str(Path(scratch) / "cycle.gif"),
               "--size", SIZE, "--frames", str(FRAMES)]
        subprocess.run(gif, env=warm, check=True, capture_output=True)  # fill the cache
        flexions = FlexCycle(0.0, 130.0, FRAMES).flexions()
        snapshots = [[*biceps, "snapshot", str(CONFIG), "-o", str(Path(scratch) / f"{k}.png"),
                      "--size", SIZE, "--flexion", repr(float(flexion))]
                     for k, flexion in enumerate(flexions)]
        rows = {
            f"biceps animate, {FRAMES}-frame GIF": lambda: seconds([gif], warm),
            f"{FRAMES} x biceps snapshot, PNG": lambda: seconds(snapshots, warm),
        }
        times: dict[str, list[float]] = {name: [] for name in rows}
        for _ in range(args.runs):
            for name, run in rows.items():
                times[name].append(run())
    baseline = statistics.median(times[f"{FRAMES} x biceps snapshot, PNG"])
    print(f"{SIZE}, warm numba cache, {args.runs} runs")
    print(f"{'command':<34} {'median s':>9} {'min s':>7} {'vs snapshots':>13}")
    for name, measured in times.items():
        median = statistics.median(measured)
        print(f"{name:<34} {median:>9.3f} {min(measured):>7.3f} {median / baseline:>13.3f}")


if __name__ == "__main__":
    main()
