"""Where the app's CPU goes while a key is held: per thread, and per function on the UI thread.

    .venv/bin/python benchmarks/app_profile.py [--config configs/elbow.toml] [--size 200x60]
                                               [--seconds 4] [--runs 3] [--top 30]
                                               [--baseline ../main/.venv/bin/python]

The app runs in a pseudo-terminal played by ``benchmarks/tui_pty.py`` (which answers the
app's questions and counts its frames), with the right arrow at 120 presses a second, the
pty benchmark's flood. Two parts:

- threads: each of the app's threads' CPU over the flood (``/proc/PID/task/TID/stat``, no
  profiler attached), in ms per frame, median over ``--runs`` runs, named as Python names
  them: MainThread is the UI thread (asyncio and Textual); asyncio_0 the render worker
  (Textual runs thread workers in asyncio's executor), which draws and encodes, with
  biceps-band_0 drawing the other band; textual-input and textual-output read and write
  the terminal. With ``--baseline``, another checkout's app too, run for run in turn.
- functions: the flood again with cProfile on the UI thread (which slows it, so the figures
  are shares, not rates): the ``--top`` functions by their own time, and by the time in
  them and what they call, in ms per frame, and their calls per frame.

The app is this script with ``--child``: it starts the app as ``biceps app`` does, and
starts or stops cProfile on SIGUSR1 or SIGUSR2 (the stop writes the statistics and the
map of thread ids to names for the parent to read).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import statistics
import sys
import tempfile
import time
from pathlib import Path

from tui_pty import CONFIG, FLOOD, Terminal, hold, started

TICK = os.sysconf("SC_CLK_TCK")


def listen(output: Path) -> None:
    """From now on, SIGUSR1 starts cProfile and SIGUSR2 stops it and writes its statistics
    and the map of thread ids to names to ``output``."""
    import cProfile
    import threading

    profile = cProfile.Profile()

    # Signals are handled on the main thread, so it is the UI thread that is profiled.
    def start(*_) -> None:
        profile.enable()

    def stop(*_) -> None:
        profile.disable()
        profile.dump_stats(str(output))
        names = {str(thread.native_id): thread.name for thread in threading.enumerate()}
        output.with_suffix(".threads").write_text(json.dumps(names))

    signal.signal(signal.SIGUSR1, start)
    signal.signal(signal.SIGUSR2, stop)


def run_child(config: Path, output: Path, signals=listen) -> None:
    """The app, as ``biceps app`` starts it, with ``signals(output)`` (:func:`listen`)
    set up first."""
    signals(output)
    sys.argv = ["biceps", "app", str(config)]
    from biceps.cli import run

    run()


def thread_ticks(pid: int) -> dict[str, int]:
    """Each thread's user and system time so far, in clock ticks."""
    ticks = {}
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{tid}/stat") as stat:
                fields = stat.read().rpartition(")")[2].split()
        except FileNotFoundError:
            continue
        ticks[tid] = int(fields[11]) + int(fields[12])
    return ticks


def thread_names(terminal: Terminal, output: Path) -> dict[str, str]:
    os.kill(terminal.process.pid, signal.SIGUSR2)
    deadline = time.monotonic() + 10
    path = output.with_suffix(".threads")
    while not path.exists() and time.monotonic() < deadline:
        terminal.pump(time.monotonic() + 0.05)
    names = json.loads(path.read_text())
    path.unlink()
    return names


def measure_threads(argv: list[str], size: tuple[int, int], seconds: float,
                    output: Path) -> tuple[dict[str, float], float, float]:
    """ms per frame for each thread (by name), fps, CPU ms per frame in all."""
    terminal = started(argv, *size)
    try:
        hold(terminal, 30, 1.0, wait=True)  # warm every path up
        before = thread_ticks(terminal.process.pid)
        phase = hold(terminal, FLOOD, seconds, wait=False)
        after = thread_ticks(terminal.process.pid)
        names = thread_names(terminal, output)
    finally:
        terminal.close()
    frames = max(phase.frames, 1)
    per_thread: dict[str, float] = {}
    for tid, ticks in after.items():
        name = names.get(tid, f"thread {tid}")
        spent = (ticks - before.get(tid, 0)) / TICK
        per_thread[name] = per_thread.get(name, 0.0) + 1000 * spent / frames
    return per_thread, phase.fps, 1000 * phase.cpu / frames


