"""The terminal app as a terminal sees it: frames per second, bytes per frame, key-to-picture
latency, CPU, and the lag left behind on slow links, beside rich-pixels in a ``Static``.

    .venv/bin/python benchmarks/tui_pty.py [--sizes 200x60,400x100] [--seconds 4]
                                           [--links 5,20] [--link-size 200x60] [--quick]
                                           [--config configs/elbow.toml]
                                           [--graphics halfblocks,sextants]

Each app runs in a pseudo-terminal of the given size, with TERM=xterm-256color and
COLORTERM=truecolor. This script plays the terminal: it answers the synchronized-output
query (so that Textual brackets every frame with ``CSI ? 2026 h`` ... ``CSI ? 2026 l``, which
is how frames are counted) and every cursor-position request (``CSI 6 n``, which the app
uses for flow control), each when it reads it, as a terminal would.

Both apps caption each picture with the yaw it was drawn at, so every frame says which key
press it shows: the latency of a key is the time from writing it to the end of the first
frame that shows it (or a later key), which is when a terminal would show that picture.

Phases, for each app and size:

- typematic: the rotate key held at 30 presses a second, as a keyboard repeats it; gives
  the key-to-picture latency (median and 95th percentile), and a frame rate that cannot
  exceed 30, since identical frames are not sent.
- flood: the key at 120 a second, faster than any frame rate, so that the frame rate is
  the pipeline's own; gives fps, bytes per frame (all bytes written over the phase, divided
  by frames) and CPU (the app process, all threads, in % of one core).

``--graphics`` measures biceps once with each of the text encoders named (its
``--graphics``), one after the other, beside the baseline: half-blocks, and the finer
sextants or quadrants, each with its bytes a frame over those of the half-blocks measured
last before it at the same size ("/ biceps").

Then, at one size, each emulated link (the pty read no faster than N Mbit/s): the key held
at 30 a second, then released; the lag is the time from the last key to the end of the
first frame showing it, and "answered" says whether that frame came at all (within 60 s).
"""

from __future__ import annotations

import argparse
import fcntl
import os
import re
import select
import signal
import statistics
import struct
import subprocess
import sys
import termios
import time
from dataclasses import dataclass, field
from pathlib import Path

import biceps
from biceps.tui.changes import TURN_STEP  # degrees per press of the right arrow

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "configs" / "biceps.toml"
INSTALLED = Path(biceps.__file__).resolve().parent.parent
"""Where the apps start: the checkout of the biceps this Python imports. From this one's
root, another installation's Python (``-m biceps.cli``) would run this checkout's code."""

SYNC_START = b"\x1b[?2026h"
SYNC_END = b"\x1b[?2026l"
SYNC_QUERY = b"\x1b[?2026$p"
SYNC_SUPPORTED = b"\x1b[?2026;2$y"
CURSOR_QUERY = b"\x1b[6n"
CURSOR_MOVE = re.compile(rb"\x1b\[(\d+);(\d+)H$")
RIGHT = b"\x1b[C"
MARKER_TAIL = max(len(SYNC_START), len(SYNC_QUERY), len(CURSOR_QUERY)) - 1

CAPTION = re.compile(rb"yaw (-?\d+(?:\.\d+)?)\xc2\xb0")
STEPS_PER_TURN = round(360 / TURN_STEP)

NOTES_GONE = 7.0  # seconds: Textual's notifications last 5
TYPEMATIC = 30.0  # key presses per second
FLOOD = 120.0
STARTUP_TIMEOUT = 180.0  # a cold numba cache compiles every kernel first
DRAIN_TIMEOUT = 60.0


@dataclass
class Frame:
    end: float  # when its last byte was read
    yaw: float | None  # the caption's yaw, if the frame drew one


