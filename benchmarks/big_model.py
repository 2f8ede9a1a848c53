"""The app with a big muscle: how long each key takes to be answered on the UI thread, and
whether a held key leaves a queue behind it.

    .venv/bin/python benchmarks/big_model.py [--nodes 16384] [--runs 3] [--size 120x36]

The app runs in this process, headless (Textual's own test mode: the UI thread does all it
does in a terminal but write the bytes), on the bundled profile resampled to ``--nodes``
nodes, and on the bundled 15-node model as the baseline, in the same run.

- Each key of KEYS, pressed once the app is calm: the time from the key to the first screen
  update after it (what a terminal would be sent), and the longest the UI thread's event
  loop went without running meanwhile (a 2 ms heartbeat). The heavy work, the picture, is
  on the render thread: the picture's own latency is printed apart, for the keys that
  change it.
- A held c: 30 presses at 30 a second, a keyboard's repeat rate. Then the time from the
  last press to the numbers showing the last length (the queue left behind), how many
  times the node table was updated for the 30, the longest stall of the event loop during
  the hold, and the time until the picture shows the last length too.

Medians over ``--runs`` fresh apps; "x15" is a figure's ratio to the 15-node model's.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from textual import events

from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.tui import app as app_module
from biceps.tui.app import BicepsApp
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.stats import Stats
from biceps.tui.widgets.viewport import Viewport

# (key, what it does): each changes the screen, so that its answer can be seen.
KEYS = [
    ("c", "contract 0.1 cm"), ("C", "contract 1 cm"), ("x", "stretch 0.1 cm"),
    ("X", "stretch 1 cm"), ("right", "turn"), ("up", "tip"), ("plus", "scale up"),
    ("a", "move"), ("j", "move the light"), ("g", "Phong"), ("g", "Gouraud"),
    ("m", "anti-aliasing"), ("r", "reset the view"), ("tab", "focus the table"),
    ("down", "next node"), ("end", "last node"), ("home", "first node"),
    ("n", "insert a node"), ("delete", "delete it"), ("ctrl+z", "undo"), ("ctrl+y", "redo"),
    ("h", "hide the panel"), ("h", "show it"), ("p", "plots"), ("c", "contract, with plots"),
    ("p", "no plots"),
    ("f1", "help"), ("escape", "close it"), ("e", "export dialog"), ("escape", "close it"),
]
HELD = 30  # presses of the held key
REPEAT = 30.0  # presses a second
CALM = 0.4  # seconds of quiet before a key is pressed
TIMEOUT = 20.0


class Timed(BicepsApp):
    """The app, noting when it sends the screen an update."""

    CSS_PATH = str(Path(app_module.__file__).with_name(BicepsApp.CSS_PATH))

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.displayed = 0.0  # when the last update was sent

    def _display(self, screen, renderable) -> None:
        super()._display(screen, renderable)
        if renderable is not None:
            self.displayed = time.perf_counter()


@dataclass
class Heartbeat:
    """The longest the event loop went without running a 2 ms sleep, since :meth:`reset`."""

    longest: float = 0.0
    _running: bool = True
    _task: asyncio.Task | None = field(default=None, repr=False)

    def start(self) -> None:
        self._task = asyncio.get_running_loop().create_task(self._beat())

    async def _beat(self) -> None:
        while self._running:
            before = time.perf_counter()
            await asyncio.sleep(0.002)
            self.longest = max(self.longest, time.perf_counter() - before - 0.002)

    def reset(self) -> None:
        self.longest = 0.0

    async def stop(self) -> None:
        self._running = False
        await self._task


async def _until(condition, timeout: float = TIMEOUT, what: str = "") -> float:
    """Seconds until ``condition()`` holds (checked every millisecond)."""
    start = time.perf_counter()
    while not condition():
        if time.perf_counter() - start > timeout:
            raise TimeoutError(f"no answer in {timeout:g} s {what}")
        await asyncio.sleep(0.001)
    return time.perf_counter() - start


async def _calm(app: Timed, viewport: Viewport) -> None:
    """Wait until the picture is up to date and nothing was sent for CALM seconds."""
    await _until(lambda: viewport.up_to_date, 60.0)
    while time.perf_counter() - app.displayed < CALM:
        await asyncio.sleep(0.02)


def _press(app: Timed, key: str) -> None:
    character = key if len(key) == 1 else None
    app.post_message(events.Key(key, character))


async def one_run(config: Path, size: tuple[int, int]) -> dict[str, list[float]]:
    """Every figure of one fresh app: name -> [value]."""
    figures: dict[str, list[float]] = {}
    app = Timed(load_config(config))
    async with app.run_test(size=size):
        heartbeat = Heartbeat()
        heartbeat.start()
        viewport = app.screen.query_one(Viewport)
        numbers = _noting_updates(app.screen.query_one(Stats))
        for key, doing in KEYS:
            await _calm(app, viewport)
            heartbeat.reset()
            shown, arm = viewport._frames.shown, app.scene.arm
            pressed = time.perf_counter()
            _press(app, key)
            # Answered: the screen sent after the key, and after its numbers if it edited.
            answered = await _until(
                lambda: app.displayed > pressed and (app.scene.arm is arm or numbers
                                                     and pressed < numbers[-1] < app.displayed),
                what=f"to {key}",
            ) * 1000
            figures[f"{key} ({doing}): answered ms"] = [answered]
            figures[f"{key} ({doing}): loop stalled ms"] = [heartbeat.longest * 1000]
            if key in "cCxX":  # (benchmarks may peek: the number of the frame on screen)
                await _until(lambda: viewport._frames.shown > shown and viewport.up_to_date)
                figures[f"{key} ({doing}): picture ms"] = [(time.perf_counter() - pressed) * 1000]
        await _calm(app, viewport)
        figures.update(await held_key(app, viewport, heartbeat))
        await heartbeat.stop()
    return figures


async def held_key(app: Timed, viewport: Viewport, heartbeat: Heartbeat) -> dict:
    table = app.screen.query_one(NodeTable)
    updates: list[tuple[float, float]] = []  # (when, length) of each update of the table
    show = table.show

    def noted(muscle) -> None:
        show(muscle)
        updates.append((time.perf_counter(), muscle.length))

    table.show = noted  # type: ignore[method-assign]
    target = round(app.scene.arm.length - HELD * 0.1, 6)
    shown = viewport._frames.shown  # the number of the frame on screen (benchmarks may peek)
    heartbeat.reset()
    start = time.perf_counter()
    for number in range(HELD):
        await asyncio.sleep(max(0.0, start + number / REPEAT - time.perf_counter()))
        _press(app, "c")
    last = time.perf_counter()
    # The numbers are out once the table has the last length and the screen is sent after.
    await _until(lambda: updates and updates[-1][1] == target
                 and app.displayed > max(updates[-1][0], last))
    numbers = time.perf_counter() - last
    await _until(lambda: viewport._frames.shown > shown and viewport.up_to_date
                 and app.scene.arm.length == target)
    picture = time.perf_counter() - last
    return {
        "held c: numbers after the last press ms": [numbers * 1000],
        f"held c: table updates for {HELD} presses": [float(len(updates))],
        "held c: loop stalled ms": [heartbeat.longest * 1000],
        "held c: picture after the last press ms": [picture * 1000],
    }


def _noting_updates(stats: Stats) -> list[float]:
    """When ``stats`` is shown a new arm, from now on."""
    times: list[float] = []
    show = stats.show

    def noted(*args, **kwargs) -> None:
        show(*args, **kwargs)
        times.append(time.perf_counter())

    stats.show = noted  # type: ignore[method-assign]
    return times


def big_config(nodes: int, folder: Path) -> Path:
    """The bundled profile resampled to ``nodes`` nodes, at the bundled length."""
    muscle = load_config(DEFAULT_CONFIG).arm.muscle
    at = np.linspace(0.0, 1.0, nodes)
    given = np.linspace(0.0, 1.0, muscle.node_count)
    radius = np.interp(at, given, muscle.reference_radii)
    growth = np.interp(at, given, muscle.growth)
    path = folder / f"n{nodes}.toml"
    path.write_text(
        f"[muscle]\nlength = {muscle.reference_length}\n"
        f"radius = [{', '.join(map(repr, radius.tolist()))}]\n"
        f"growth = [{', '.join(map(repr, growth.tolist()))}]\n"
    )
    return path


async def measure(config: Path, runs: int, size: tuple[int, int]) -> dict[str, float]:
    collected: dict[str, list[float]] = {}
    for _ in range(runs):
        for name, values in (await one_run(config, size)).items():
            collected.setdefault(name, []).extend(values)
    return {name: statistics.median(values) for name, values in collected.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", type=int, default=16_384)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--size", default="120x36", help="the terminal, columns x rows")
    options = parser.parse_args()
    size = tuple(int(side) for side in options.size.split("x"))
    with tempfile.TemporaryDirectory() as folder:
        big = big_config(options.nodes, Path(folder))
        base = asyncio.run(measure(DEFAULT_CONFIG, options.runs, size))
        large = asyncio.run(measure(big, options.runs, size))
    print(f"the app at {size[0]}x{size[1]}, medians of {options.runs} runs")
    print(f"{'':52} {'15 nodes':>10} {f'{options.nodes:,} nodes':>14} {'x15':>6}")
    for name, value in large.items():
        ratio = value / base[name] if base[name] else float("nan")
        print(f"{name:52} {base[name]:10.1f} {value:14.1f} {ratio:6.1f}")
    answers = [value for name, value in large.items() if name.endswith("answered ms")]
    stalls = [value for name, value in large.items() if name.endswith("stalled ms")]
    print(f"slowest answer at {options.nodes:,} nodes: {max(answers):.1f} ms; longest stall of "
          f"the UI thread: {max(stalls):.1f} ms")


if __name__ == "__main__":
    main()
