"""What undo history costs as it grows: 1,000 and 8,000 node edits of the bundled model,
each recorded as the app records it, and the ratio of the two (linear is 8; the goal is at
most 10); optionally against another installation in the same run.

    .venv/bin/python benchmarks/history.py [--runs N] [--against PYTHON]

``--against`` names the Python of another installation of biceps (a checkout of main with
its own venv, say), measured in turns with this one so that both see the same load. Each
figure is the median over the runs, in seconds of this process's CPU time.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time

EDITS = (1_000, 8_000)


def measure() -> dict[str, float]:
    """One run here: {edits: CPU seconds} to make and record that many edits."""
    from biceps.configs import DEFAULT
    from biceps.engine.config import load_config
    from biceps.tui.history import History

    arm = load_config(DEFAULT).arm
    figures = {}
    for edits in EDITS:
        history, current = History(), arm
        start = time.process_time()
        for number in range(edits):
            radius = 2.0 + 0.5 * (number % 2)  # each edit a new shape, as a person makes
            edited = current.with_muscle(current.muscle.with_radius(7, radius))
            history.record(current, f"node 8's radius set to {radius}")
            current = edited
        figures[str(edits)] = time.process_time() - start
    return figures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--against", help="the Python of another installation of biceps")
    parser.add_argument("--one-run", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one_run:
        print(json.dumps(measure()))
        return
    pythons = {"this tree": sys.executable}
    if args.against:
        pythons["against"] = args.against
    runs: dict[str, list[dict[str, float]]] = {tree: [] for tree in pythons}
    for _ in range(args.runs):
        for tree, python in pythons.items():
            out = subprocess.run([python, __file__, "--one-run"], check=True,
                                 capture_output=True, text=True).stdout
            runs[tree].append(json.loads(out.splitlines()[-1]))
    print(f"median of {args.runs} runs, CPU seconds" + "".join(f"{t:>12}" for t in pythons))
    medians = {tree: {edits: statistics.median(run[str(edits)] for run in runs[tree])
                      for edits in EDITS} for tree in pythons}
    for edits in EDITS:
        print(f"{edits:>6,} edits{'':<23}" + "".join(f"{medians[t][edits]:>12.3f}" for t in pythons))
    low, high = EDITS
    print(f"{high:,} against {low:,} (goal: at most 10){'':<7}"
          + "".join(f"{medians[t][high] / medians[t][low]:>12.1f}" for t in pythons))


if __name__ == "__main__":
    main()