@dataclass
class Terminal:
    """A command in a pseudo-terminal, and what a terminal would see of it."""

    process: subprocess.Popen
    master: int
    rate: float | None = None  # bytes per second the link carries; None for no limit
    frames: list[Frame] = field(default_factory=list)
    received: int = 0  # bytes read so far
    keys: list[float] = field(default_factory=list)  # when each key was written
    _tail: bytes = b""
    _recent: bytearray = field(default_factory=bytearray)  # the output from _recent_at on
    _recent_at: int = 0
    _frame_at: int | None = None  # where the frame being read began
    _tokens: float = 0.0
    _refilled: float = 0.0

    @classmethod
    def start(cls, argv: list[str], columns: int, rows: int,
              pixels: tuple[int, int] = (0, 0)) -> Terminal:
        """``argv`` in a terminal of ``columns x rows`` cells, ``pixels`` (width, height)
        in all, if it says."""
        master, slave = os.openpty()
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", rows, columns, *pixels))
        environment = {
            key: value for key, value in os.environ.items() if not key.startswith("TEXTUAL")
        }
        environment.update(TERM="xterm-256color", COLORTERM="truecolor")
        process = subprocess.Popen(
            argv, stdin=slave, stdout=slave, stderr=slave, env=environment, cwd=INSTALLED,
            start_new_session=True, close_fds=True,
        )  # fmt: skip
        os.close(slave)
        return cls(process, master)

    def limit(self, megabits: float | None) -> None:
        """From now on, read no faster than a link of ``megabits`` per second."""
        self.rate = None if megabits is None else megabits * 1e6 / 8
        self._tokens, self._refilled = 0.0, time.monotonic()

    def press(self, key: bytes = RIGHT) -> None:
        os.write(self.master, key)
        self.keys.append(time.monotonic())

    def pump(self, until: float) -> None:
        """Read and answer the app's output until ``until`` (a monotonic time)."""
        while (now := time.monotonic()) < until:
            wanted = 1 << 16
            if self.rate is not None:
                # A token bucket: what the link has carried since the last read, at most
                # 20 ms of it, so that a pause does not turn into a burst.
                self._tokens = min(self._tokens + (now - self._refilled) * self.rate,
                                   0.02 * self.rate)
                self._refilled = now
                wanted = int(min(wanted, self._tokens))
                if wanted < 512:
                    time.sleep(min(until - now, (512 - wanted) / self.rate))
                    continue
            ready, _, _ = select.select([self.master], [], [], min(until - now, 0.005))
            if not ready:
                continue
            try:
                data = os.read(self.master, wanted)
            except OSError:  # the app has gone
                return
            if self.rate is not None:
                self._tokens -= len(data)
            self._take(data, time.monotonic())

    def _take(self, data: bytes, now: float) -> None:
        # Markers may straddle two reads: look at the end of the last read too, and take
        # only the markers that end in this one.
        seen = self._tail + data
        base = self.received - len(self._tail)  # where seen begins in the whole output
        markers = sorted(
            (base + at, marker)
            for marker in (SYNC_QUERY, CURSOR_QUERY, SYNC_START, SYNC_END)
            for at in _offsets(seen, marker, len(self._tail) - len(marker) + 1)
        )
        self._recent += data
        self.received += len(data)
        self._tail = seen[-MARKER_TAIL:]
        for at, marker in markers:
            if marker == SYNC_QUERY:
                os.write(self.master, SYNC_SUPPORTED)
            elif marker == CURSOR_QUERY:
                os.write(self.master, self._cursor_report(at))
            elif marker == SYNC_START:
                self._frame_at = at
            elif self._frame_at is not None:
                end = at + len(SYNC_END)
                frame = self._recent[self._frame_at - self._recent_at:end - self._recent_at]
                captions = CAPTION.findall(frame)
                yaw = float(captions[-1]) if captions else None
                self.frames.append(Frame(now, yaw))
                self._frame_at = None
        if self._frame_at is None:  # keep only what a marker or a question may need
            self._recent = self._recent[-32:]
            self._recent_at = self.received - len(self._recent)

    def _cursor_report(self, at: int) -> bytes:
        # Where the cursor is: this terminal follows only a move just before the question,
        # which is how the app asks (tui/pacing.py); anything else is answered with 1;1.
        before = self._recent[max(at - self._recent_at - 16, 0):at - self._recent_at]
        move = CURSOR_MOVE.search(bytes(before))
        row, column = move.groups() if move else (b"1", b"1")
        return b"\x1b[" + row + b";" + column + b"R"

    def cpu_seconds(self) -> float:
        """User and system time of the app process so far, all its threads."""
        with open(f"/proc/{self.process.pid}/stat") as stat:
            fields = stat.read().rpartition(")")[2].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")

    def close(self) -> None:
        if self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
        self.process.wait()
        os.close(self.master)


