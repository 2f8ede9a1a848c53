"""What undo history costs as it grows: 1,000 and 8,000 node edits of the bundled model,
each recorded as the app records it, and the ratio of the two (linear is 8; the goal is at
most 10); optionally against another installation in the same run.

    .venv/bin/python benchmarks/history.py [--runs N] [--against PYTHON]

``--against`` names the Python of another installation of biceps (a checkout of main with
its own venv, say), measured in turns with this one so that both see the same load. Each
figure is the median over the runs, in seconds of this process's CPU time.
"""

from __future__ import annotations

import statistics
import time

import interleaved

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
    count, runs = interleaved.runs(__file__, measure, __doc__.splitlines()[0], 3)
    pythons = list(runs)
    print(f"median of {count} runs, CPU seconds" + "".join(f"{t:>12}" for t in pythons))
    medians = {tree: {edits: statistics.median(run[str(edits)] for run in runs[tree])
                      for edits in EDITS} for tree in pythons}
    for edits in EDITS:
        print(f"{edits:>6,} edits{'':<23}" + "".join(f"{medians[t][edits]:>12.3f}" for t in pythons))
    low, high = EDITS
    print(f"{high:,} against {low:,} (goal: at most 10){'':<7}"
          + "".join(f"{medians[t][high] / medians[t][low]:>12.1f}" for t in pythons))


if __name__ == "__main__":
    main()
