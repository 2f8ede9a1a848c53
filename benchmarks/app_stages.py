"""The UI thread's CPU per frame, stage by stage, while a key is held, without a profiler's
distortion.

    .venv/bin/python benchmarks/app_stages.py [--config configs/elbow.toml] [--size 200x60]
                                              [--seconds 4] [--runs 3]
                                              [--baseline ../main/.venv/bin/python]

The app runs as ``benchmarks/app_profile.py`` runs it (in a pseudo-terminal, the right arrow
at 120 presses a second), with a timer around each function of :data:`STAGES`: the UI
thread's CPU time (``time.thread_time``, so not the time it waits for the GIL) in each call,
callees included, in ms per frame, and the calls per frame; medians over ``--runs`` runs.
cProfile (app_profile.py's functions) costs every Python call, which doubles what Python
code seems to cost beside compiled code; a dozen timers a frame cost a few microseconds.
With ``--baseline``, another checkout's app too, run for run in turn (a stage it does not
have is left out).

The app is this script with ``--child``: it starts the timers on SIGUSR1 and, on SIGUSR2,
stops them and writes what they counted for the parent to read.
"""

from __future__ import annotations

import functools
import importlib
import json
import os
import signal
import statistics
import tempfile
import threading
import time
from pathlib import Path

from app_profile import flood_arguments, in_turn, run_child
from tui_pty import FLOOD, hold, started

# What each stage is: a function of the UI thread, by module and qualified name. Indented
# stages run inside the one above them.
STAGES = {
    "compositor refresh": ("textual.screen", "Screen._compositor_refresh"),
    "  compose the update": ("textual._compositor", "Compositor._render_chops"),
    "    the viewport's lines": ("biceps.tui.widgets.viewport", "Viewport.render_lines"),
    "    Textual's styled lines": ("textual.widget", "Widget.render_lines"),
    "  write it": ("textual.app", "App._display"),
    "    the update's text": ("textual._compositor", "ChopsUpdate.render_segments"),
    "a frame received": ("biceps.tui.widgets.viewport", "Viewport.on_viewport_frame_rendered"),
    "  written by the viewport": ("biceps.tui.widgets.viewport", "Viewport._wrote"),
    "    its border rows": ("biceps.tui.widgets.viewport", "Viewport._styled"),
    "the SGR minimiser, all writes": ("biceps.tui.sgr", "minimized"),
    "a turn": ("biceps.tui.app", "BicepsApp.action_turn"),
}
TOTAL = "UI thread in all"


def time_stages(output: Path) -> None:
    """Wrap every stage in a timer, started by SIGUSR1; SIGUSR2 writes the timers' counts
    to ``output``."""
    spent: dict[str, float] = dict.fromkeys(STAGES, 0.0)
    calls: dict[str, int] = dict.fromkeys(STAGES, 0)
    timing = threading.Event()
    ui = threading.main_thread()

    def timed(name: str, function):
        @functools.wraps(function)  # (Textual reads an action's parameters from it)
        def timed_function(*args, **kwargs):
            if not timing.is_set() or threading.current_thread() is not ui:
                return function(*args, **kwargs)
            start = time.thread_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[name] += time.thread_time() - start
                calls[name] += 1
        return timed_function

    for name, (module_name, qualified) in STAGES.items():
        owner = importlib.import_module(module_name)
        *path, attribute = qualified.split(".")
        for part in path:
            owner = getattr(owner, part)
        if hasattr(owner, attribute):
            setattr(owner, attribute, timed(name, getattr(owner, attribute)))
        else:
            del spent[name], calls[name]

    started_at = [0.0]

    def start(*_) -> None:
        started_at[0] = time.thread_time()  # (signals are handled on the main thread)
        timing.set()

    def stop(*_) -> None:
        timing.clear()
        spent[TOTAL], calls[TOTAL] = time.thread_time() - started_at[0], 0
        output.write_text(json.dumps({"spent": spent, "calls": calls}))

    signal.signal(signal.SIGUSR1, start)
    signal.signal(signal.SIGUSR2, stop)


def measure(argv: list[str], size: tuple[int, int], seconds: float,
            output: Path) -> tuple[dict[str, float], dict[str, float], float]:
    """ms per frame and calls per frame of each stage, and the frame rate, over a flood."""
    terminal = started(argv, *size)
    try:
        hold(terminal, 30, 1.0, wait=True)  # warm every path up
        os.kill(terminal.process.pid, signal.SIGUSR1)
        phase = hold(terminal, FLOOD, seconds, wait=False)
        os.kill(terminal.process.pid, signal.SIGUSR2)
        deadline = time.monotonic() + 10
        while not output.exists() and time.monotonic() < deadline:
            terminal.pump(time.monotonic() + 0.05)
        counted = json.loads(output.read_text())
        output.unlink()
    finally:
        terminal.close()
    frames = max(phase.frames, 1)
    return ({name: 1000 * spent / frames for name, spent in counted["spent"].items()},
            {name: calls / frames for name, calls in counted["calls"].items()}, phase.fps)


def main() -> None:
    arguments = flood_arguments(__doc__.split("\n\n")[0]).parse_args()
    if arguments.child:
        run_child(arguments.child, arguments.output, time_stages)
        return
    with tempfile.TemporaryDirectory() as folder:
        runs, _ = in_turn(arguments, Path(__file__), measure, Path(folder) / "stages.json")
    pythons = list(runs)
    print(f"UI thread CPU, ms per frame (calls per frame), medians of {arguments.runs}")
    print(f"{'':28}" + "".join(f"{name:>18}" for name in pythons))
    fps = {name: statistics.median(run[2] for run in name_runs)
           for name, name_runs in runs.items()}
    print(f"{'frames per second':28}" + "".join(f"{fps[name]:18.1f}" for name in pythons))
    for stage in [*STAGES, TOTAL]:
        cells = []
        for name_runs in runs.values():
            if stage not in name_runs[0][0]:
                cells.append(f"{'-':>18}")
                continue
            spent = statistics.median(run[0][stage] for run in name_runs)
            calls = statistics.median(run[1][stage] for run in name_runs)
            cells.append(f"{spent:11.3f} ({calls:3.1f})" if stage != TOTAL else f"{spent:18.3f}")
        print(f"{stage:28}" + "".join(cells))


if __name__ == "__main__":
    main()