def _offsets(data: bytes, marker: bytes, start: int):
    """Every offset of ``marker`` in ``data`` from ``start`` on."""
    at = data.find(marker, max(start, 0))
    while at >= 0:
        yield at
        at = data.find(marker, at + 1)


# ----------------------------------------------------------------------------------------
# Keys held, and what the pictures say about them


@dataclass
class Phase:
    seconds: float
    frames: int
    received: int
    cpu: float  # seconds
    latencies: list[float]  # seconds, one per key whose picture came

    @property
    def fps(self) -> float:
        return self.frames / self.seconds

    @property
    def kb_per_frame(self) -> float:
        return self.received / max(self.frames, 1) / 1000

    @property
    def cpu_percent(self) -> float:
        return 100 * self.cpu / self.seconds

    @property
    def latency_ms(self) -> tuple[float, float]:
        if not self.latencies:
            return float("nan"), float("nan")
        ordered = sorted(self.latencies)
        return 1000 * statistics.median(ordered), 1000 * ordered[int(0.95 * (len(ordered) - 1))]


def hold(terminal: Terminal, rate: float, seconds: float, wait: bool = True) -> Phase:
    """Press the rotate key ``rate`` times a second for ``seconds``, reading all along;
    then, if ``wait``, read on until the last key's picture arrives (or the timeout), so
    that every key has a latency, however late."""
    first_key, first_frame = len(terminal.keys), len(terminal.frames)
    received, cpu = terminal.received, terminal.cpu_seconds()
    start = time.monotonic()
    for press in range(round(rate * seconds)):
        terminal.pump(start + press / rate)
        terminal.press()
    end = start + seconds
    terminal.pump(end)
    frames = sum(frame.end <= end for frame in terminal.frames[first_frame:])
    phase = Phase(seconds, frames, terminal.received - received, terminal.cpu_seconds() - cpu,
                  latencies=[])
    if wait:
        deadline = time.monotonic() + DRAIN_TIMEOUT
        while pictures(terminal)[-1] is None and time.monotonic() < deadline:
            terminal.pump(time.monotonic() + 0.05)
    phase.latencies = [shown - pressed for pressed, shown in
                       zip(terminal.keys[first_key:], pictures(terminal)[first_key:])
                       if shown is not None]
    return phase


def pictures(terminal: Terminal) -> list[float | None]:
    """For each key pressed, when the first frame showing it (or a later key) ended."""
    shown: list[float | None] = [None] * len(terminal.keys)
    count, first = None, 0
    for frame in terminal.frames:
        if frame.yaw is None:
            continue
        steps = round(frame.yaw / TURN_STEP)
        if count is None:  # the first picture, before any key
            count, base = 0, steps
            continue
        # Yaw wraps every full turn: count on from the last picture, which is right as
        # long as fewer than a full turn of keys go by between two pictures.
        count += (steps - base - count) % STEPS_PER_TURN
        while first < min(count, len(shown)):
            shown[first] = frame.end
            first += 1
    return shown


@dataclass
class LinkResult:
    megabits: float
    lag: float | None  # seconds from the last key to its picture; None: never shown
    latencies: list[float]


