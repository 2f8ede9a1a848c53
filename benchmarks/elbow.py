"""The elbow's six muscles (configs/elbow.toml) against the single biceps (configs/biceps.toml):
a 1920x1080 snapshot, in the process and as a whole command, and one contraction step's
new mesh, with the ratio of six to one. Goal (issue 9): the snapshot of the six within 1.5x
the single muscle's.

    .venv/bin/python benchmarks/elbow.py [--runs N]

In the process: a fresh renderer each run (so the meshes are built, as ``snapshot`` builds
them), the scene posed at 60 degrees and drawn at 1920x1080 with the file's settings; the
kernels compiled beforehand. The command: ``biceps snapshot --size 1920x1080 --flexion 60``
with a warm numba cache, start to exit. A step: the arm contracted by 0.1 cm and its scene
mesh built, what a held ``c`` costs before the picture is drawn. The two models are measured
in turn within each round, so that the ratios stay meaningful on a noisy machine; medians.
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


def in_process(path: Path) -> float:
    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene, SceneRenderer

    scene = Scene.of(load_config(path))
    scene = scene.with_arm(scene.arm.at_flexion(60.0))
    start = time.perf_counter()
    SceneRenderer().render(scene, *SIZE)
    return time.perf_counter() - start


def command(path: Path, output: Path) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "biceps.cli", "snapshot", str(path), "-o", str(output),
                    "--size", "x".join(map(str, SIZE)), "--flexion", "60"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def step(path: Path) -> float:
    from biceps.engine.config import load_config
    from biceps.engine.scene import scene_mesh

    config = load_config(path)
    arm = config.arm.at_flexion(60.0)
    start = time.perf_counter()
    scene_mesh(arm.stepped(-0.1)[0], config.render)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    for path in MODELS.values():  # compile, fill the caches, load the modules
        in_process(path)
        step(path)
    output = Path("/tmp/biceps-elbow-benchmark.png")
    times: dict[tuple[str, str], list[float]] = {}
    for _ in range(args.runs):
        for name, path in MODELS.items():
            times.setdefault(("snapshot in the process", name), []).append(in_process(path))
            times.setdefault(("snapshot command", name), []).append(command(path, output))
            times.setdefault(("contraction step's mesh", name), []).append(step(path))
    print(f"{'median of ' + str(args.runs):<26}{'biceps (1)':>12}{'elbow (6)':>12}{'ratio':>8}")
    for what in dict.fromkeys(kind for kind, _ in times):
        one, six = (statistics.median(times[what, name]) for name in MODELS)
        print(f"{what:<26}{1000 * one:>9.1f} ms{1000 * six:>9.1f} ms{six / one:>8.2f}")


if __name__ == "__main__":
    main()
