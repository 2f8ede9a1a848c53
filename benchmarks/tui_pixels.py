"""Real pixels as a terminal sees them: the app in a pseudo-terminal that answers like kitty
and like a sixel terminal, beside half-blocks measured in the same run.

    .venv/bin/python benchmarks/tui_pixels.py [--size 120x40] [--cell 10x20] [--seconds 4]
                                              [--links 5] [--runs 3] [--quick]

The machinery is ``tui_pty.py``'s: the same key held at 30 presses a second (typematic:
key-to-picture latency) and at 120 (flood: frames per second, bytes per frame, CPU), the
same emulated slow links (lag from the last key to its picture). This terminal also
answers the app's questions at start (``terminal/detect.py``) as the terminal it plays would,
with cells of ``--cell`` pixels, and counts a frame when an image ends (the cursor
restored after it), taking its yaw from the last caption written before it.

Each figure is the median over ``--runs`` runs. Goals (issue 14), at 120x40 cells of
10x20 pixels: at least 30 fps with a key held, a key's picture within 50 ms (median),
and at most 0.5 s of lag on a 5 Mbit/s link; half-blocks keep their 58 fps at 200x60 and
18 KB a frame.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import tui_pty  # noqa: E402
from tui_pty import (  # noqa: E402
    CAPTION,
    CURSOR_QUERY,
    SYNC_QUERY,
    SYNC_SUPPORTED,
    TYPEMATIC,
    FLOOD,
    Frame,
    Terminal,
    hold,
    over_link,
    started,
)

DEVICE_ATTRIBUTES_QUERY = b"\x1b[c"
RESTORE_CURSOR = b"\x1b8"
IMAGE_STARTS = (b"\x1b_Ga=T", b"\x1bP0;1;0q")  # kitty, sixel (terminal/kitty.py, sixel.py)


def answers(graphics: str, cell: tuple[int, int]) -> bytes:
    """What the terminal says to the app's questions at start: kitty's or xterm's."""
    width, height = cell
    size = f"\x1b[6;{height};{width}t".encode()
    if graphics == "kitty":
        return b"\x1b_Gi=31;OK\x1b\\\x1bP>|kitty(benchmark)\x1b\\" + size + b"\x1b[?62;c"
    return b"\x1bP>|XTerm(benchmark)\x1b\\\x1b[?1;0;256S" + size + b"\x1b[?63;1;2;4;6c"


@dataclass
class PixelTerminal(Terminal):
    """A terminal that shows images: a frame ends where an image does."""

    graphics: str = "kitty"
    cell: tuple[int, int] = (10, 20)
    _yaw: float | None = None
    _in_image: bool = False
    _seen: bytes = b""

    def _take(self, data: bytes, now: float) -> None:
        seen = self._seen + data
        start = len(self._seen)  # where this read begins in seen
        self.received += len(data)
        events = sorted(
            (at, marker)
            for marker in (SYNC_QUERY, CURSOR_QUERY, DEVICE_ATTRIBUTES_QUERY, RESTORE_CURSOR,
                           *IMAGE_STARTS)
            for at in tui_pty._offsets(seen, marker, start - len(marker) + 1)
        )
        for at, marker in events:
            before = seen[:at]
            if marker == SYNC_QUERY:
                os.write(self.master, SYNC_SUPPORTED)
            elif marker == DEVICE_ATTRIBUTES_QUERY:
                os.write(self.master, answers(self.graphics, self.cell))
            elif marker == CURSOR_QUERY:
                move = tui_pty.CURSOR_MOVE.search(before[-16:])
                row, column = move.groups() if move else (b"1", b"1")
                os.write(self.master, b"\x1b[" + row + b";" + column + b"R")
            elif marker in IMAGE_STARTS:
                captions = CAPTION.findall(before)
                if captions:
                    self._yaw = float(captions[-1])
                self._in_image = True
            elif self._in_image:  # the cursor restored: the image has ended
                self._in_image = False
                self.frames.append(Frame(now, self._yaw))
        if not self._in_image:
            captions = CAPTION.findall(seen)
            if captions:
                self._yaw = float(captions[-1])
        # Keep enough to find a marker or caption cut in two, and the cursor move before a
        # question; an image in progress needs no more than that either.
        self._seen = seen[-64:]


