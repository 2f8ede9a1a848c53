"""What reading a configuration costs: importing ``engine/config.py`` and what it needs but
numpy (pydantic, the model; the tables' schemas are built then), loading the bundled biceps and the elbow's six muscles, refusing a bad
file, and making a view setting as a key does; optionally against another installation in
the same run.

    .venv/bin/python benchmarks/config_load.py [--runs N] [--against PYTHON]

``--against`` names the Python of another installation of biceps (a checkout of main with
its own venv, say), measured in turns with this one so that both see the same load. Each
run is a fresh process; each figure is the median over the runs of that run's fastest of
``REPEATS`` (the import: its one time), in milliseconds of CPU time.
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

import interleaved

REPEATS = 20
BAD_VIEW = "[muscle]\nlength = 33.0\nradius = [0.5, 2.0, 0.5]\ngrowth = [0, 1, 0]\n[view]\nfov = 500\n"
FIGURES = ("import", "biceps.toml", "elbow.toml", "bad [view]", "a view setting")


def _fastest(work) -> float:
    """``work()``'s least CPU time over :data:`REPEATS` calls, ms."""
    times = []
    for _ in range(REPEATS):
        start = time.process_time()
        work()
        times.append(time.process_time() - start)
    return 1e3 * min(times)


def measure() -> dict[str, float]:
    """One run here: {figure: CPU ms}."""
    import numpy  # noqa: F401 (every command has it before it reads a file)

    start = time.process_time()
    from biceps.configs import FOLDER
    from biceps.engine.config import load_config
    from biceps.engine.errors import ConfigError
    from biceps.engine.settings import View
    figures = {"import": 1e3 * (time.process_time() - start)}
    for name in ("biceps.toml", "elbow.toml"):
        figures[name] = _fastest(lambda: load_config(FOLDER / name))
    with tempfile.TemporaryDirectory() as folder:
        bad = Path(folder) / "bad.toml"
        bad.write_text(BAD_VIEW)

        def refuse() -> None:
            try:
                load_config(bad)
            except ConfigError:
                return
            sys.exit("the bad file loaded")

        figures["bad [view]"] = _fastest(refuse)
    figures["a view setting"] = _fastest(lambda: [View(yaw=float(i)) for i in range(100)]) / 100
    return figures


def main() -> None:
    count, runs = interleaved.runs(__file__, measure, __doc__.splitlines()[0], 7)
    pythons = list(runs)
    print(f"median of {count} runs, CPU ms" + "".join(f"{t:>12}" for t in pythons))
    for figure in FIGURES:
        medians = [statistics.median(run[figure] for run in runs[t]) for t in pythons]
        print(f"{figure:<26}" + "".join(f"{m:>12.3f}" for m in medians))


if __name__ == "__main__":
    main()
