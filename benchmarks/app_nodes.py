"""How fast the app answers a contraction as the muscle grows to thousands of nodes, and
what a picture of that many nodes costs.

    .venv/bin/python benchmarks/app_nodes.py [--nodes 5000,20000] [--presses 20]
                                            [--frames 15,5000,20000,100000]

Each muscle (a smooth spindle of N nodes, the arm26 skeleton) runs in the real app in a
pseudo-terminal of 120x36, which this script plays the terminal of (as
``benchmarks/tui_pty.py`` does: it answers the app's cursor-position questions). Once the
first picture is out, it presses ``c`` and ``x`` in turn, one at a time, and times each from
writing the key to reading the new length in the side panel: the app has answered when the
person sees the number change (the picture follows at its own pace, from its own thread).
It waits a moment between presses, so that each is timed alone.

Prints the median and the slowest answer for each node count, and the ratio of the median
to the bundled 15-node model's, measured in the same run.

Then, for each of ``--frames`` (past the most nodes a muscle may have, engine/bounds.py,
which this lifts for the measurement), each in a process of its own: the median time of a
200x140 picture after a length change (a new mesh, as the render thread makes at every
``c``) over 5 changes, and the process's peak memory.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from tui_pty import ROOT, Terminal  # noqa: E402  (the pseudo-terminal this script plays)

from biceps.tui.changes import FINE_STEP  # noqa: E402

STARTUP_TIMEOUT = 180.0
ANSWER_TIMEOUT = 30.0
SETTLE = 0.3  # seconds between presses, for the picture to catch up


def spindle(nodes: int, folder: Path) -> Path:
    """A configuration of ``nodes`` nodes: thin tendons, a belly that grows with its radius."""
    x = np.linspace(0.0, 1.0, nodes)
    radius = 0.35 + 1.75 * np.sin(np.pi * x) ** 2
    growth = np.where((x > 0.1) & (x < 0.9), radius, 0.0)
    path = folder / f"spindle-{nodes}.toml"
    path.write_text("[muscle]\nlength = 33.0\n"
                    f"radius = [{', '.join(f'{v:.4f}' for v in radius)}]\n"
                    f"growth = [{', '.join(f'{v:.4f}' for v in growth)}]\n")
    return path


def answers(config: Path, presses: int) -> list[float]:
    """Seconds from each key to the new length on screen."""
    terminal = Terminal.start([sys.executable, "-m", "biceps", str(config)], 120, 36)
    try:
        _wait_for(terminal, b"33.00 cm", STARTUP_TIMEOUT)
        terminal.pump(time.monotonic() + 2.0)  # the first picture, and anything queued
        length, times = 33.0, []
        for press in range(presses):
            key, change = (b"c", -FINE_STEP) if press % 2 == 0 else (b"x", FINE_STEP)
            length = round(length + change, 2)
            start = time.monotonic()
            terminal.press(key)
            _wait_for(terminal, f"{length:.2f} cm".encode(), ANSWER_TIMEOUT)
            times.append(time.monotonic() - start)
            terminal.pump(time.monotonic() + SETTLE)
        return times
    finally:
        terminal.close()


def _wait_for(terminal: Terminal, text: bytes, timeout: float) -> None:
    """Pump the terminal until ``text`` has been written after this call began."""
    seen = bytearray()
    deadline = time.monotonic() + timeout
    take = terminal._take

    def keep(data: bytes, now: float) -> None:
        seen.extend(data)
        take(data, now)

    terminal._take = keep
    try:
        while text not in seen:
            if time.monotonic() > deadline or terminal.process.poll() is not None:
                raise SystemExit(f"no {text!r} within {timeout} s")
            terminal.pump(time.monotonic() + 0.002)
    finally:
        terminal._take = take


def frame_cost(nodes: int) -> tuple[float, float]:
    """Seconds a picture takes after a length change, and peak megabytes, in this process."""
    import biceps.engine.muscle

    biceps.engine.muscle.NODES = max(nodes, biceps.engine.muscle.NODES)
    from biceps.engine.arm import Arm
    from biceps.engine.muscle import Muscle
    from biceps.engine.scene import Scene
    from biceps.engine.scene_renderer import SceneRenderer
    from biceps.engine.settings import RenderSettings, View
    from biceps.engine.skeleton import Skeleton
    from biceps.engine.transforms import Light

    x = np.linspace(0.0, 1.0, nodes)
    radius = 0.35 + 1.75 * np.sin(np.pi * x) ** 2
    growth = np.where((x > 0.1) & (x < 0.9), radius, 0.0)
    scene = Scene(Arm(Muscle.of(radius, growth, 33.0), Skeleton()), View(), Light(),
                  RenderSettings())
    renderer = SceneRenderer()
    renderer.render(scene, 200, 140)  # compiled and warm
    times = []
    for change in range(5):
        changed = scene.with_arm(scene.arm.at_length(32.0 - 0.1 * change))
        start = time.perf_counter()
        renderer.render(changed, 200, 140)
        times.append(time.perf_counter() - start)
    return statistics.median(times), resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nodes", default="5000,20000")
    parser.add_argument("--presses", type=int, default=20)
    parser.add_argument("--frames", default="15,5000,20000,100000")
    parser.add_argument("--frame-cost", type=int, help=argparse.SUPPRESS)  # the child's part
    options = parser.parse_args()
    if options.frame_cost:
        print(*frame_cost(options.frame_cost))
        return
    counts = [int(n) for n in options.nodes.split(",") if n]
    with tempfile.TemporaryDirectory() as folder:
        baseline = statistics.median(answers(ROOT / "configs" / "biceps.toml", options.presses))
        print(f"{'nodes':>7} {'median ms':>10} {'slowest ms':>11} {'vs 15 nodes':>12}")
        print(f"{15:>7} {baseline * 1e3:>10.1f} {'':>11} {1.0:>12.2f}")
        for nodes in counts:
            times = answers(spindle(nodes, Path(folder)), options.presses)
            median = statistics.median(times)
            print(f"{nodes:>7} {median * 1e3:>10.1f} {max(times) * 1e3:>11.1f} "
                  f"{median / baseline:>12.2f}")
    print(f"\n{'nodes':>7} {'frame ms':>9} {'peak MB':>8}")
    for nodes in (int(n) for n in options.frames.split(",") if n):
        child = subprocess.run([sys.executable, __file__, "--frame-cost", str(nodes)],
                               capture_output=True, text=True, check=True)
        seconds, megabytes = map(float, child.stdout.split())
        print(f"{nodes:>7} {seconds * 1e3:>9.0f} {megabytes:>8.0f}")


if __name__ == "__main__":
    main()
