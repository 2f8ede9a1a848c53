"""The elbow's six muscles (configs/elbow.toml) against the single biceps (configs/biceps.toml):
a 1920x1080 snapshot, in the process and as a whole command, and what it is made of, with
the ratio of six to one. Goal (issue 9): the snapshot of the six within 1.5x the single
muscle's.

    .venv/bin/python benchmarks/elbow.py [--runs N]

Rows, each a median over the runs:

- snapshot in the process: a fresh renderer each run (so the meshes are built and the
  buffers allocated, as ``snapshot`` does), the scene posed at 60 degrees and drawn at
  1920x1080 with the file's settings; the kernels compiled beforehand.
- frame of a flex sweep: one renderer drawing a new pose each run (what ``animate`` pays a
  frame): the pose's meshes, the framing and the drawing, the buffers reused.
- pose's meshes: the arm contracted by 0.1 cm and its scene mesh built (what a held ``c``
  costs before the picture is drawn); "of which clearance" is the time inside
  ``engine/clearance.py`` (`best_lean` and `path_offsets`, timed as anatomy calls them).
- drawing, view turned: the same pose drawn again turned by a degree, the meshes kept
  (what a held arrow key costs).
- snapshot command: ``biceps snapshot --size 1920x1080 --flexion 60`` with a warm numba
  cache, start to exit.

The two models are measured in turn within each round, so that the ratios stay meaningful
on a noisy machine.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODELS = {"biceps": ROOT / "configs" / "biceps.toml", "elbow": ROOT / "configs" / "elbow.toml"}
SIZE = (1920, 1080)
FLEXION = 60.0


def posed(path: Path):
    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene

    scene = Scene.of(load_config(path))
    return scene.with_arm(scene.arm.at_flexion(FLEXION))


def in_process(path: Path) -> float:
    from biceps.engine.scene import SceneRenderer

    scene = posed(path)
    start = time.perf_counter()
    SceneRenderer().render(scene, *SIZE)
    return time.perf_counter() - start


class Sweep:
    """One renderer drawing the model at a new flexion each call, back and forth."""

    def __init__(self, path: Path) -> None:
        from biceps.engine.scene import SceneRenderer

        self.scene, self.renderer, self.calls = posed(path), SceneRenderer(), 0

    def frame(self) -> float:
        self.calls += 1
        flexion = FLEXION + (self.calls % 20 - 10)  # a new pose every call
        scene = self.scene.with_arm(self.scene.arm.at_flexion(flexion))
        start = time.perf_counter()
        self.renderer.render(scene, *SIZE)
        return time.perf_counter() - start


class Turn:
    """One renderer drawing the same pose, turned a degree further each call."""

    def __init__(self, path: Path) -> None:
        from biceps.engine.scene import SceneRenderer

        self.scene, self.renderer, self.calls = posed(path), SceneRenderer(), 0
        self.renderer.render(self.scene, *SIZE)

    def frame(self) -> float:
        self.calls += 1
        scene = self.scene.with_view(yaw=self.scene.view.yaw + self.calls % 10)
        start = time.perf_counter()
        self.renderer.render(scene, *SIZE)
        return time.perf_counter() - start


def step(path: Path) -> tuple[float, float]:
    """The pose's meshes after a contraction step, and the share inside engine/clearance.py."""
    from biceps.engine import anatomy
    from biceps.engine.config import load_config
    from biceps.engine.scene import scene_mesh

    config = load_config(path)
    arm = config.arm.at_flexion(FLEXION)
    inside = [0.0]
    originals = {name: getattr(anatomy, name) for name in ("best_lean", "path_offsets")}

    def timed(function):
        def call(*args, **kwargs):
            start = time.perf_counter()
            try:
                return function(*args, **kwargs)
            finally:
                inside[0] += time.perf_counter() - start
        return call

    try:
        for name, function in originals.items():
            setattr(anatomy, name, timed(function))
        start = time.perf_counter()
        scene_mesh(arm.stepped(-0.1)[0], config.render)
        return time.perf_counter() - start, inside[0]
    finally:
        for name, function in originals.items():
            setattr(anatomy, name, function)


def command(path: Path, output: Path) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "biceps.cli", "snapshot", str(path), "-o", str(output),
                    "--size", "x".join(map(str, SIZE)), "--flexion", str(FLEXION)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--no-command", action="store_true",
                        help="leave out the whole command (a second a run)")
    args = parser.parse_args()
    sweeps = {name: Sweep(path) for name, path in MODELS.items()}
    turns = {name: Turn(path) for name, path in MODELS.items()}
    for name, path in MODELS.items():  # compile, fill the caches, load the modules
        in_process(path)
        step(path)
        sweeps[name].frame()
        turns[name].frame()
    output = Path("/tmp/biceps-elbow-benchmark.png")
    times: dict[tuple[str, str], list[float]] = {}

    def record(what: str, name: str, seconds: float) -> None:
        times.setdefault((what, name), []).append(seconds)

    for _ in range(args.runs):
        for name, path in MODELS.items():
            record("snapshot in the process", name, in_process(path))
            record("frame of a flex sweep", name, sweeps[name].frame())
            meshes, clearance = step(path)
            record("pose's meshes", name, meshes)
            record("  of which clearance", name, clearance)
            record("drawing, view turned", name, turns[name].frame())
            if not args.no_command:
                record("snapshot command", name, command(path, output))
    print(f"{'median of ' + str(args.runs):<26}{'biceps (1)':>12}{'elbow (6)':>12}{'ratio':>8}")
    for what in dict.fromkeys(kind for kind, _ in times):
        one, six = (statistics.median(times[what, name]) for name in MODELS)
        ratio = f"{six / one:>8.2f}" if one > 0 else f"{'-':>8}"
        print(f"{what:<26}{1000 * one:>9.1f} ms{1000 * six:>9.1f} ms{ratio}")


if __name__ == "__main__":
    main()
