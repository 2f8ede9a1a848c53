"""The elbow's six muscles (configs/elbow.toml) against the single biceps (configs/biceps.toml):
a 1920x1080 snapshot, in the process and as a whole command, and what it is made of, with
the ratio of six to one. Goal (issue 9): the snapshot of the six within 1.5x the single
muscle's.

    .venv/bin/python benchmarks/elbow.py [--runs N]

Rows, each a median over the runs:

- snapshot in the process: a fresh renderer each time (so the meshes are built and the
  buffers allocated, as ``snapshot`` does), the scene posed at 60 degrees and drawn at
  1920x1080 with the file's settings; the kernels compiled beforehand. Allocating a
  1080p picture's buffers costs more or less depending on whether the allocator hands
  back pages this process has touched already or fresh ones, which swung the ratio of
  medians from 0.97 to 1.69 between runs: so the two models are drawn in pairs, ``PAIRS``
  a run, one then the other, in turn first, and the ratio is the median of the pairs'
  (the times, the medians of all pairs).
- frame of a flex sweep: one renderer drawing a new pose each run (what ``animate`` pays a
  frame): the pose's meshes, the framing and the drawing, the buffers reused.
- pose's meshes: the arm contracted by 0.1 cm and its scene mesh built (what a held ``c``
  costs before the picture is drawn); "of which clearance" is the time inside
  ``engine/clearance.py`` (`path_offsets`, timed as ``engine/packing.py`` calls it; the
  leans are chosen once for an arm's shapes, not per pose).
- drawing, view turned: the same pose drawn again turned by a degree, the meshes kept
  (what a held arrow key costs).
- snapshot command: ``biceps snapshot --size 1920x1080 --flexion 60`` with a warm numba
  cache, start to exit.

The two models are measured in turn within each round, so that the ratios stay meaningful
on a noisy machine. Each row gives wall time and CPU time (every thread of this process,
``time.process_time``): on a machine shared with other work, waiting for a core inflates
the wall time, the CPU time much less, so its ratio is the steadier.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODELS = {"biceps": ROOT / "configs" / "biceps.toml", "elbow": ROOT / "configs" / "elbow.toml"}
SIZE = (1920, 1080)
FLEXION = 60.0
PAIRS = 5  # snapshots in the process of each model a run, in pairs


def posed(path: Path):
    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene

    scene = Scene.of(load_config(path))
    return scene.with_arm(scene.arm.at_flexion(FLEXION))


def timed(call) -> tuple[float, float]:
    """The wall and CPU seconds ``call()`` takes."""
    wall, cpu = time.perf_counter(), time.process_time()
    call()
    return time.perf_counter() - wall, time.process_time() - cpu


def in_process(path: Path) -> tuple[float, float]:
    from biceps.engine.scene_renderer import SceneRenderer

    scene = posed(path)
    return timed(lambda: SceneRenderer().render(scene, *SIZE))


def snapshot_pairs(pairs: int) -> list[dict[str, tuple[float, float]]]:
    """``pairs`` snapshots in the process of each model, by model, each pair drawn one
    after the other, the first in turn."""
    names = list(MODELS)
    return [{name: in_process(MODELS[name]) for name in names[::1 if pair % 2 else -1]}
            for pair in range(pairs)]


class Sweep:
    """One renderer drawing the model at a new flexion each call (50 to 69 degrees, round)."""

    def __init__(self, path: Path) -> None:
        from biceps.engine.scene_renderer import SceneRenderer

        self.scene, self.renderer, self.calls = posed(path), SceneRenderer(), 0

    def frame(self) -> tuple[float, float]:
        self.calls += 1
        flexion = FLEXION + (self.calls % 20 - 10)  # a new pose every call
        scene = self.scene.with_arm(self.scene.arm.at_flexion(flexion))
        return timed(lambda: self.renderer.render(scene, *SIZE))


class Turn:
    """One renderer drawing the same pose, turned a degree further each call."""

    def __init__(self, path: Path) -> None:
        from biceps.engine.scene_renderer import SceneRenderer

        self.scene, self.renderer, self.calls = posed(path), SceneRenderer(), 0
        self.renderer.render(self.scene, *SIZE)

    def frame(self) -> tuple[float, float]:
        self.calls += 1
        scene = self.scene.with_view(yaw=self.scene.view.yaw + self.calls % 10)
        return timed(lambda: self.renderer.render(scene, *SIZE))


def step(path: Path) -> tuple[tuple[float, float], tuple[float, float]]:
    """The pose's meshes after a contraction step, and the share inside engine/clearance.py,
    each (wall, CPU) seconds."""
    from biceps.engine import packing
    from biceps.engine.appearance import scene_mesh
    from biceps.engine.config import load_config

    config = load_config(path)
    arm = config.arm.at_flexion(FLEXION)
    inside = [0.0, 0.0]
    path_offsets = packing.path_offsets

    def counted(*args, **kwargs):
        wall, cpu = time.perf_counter(), time.process_time()
        try:
            return path_offsets(*args, **kwargs)
        finally:
            inside[0] += time.perf_counter() - wall
            inside[1] += time.process_time() - cpu

    packing.path_offsets = counted
    try:
        whole = timed(lambda: scene_mesh(arm.stepped(-0.1)[0], config.render))
        return whole, (inside[0], inside[1])
    finally:
        packing.path_offsets = path_offsets


def command(path: Path, output: Path) -> tuple[float, float]:
    """The command's wall time, and the CPU time of the process it ran in."""
    before = os.times()
    wall = time.perf_counter()
    subprocess.run([sys.executable, "-m", "biceps.cli", "snapshot", str(path), "-o", str(output),
                    "--size", "x".join(map(str, SIZE)), "--flexion", str(FLEXION)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = os.times()
    cpu = (after.children_user - before.children_user
           + after.children_system - before.children_system)
    return time.perf_counter() - wall, cpu


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
    times: dict[tuple[str, str], list[tuple[float, float]]] = {}
    pair_ratios: list[tuple[float, float]] = []  # elbow / biceps of each pair, wall and CPU

    def record(what: str, name: str, seconds: tuple[float, float]) -> None:
        times.setdefault((what, name), []).append(seconds)

    for _ in range(args.runs):
        for pair in snapshot_pairs(PAIRS):
            for name, seconds in pair.items():
                record("snapshot in the process", name, seconds)
            pair_ratios.append(tuple(six / one for one, six in zip(*(pair[name]
                                                                     for name in MODELS))))
        for name, path in MODELS.items():
            record("frame of a flex sweep", name, sweeps[name].frame())
            meshes, clearance = step(path)
            record("pose's meshes", name, meshes)
            record("  of which clearance", name, clearance)
            record("drawing, view turned", name, turns[name].frame())
            if not args.no_command:
                record("snapshot command", name, command(path, output))
    load = " ".join(f"{value:.2f}" for value in os.getloadavg())
    print(f"load average {load}; medians of {args.runs} ({args.runs * PAIRS} pairs of "
          f"snapshots in the process), ms")
    print(f"{'':<26}{'wall':>24}{'':>8}{'CPU, every thread':>24}")
    print(f"{'':<26}" + f"{'biceps (1)':>12}{'elbow (6)':>12}{'ratio':>8}" * 2)
    for what in dict.fromkeys(kind for kind, _ in times):
        row = f"{what:<26}"
        for clock in (0, 1):
            one, six = (statistics.median(seconds[clock] for seconds in times[what, name])
                        for name in MODELS)
            if what == "snapshot in the process":  # see the module's docstring
                ratio = f"{statistics.median(pair[clock] for pair in pair_ratios):>8.2f}"
            else:
                ratio = f"{six / one:>8.2f}" if one > 0 else f"{'-':>8}"
            row += f"{1000 * one:>12.1f}{1000 * six:>12.1f}{ratio}"
        print(row)


if __name__ == "__main__":
    main()