def over_link(terminal: Terminal, megabits: float, seconds: float) -> LinkResult:
    """Hold the key over a slow link, release it, and wait for its last picture."""
    terminal.limit(megabits)
    phase = hold(terminal, TYPEMATIC, seconds)
    shown = pictures(terminal)[-1]
    lag = None if shown is None else shown - terminal.keys[-1]
    return LinkResult(megabits, lag, phase.latencies)


def started(argv: list[str], columns: int, rows: int, start=Terminal.start,
            first: bytes = b"") -> Terminal:
    """The app in a terminal (made by ``start``), its first picture drawn, the keys
    ``first`` typed, and a moment to settle."""
    terminal = start(argv, columns, rows)
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while not any(frame.yaw is not None for frame in terminal.frames):
        if time.monotonic() > deadline or terminal.process.poll() is not None:
            terminal.close()
            raise RuntimeError(f"{argv} drew no picture at {columns}x{rows}")
        terminal.pump(time.monotonic() + 0.1)
    for key in first:  # not as presses: no picture is awaited for them
        os.write(terminal.master, bytes([key]))
        terminal.pump(time.monotonic() + 0.2)
    # Time for what they said to go: a notification over the picture slows every frame.
    terminal.pump(time.monotonic() + (NOTES_GONE if first else 1.0))
    return terminal


# ----------------------------------------------------------------------------------------
# The apps


def biceps_argv(config: Path = CONFIG, graphics: str | None = None) -> list[str]:
    """The app on ``config``, with ``--graphics graphics`` if given."""
    return [sys.executable, "-m", "biceps.cli", "app", str(config),
            *(["--graphics", graphics] if graphics else [])]


def baseline_argv(config: Path) -> list[str]:
    return [sys.executable, str(Path(__file__).resolve()), "--rich-pixels-app",
            "--config", str(config)]


def run_rich_pixels_app(config: Path) -> None:
    """The baseline: each key re-renders the scene and shows it with rich-pixels in a Static."""
    from PIL import Image
    from rich.console import Group
    from rich.text import Text
    from rich_pixels import Pixels
    from textual.app import App, ComposeResult
    from textual.widgets import Static

    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene
    from biceps.engine.scene_renderer import SceneRenderer
    from biceps.tui.changes import turned

    class RichPixelsApp(App[None]):
        CSS = "Static { height: 1fr; }"
        BINDINGS = [("right", "turn", "Turn"), ("q", "quit", "Quit")]

        def __init__(self) -> None:
            super().__init__()
            self.scene = Scene.of(load_config(config))
            self.renderer = SceneRenderer()

        def compose(self) -> ComposeResult:
            yield Static()

        def on_resize(self) -> None:
            self.call_after_refresh(self.draw)

        def action_turn(self) -> None:
            self.scene = turned(self.scene, yaw=TURN_STEP)
            self.draw()

        def draw(self) -> None:
            static = self.query_one(Static)
            width, height = static.size
            if width and height > 1:
                frame = self.renderer.render(self.scene, width, 2 * (height - 1))
                caption = Text(f"yaw {self.scene.view.yaw:g}°")
                static.update(Group(caption, Pixels.from_image(Image.fromarray(frame))))

    RichPixelsApp().run()


# ----------------------------------------------------------------------------------------
# The table


def measure_app(name: str, argv: list[str], size: tuple[int, int], seconds: float,
                half_blocks_kb: float | None = None, first: bytes = b"") -> tuple[str, float]:
    """The app's line of the table, and its KB a frame in the flood; ``half_blocks_kb``:
    the half-blocks' at this size in this run, for the ratio; ``first``: keys typed once it
    is up."""
    terminal = started(argv, *size, first=first)
    try:
        typematic = hold(terminal, TYPEMATIC, seconds)
        flood = hold(terminal, FLOOD, seconds, wait=False)
    finally:
        terminal.close()
    median, p95 = typematic.latency_ms
    ratio = (f"{flood.kb_per_frame / half_blocks_kb:8.2f}x" if half_blocks_kb else
             f"{'-':>9}")
    return (f"{name:<12} {size[0]}x{size[1]:<8} {typematic.fps:7.1f} {flood.fps:7.1f} "
            f"{flood.kb_per_frame:9.1f} {ratio} {median:8.1f} {p95:8.1f} "
            f"{flood.cpu_percent:6.0f}"), flood.kb_per_frame


