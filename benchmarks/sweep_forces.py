"""What the forces cost ``biceps sweep``: the whole command over configs/elbow.toml's 131
angles (0 to 130 by 1 degree), plain and with ``--activation 1``, here and, in turns with
it, in another installation (which may have no ``--activation``: its plain sweep is the
baseline).

    .venv/bin/python benchmarks/sweep_forces.py [--runs N] [--against PYTHON]

``--against`` names the Python of another installation of biceps (``/work/main/.venv/bin/
python``, say). Each command runs ``--runs`` times, the variants in turns so that all see
the same load; the figures are medians of wall time, in seconds, and the ratios are to the
baseline's median.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

ARGS = ["sweep", "elbow", "--step", "1", "--json"]


def timed(python: str, extra: list[str]) -> float:
    """Seconds one ``biceps sweep`` takes, start to end, its output thrown away."""
    start = time.perf_counter()
    # From the root, so that neither checkout's folder shadows the installation's package.
    subprocess.run([python, "-m", "biceps", *ARGS, *extra], check=True, cwd="/",
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--against", help="the Python of another installation of biceps")
    args = parser.parse_args()
    variants = {"here, sweep": (sys.executable, []),
                "here, sweep --activation 1": (sys.executable, ["--activation", "1"])}
    if args.against:
        variants = {"other, sweep": (args.against, []), **variants}
    for python, extra in variants.values():  # the numba cache and the disk warmed
        timed(python, extra)
    times = {name: [] for name in variants}
    for _ in range(args.runs):
        for name, (python, extra) in variants.items():
            times[name].append(timed(python, extra))
    baseline = statistics.median(next(iter(times.values())))
    with open("/proc/loadavg") as stream:
        load = stream.read().split()[:3]
    print(f"{args.runs} runs each, in turns; load average {' '.join(load)}")
    for name, seconds in times.items():
        median = statistics.median(seconds)
        print(f"{name:>28}: median {median:.3f} s (min {min(seconds):.3f}), "
              f"{median / baseline:.2f}x the first")


if __name__ == "__main__":
    main()
