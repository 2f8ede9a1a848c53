"""What laying the six muscles of configs/elbow.toml costs: a contraction step's scene mesh
(what a held ``c`` costs before the picture is drawn), and an edit of a muscle's node with
its first mesh (the edit chooses the muscles' leans round the humerus anew), against the
same two for the single biceps of configs/biceps.toml; optionally against another tree.

    .venv/bin/python benchmarks/packing.py [--runs N] [--against PYTHON]

``--against`` names the Python of another installation of biceps (a checkout of main with
its own venv, say): the same measures are taken there too, in turns with this one's, so
that both see the same load on a busy machine. Each figure is the median over the runs of
the median of ``STEPS`` meshes, in ms CPU time of this process (load from other processes
disturbs it less than wall time).
"""

from __future__ import annotations

import statistics
import time

import interleaved

MODELS = ("biceps", "elbow")  # the bundled configs/biceps.toml and configs/elbow.toml
STEPS = 15


def measure() -> dict[str, float]:
    """One run here: {what model: median ms} for a step and for an edit's first mesh."""
    from biceps.configs import FOLDER
    from biceps.engine.appearance import scene_mesh
    from biceps.engine.config import load_config

    figures = {}
    for name in MODELS:
        config = load_config(FOLDER / f"{name}.toml")
        arm = config.arm.at_flexion(60.0)
        scene_mesh(arm, config.render)  # the modules loaded, any cache filled
        steps, edits = [], []
        for i in range(STEPS):
            start = time.process_time()
            scene_mesh(arm.stepped(-0.1 * (i % 5 + 1))[0], config.render)
            steps.append(time.process_time() - start)
            radius = arm.muscle.radii[5] + 0.001 * (i + 1)  # a new shape: leans chosen anew
            start = time.process_time()
            scene_mesh(arm.with_muscle(arm.muscle.with_radius(5, radius)), config.render)
            edits.append(time.process_time() - start)
        figures[f"step {name}"] = 1000 * statistics.median(steps)
        figures[f"edit {name}"] = 1000 * statistics.median(edits)
    return figures


def main() -> None:
    count, runs = interleaved.runs(__file__, measure, __doc__.splitlines()[0], 5)
    pythons = list(runs)
    whats = list(runs["this tree"][0])
    print(f"median of {count} runs, ms CPU per mesh" + "".join(f"{t:>12}" for t in pythons)
          + ("    ratio" if len(pythons) > 1 else ""))
    for what in whats:
        medians = [statistics.median(run[what] for run in runs[tree]) for tree in pythons]
        ratio = f"{medians[0] / medians[1]:>9.2f}" if len(pythons) > 1 else ""
        print(f"{what:<34}" + "".join(f"{m:>12.2f}" for m in medians) + ratio)


if __name__ == "__main__":
    main()