def measure_link(name: str, argv: list[str], size: tuple[int, int], megabits: float,
                 seconds: float) -> str:
    terminal = started(argv, *size)
    try:
        result = over_link(terminal, megabits, seconds)
    finally:
        terminal.close()
    lag = "never" if result.lag is None else f"{result.lag:.2f} s"
    latency = (f"{1000 * statistics.median(result.latencies):.0f}"
               if result.latencies else "-")
    answered = "yes" if result.lag is not None else "no"
    return (f"{name:<12} {size[0]}x{size[1]:<6} {megabits:5g} Mbit/s {lag:>9} "
            f"{latency:>10} {answered:>9}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="200x60,400x100",
                        help="terminal sizes in cells, comma-separated")
    parser.add_argument("--seconds", type=float, default=4.0, help="length of each phase")
    parser.add_argument("--links", default="5,20",
                        help='emulated links in Mbit/s ("" for none)')
    parser.add_argument("--link-size", default="200x60")
    parser.add_argument("--link-seconds", type=float, default=5.0)
    parser.add_argument("--no-baseline", action="store_true", help="measure biceps only")
    parser.add_argument("--quick", action="store_true",
                        help="200x60 only, 2 s phases, 5 Mbit/s only")
    parser.add_argument("--config", type=Path, default=CONFIG,
                        help="the model both apps show (default configs/biceps.toml)")
    parser.add_argument("--graphics", default="halfblocks",
                        help="biceps's text encoders to measure, comma-separated: halfblocks, "
                        "sextants, quadrants")
    parser.add_argument("--first", default="",
                        help="keys biceps is typed once it is up, before the phases: '}}}}}' "
                        "puts 5 kg in the hand, so that the forces are shown")
    parser.add_argument("--rich-pixels-app", action="store_true", help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.rich_pixels_app:
        run_rich_pixels_app(arguments.config)
        return
    if arguments.quick:
        arguments.sizes, arguments.seconds, arguments.links = "200x60", 2.0, "5"
    sizes = [tuple(map(int, size.split("x"))) for size in arguments.sizes.split(",")]
    link_size = tuple(map(int, arguments.link_size.split("x")))
    apps = [("biceps" if graphics == "halfblocks" else graphics,
             biceps_argv(arguments.config, graphics))
            for graphics in arguments.graphics.split(",")]
    if not arguments.no_baseline:
        apps.append(("rich-pixels", baseline_argv(arguments.config)))
    print(f"model: {arguments.config}")

    # The bytes a frame of each over the half-blocks' measured last at the same size.
    print(f"{'':<12} {'':<12} {'fps at keys/s':>15} {'':>9} {'bytes':>9} "
          f"{'key to picture':>17}")
    print(f"{'app':<12} {'size':<12} {'30':>7} {'120':>7} {'KB/frame':>9} {'/ biceps':>9} "
          f"{'median':>8} {'p95 ms':>8} {'CPU %':>6}")
    for size in sizes:
        half_blocks_kb = None
        for name, argv in apps:
            first = arguments.first.encode() if name != "rich-pixels" else b""
            line, kb = measure_app(name, argv, size, arguments.seconds, half_blocks_kb, first)
            if name == "biceps":
                half_blocks_kb = kb
            print(line, flush=True)
    links = [float(megabits) for megabits in arguments.links.split(",") if megabits.strip()]
    if not links:  # --links "": the sizes alone
        return
    print()
    print(f"{'app':<12} {'size':<10} {'link':>12} {'lag':>9} {'key ms':>10} {'answered':>9}")
    for megabits in links:
        for name, argv in apps:
            print(measure_link(name, argv, link_size, megabits, arguments.link_seconds),
                  flush=True)


if __name__ == "__main__":
    main()
