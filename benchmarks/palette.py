"""256 colours against 24 bits: how far ``snapshot --ansi --colors 256`` is from the 24-bit
picture, and how fast frames are mapped onto the palette, against another checkout's.

    .venv/bin/python benchmarks/palette.py [--against /work/main/.venv/bin/python]

For each model, size and view: the mean OKLab difference over the arm after a 2 x 2 box
blur of both pictures, and the share of the red belly's pixels more than 25 degrees of
OKLab hue away from the 24-bit picture's (tests/colours.py; the issue's acceptance: at most
0.025 and 2 %). The pictures are made by each interpreter's ``biceps.terminal.palette`` (its
``Palette256().mapped``, what the app and ``snapshot --ansi`` use) and measured here. Then
the time to map one frame of the app at 200x60 cells (200x120 pixels), the first (with
nothing chosen yet) and the median of the next 50 as a model turns, in each interpreter in
turn.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from colours import blurred_difference, off_hue_share  # noqa: E402

CONFIGS = ("biceps.toml", "elbow.toml")  # each interpreter's own bundled models
SIZES = ((80, 44), (120, 68), (200, 112))
VIEWS = ({}, {"scale": 2.0}, {"yaw": 60, "pitch": 20}, {"yaw": -90})

# Run by each interpreter: the pictures, and the timings.
MAP = """
import json, sys, time
import numpy as np
from biceps.configs import FOLDER
from biceps.engine.config import load_config, rgb
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal.palette import Palette256

configs, sizes, views, out = *map(json.loads, sys.argv[1:4]), sys.argv[4]
pictures = {}
for name in configs:
    config = load_config(FOLDER / name)
    background = rgb(config.render.background)
    for width, height in sizes:
        for number, view in enumerate(views):
            scene = Scene.of(config).with_view(**view)
            frame = SceneRenderer().render(scene, width, height).copy()
            pictures[f"{name} {width} {number} 24"] = frame
            pictures[f"{name} {width} {number} 256"] = Palette256().mapped(frame, background)
np.savez(out, **pictures)
config = load_config(FOLDER / configs[0])
background, renderer, palette = rgb(config.render.background), SceneRenderer(), Palette256()
frames = [renderer.render(Scene.of(config).with_view(yaw=2.0 * step), 200, 120).copy()
          for step in range(51)]
palette.mapped(frames[0][:2, :2], background)  # compiled, or loaded from the cache
start = time.perf_counter()
palette.mapped(frames[0], background)
first = time.perf_counter() - start
times = []
for frame in frames[1:]:
    start = time.perf_counter()
    palette.mapped(frame, background)
    times.append(time.perf_counter() - start)
print(json.dumps({"first": first, "median": sorted(times)[len(times) // 2]}))
"""


def measured(python: str, folder: Path, name: str) -> tuple[dict, dict]:
    out = folder / f"{name}.npz"
    # -P, from a folder of its own: the biceps that interpreter has installed, not this
    # checkout's through the current folder.
    process = subprocess.run(
        [python, "-P", "-c", MAP, json.dumps(CONFIGS), json.dumps(SIZES), json.dumps(VIEWS),
         str(out)],
        capture_output=True, text=True, check=True, timeout=1800, cwd=folder)
    return dict(np.load(out)), json.loads(process.stdout.splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--against", help="another interpreter with biceps installed")
    arguments = parser.parse_args()
    pythons = {"this": sys.executable}
    if arguments.against:
        pythons["other"] = arguments.against
    with tempfile.TemporaryDirectory() as folder:
        results = {label: measured(python, Path(folder), label)
                   for label, python in pythons.items()}
    from biceps.configs import FOLDER
    from biceps.engine.config import load_config, rgb

    print(f"{'model':<12} {'size':>7} {'view':<22}"
          + "".join(f" {label + ': blurred':>16} {'off hue':>8}" for label in pythons))
    for name in CONFIGS:
        config = load_config(FOLDER / name)
        background, muscle = rgb(config.render.background), rgb(config.render.muscle_colour)
        for width, height in SIZES:
            for number, view in enumerate(VIEWS):
                row = f"{Path(name).stem:<12} {f'{width}x{height}':>7} {json.dumps(view):<22}"
                for label in pythons:
                    pictures = results[label][0]
                    true = pictures[f"{name} {width} {number} 24"]
                    shown = pictures[f"{name} {width} {number} 256"]
                    row += (f" {blurred_difference(true, shown, background):16.4f}"
                            f" {100 * off_hue_share(true, shown, background, muscle):7.1f}%")
                print(row)
    print()
    for label in pythons:
        timing = results[label][1]
        print(f"{label}: a 200x120 frame mapped in {1000 * timing['median']:.2f} ms (median "
              f"of 50 as the model turns; the first {1000 * timing['first']:.1f} ms)")


if __name__ == "__main__":
    main()
