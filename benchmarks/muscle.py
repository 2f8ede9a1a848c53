"""How long one length change takes, against the cost of merely copying the radii.

Run: .venv/bin/python benchmarks/muscle.py
Each change starts from the last one, as the app steps the muscle. Goal (issue 2): a
length change of a 10,000-node muscle in under 1 ms.
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from biceps.engine.muscle import Muscle

RUNS = 7
CHANGES_PER_RUN = 2000


def median_microseconds(action, count: int = CHANGES_PER_RUN) -> float:
    """Median over RUNS runs of the mean time of ``action(i)`` over ``count`` calls."""
    runs = []
    for _ in range(RUNS):
        start = time.perf_counter()
        for i in range(count):
            action(i)
        runs.append((time.perf_counter() - start) / count * 1e6)
    return statistics.median(runs)


def main() -> None:
    rng = np.random.default_rng(1)
    print(f"{'nodes':>7} {'mode':>7} {'change (us)':>12} {'copy (us)':>10} {'ratio':>6}")
    for nodes in (15, 1_000, 10_000, 100_000):
        for mode in ("closed", "frusta"):
            radii = rng.uniform(0.3, 2.5, nodes)
            growth = rng.uniform(0.0, 2.0, nodes)
            lengths = np.linspace(28.0, 35.0, 997)
            # Each change from the last one, as the app steps: muscle[0] is the latest.
            muscle = [Muscle.of(radii, growth, 33.0, mode)]

            def change_length(i: int) -> None:
                muscle[0] = muscle[0].at_length(lengths[i % 997])

            change = median_microseconds(change_length)
            copy = median_microseconds(lambda i: radii + 0.5 * growth)
            print(f"{nodes:>7} {mode:>7} {change:>12.1f} {copy:>10.1f} {change / copy:>6.1f}")


if __name__ == "__main__":
    main()