def profile_functions(argv: list[str], size: tuple[int, int], seconds: float, output: Path,
                      top: int) -> None:
    import pstats

    terminal = started(argv, *size)
    try:
        hold(terminal, 30, 1.0, wait=True)
        os.kill(terminal.process.pid, signal.SIGUSR1)
        phase = hold(terminal, FLOOD, seconds, wait=False)
        thread_names(terminal, output)
    finally:
        terminal.close()
    frames = max(phase.frames, 1)
    print(f"\nprofiled flood: {phase.fps:.1f} fps (slowed by the profiler), {frames} frames")
    for key, title in (("tottime", "own time"), ("cumulative", "time with callees")):
        stats = pstats.Stats(str(output))
        print(f"\nUI thread, top {top} by {title}, ms per frame:")
        rows = sorted(stats.stats.items(), key=lambda item: item[1][2 if key == "tottime"
                                                                      else 3], reverse=True)
        for (path, line, name), (_, calls, own, cumulative, _) in rows[:top]:
            where = f"{Path(path).parent.name}/{Path(path).name}:{line}" if path != "~" else ""
            print(f"  {1000 * own / frames:7.3f} {1000 * cumulative / frames:7.3f} "
                  f"{calls / frames:8.1f}  {name}  {where}")


def report(name: str, runs: list[tuple[dict[str, float], float, float]]) -> float:
    """Print the medians of ``runs``; return the CPU ms per frame."""
    cpu = statistics.median(run[2] for run in runs)
    fps = statistics.median(run[1] for run in runs)
    print(f"{name}: {fps:.1f} fps, CPU {cpu:.2f} ms per frame, {cpu * fps / 10:.0f} % of a "
          f"core (medians of {len(runs)})")
    names = {name for run in runs for name in run[0]}
    for thread in sorted(names, key=lambda thread: -statistics.median(
            run[0].get(thread, 0.0) for run in runs)):
        spent = statistics.median(run[0].get(thread, 0.0) for run in runs)
        if spent >= 0.005:
            print(f"  {spent:7.2f} ms/frame  {thread}")
    return cpu


def flood_arguments(description: str) -> argparse.ArgumentParser:
    """The options of a benchmark of the app under a held key (this one's, and
    ``app_stages.py``'s): the model, the size, the runs, another checkout to measure in
    turn; and the child's."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--config", type=Path, default=CONFIG)
    parser.add_argument("--size", default="200x60")
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--baseline", type=Path, metavar="PYTHON",
                        help="the Python of another checkout's environment (main's, say): "
                             "its app is measured too, run for run in turn with this one")
    parser.add_argument("--child", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--output", type=Path, help=argparse.SUPPRESS)
    return parser


def in_turn(arguments: argparse.Namespace, script: Path, measure, output: Path):
    """``measure(argv, size, seconds, output)`` of the app started by ``script`` with
    ``--child``, by this checkout's Python and the baseline's, ``--runs`` times in turn so
    that both see the same load: each one's results by name ("baseline", "this"), the
    load averages seen, and the argv of each."""
    size = tuple(map(int, arguments.size.split("x")))
    pythons = {"this": Path(sys.executable)}
    if arguments.baseline:
        pythons = {"baseline": arguments.baseline, **pythons}
    argvs = {name: [str(python), str(script.resolve()), "--child",
                    str(arguments.config.resolve()), "--output", str(output)]
             for name, python in pythons.items()}
    runs: dict[str, list] = {name: [] for name in pythons}
    loads = []
    for _ in range(arguments.runs):
        for name, argv in argvs.items():
            runs[name].append(measure(argv, size, arguments.seconds, output))
            loads.append(os.getloadavg()[0])
    print(f"model: {arguments.config}, {size[0]}x{size[1]}, key at {FLOOD:g}/s, "
          f"load {min(loads):.2f} to {max(loads):.2f}")
    return runs, argvs


def main() -> None:
    parser = flood_arguments(__doc__.split("\n\n")[0])
    parser.add_argument("--top", type=int, default=30)
    parser.add_argument("--no-functions", action="store_true", help="threads only")
    arguments = parser.parse_args()
    if arguments.child:
        run_child(arguments.child, arguments.output)
        return
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "profile.pstat"
        runs, argvs = in_turn(arguments, Path(__file__), measure_threads, output)
        cpu = {name: report(name, name_runs) for name, name_runs in runs.items()}
        if arguments.baseline:
            print(f"CPU per frame, this / baseline: {cpu['this'] / cpu['baseline']:.2f}")
        if not arguments.no_functions:
            size = tuple(map(int, arguments.size.split("x")))
            profile_functions(argvs["this"], size, arguments.seconds, output, arguments.top)


if __name__ == "__main__":
    main()