def start_pixels(graphics: str, size: tuple[int, int], cell: tuple[int, int]) -> Terminal:
    """The app with ``--graphics graphics`` in a terminal of ``size`` cells of ``cell``."""
    width, height = cell

    def start(argv: list[str], columns: int, rows: int) -> PixelTerminal:
        terminal = PixelTerminal.start(argv, columns, rows, (columns * width, rows * height))
        terminal.graphics, terminal.cell = graphics, cell  # long before the app asks
        return terminal

    return started([*tui_pty.biceps_argv(), "--graphics", graphics], *size, start=start)


def measure(graphics: str, size, cell, seconds: float, megabits: list[float],
            python: str = sys.executable) -> dict:
    if graphics == "halfblocks":
        # -P: the code installed for ``python``, not the checkout this runs in, and its own
        # bundled model (the same picture, in the format that code reads).
        terminal = started([python, "-P", "-m", "biceps.cli", "app"], *size)
    else:
        terminal = start_pixels(graphics, size, cell)
    try:
        typematic = hold(terminal, TYPEMATIC, seconds)
        flood = hold(terminal, FLOOD, seconds, wait=False)
        links = [over_link(terminal, rate, seconds) for rate in megabits]
    finally:
        terminal.close()
    median, _ = typematic.latency_ms
    return {"fps 30": typematic.fps, "fps 120": flood.fps, "KB/frame": flood.kb_per_frame,
            "key ms": median, "CPU %": flood.cpu_percent,
            **{f"lag {rate:g} Mbit/s": (link.lag if link.lag is not None else float("inf"))
               for rate, link in zip(megabits, links)}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--size", default="120x40", help="terminal size in cells")
    parser.add_argument("--cell", default="10x20", help="cell size in pixels")
    parser.add_argument("--halfblocks-size", default="200x60")
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--links", default="5", help="emulated links in Mbit/s")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="one run of 2 s phases")
    parser.add_argument("--baseline", metavar="PYTHON",
                        help="also half-blocks at --halfblocks-size from another install "
                        "(the Python of a venv with the code to compare with)")
    arguments = parser.parse_args()
    if arguments.quick:
        arguments.runs, arguments.seconds = 1, 2.0
    size = tuple(map(int, arguments.size.split("x")))
    cell = tuple(map(int, arguments.cell.split("x")))
    halfblocks_size = tuple(map(int, arguments.halfblocks_size.split("x")))
    megabits = [float(rate) for rate in arguments.links.split(",")]
    cases = [("kitty", size, sys.executable), ("sixel", size, sys.executable),
             ("halfblocks", size, sys.executable),
             ("halfblocks", halfblocks_size, sys.executable)]
    if arguments.baseline:
        cases.append(("halfblocks", halfblocks_size, arguments.baseline))
    columns, table = None, []
    # Runs of the cases interleave, so that a busy moment of the machine touches them all.
    runs = {case: [] for case in cases}
    for _ in range(arguments.runs):
        for case in cases:
            graphics, case_size, python = case
            runs[case].append(measure(graphics, case_size, cell, arguments.seconds, megabits,
                                      python))
    for case in cases:
        graphics, case_size, python = case
        figures = {key: statistics.median(run[key] for run in runs[case])
                   for key in runs[case][0]}
        table.append(figures)
        if columns is None:
            columns = list(figures)
            print(f"{'graphics':<11} {'size':<8} " + " ".join(f"{key:>14}" for key in columns))
        name = graphics if python == sys.executable else "baseline"
        print(f"{name:<11} {case_size[0]}x{case_size[1]:<5} "
              + " ".join(f"{figures[key]:>14.2f}" for key in columns), flush=True)
    if arguments.baseline:
        ours, theirs = table[3], table[4]
        print("\nhalf-blocks at {}x{} against the baseline: ".format(*halfblocks_size)
              + ", ".join(f"{key} {ours[key] / theirs[key]:.2f}x" for key in
                          ("fps 120", "KB/frame", "key ms", "CPU %")))
    print(f"\nmedians of {arguments.runs} runs of {arguments.seconds:g} s phases; cells of "
          f"{cell[0]}x{cell[1]} pixels for kitty and sixel; lag in seconds")


if __name__ == "__main__":
    main()
