"""What Textual itself costs to redraw a terminal-sized picture at each key: the floor under
the app's CPU per frame.

    .venv/bin/python benchmarks/textual_floor.py [--size 200x60] [--seconds 4] [--runs 3]
                                                 [--segments 12]

A Textual app of one Line-API widget over the whole screen, with nothing else on it,
measured as ``benchmarks/app_profile.py`` measures the app (the right arrow at 120 presses a
second in a pseudo-terminal, CPU per thread from /proc, medians of ``--runs``). Each key
switches the widget between two pictures made beforehand, lines of ``--segments`` coloured
segments each (about what the biceps' lines have), and refreshes it whole; its first line
is the caption by which the harness counts frames. Nothing is rendered or encoded: what is
left is Textual's own work for a key and a frame (events, bindings, the compositor, the
segments' codes, the driver), and the process's other threads.

``--prerendered`` gives the lines their terminal text beforehand, as the app's viewport
does (``tui/prerendered.py``), and frames them as the viewport does (no styling of
Textual's per line).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from app_profile import measure_threads, report
from tui_pty import FLOOD

from biceps.tui.changes import TURN_STEP


def run_floor_app(segments: int, prerendered: bool) -> None:
    from rich.color import Color
    from rich.segment import Segment
    from rich.style import Style
    from textual.app import App, ComposeResult
    from textual.geometry import Region
    from textual.strip import Strip
    from textual.widget import Widget

    from biceps.tui.prerendered import RESET, codes
    from biceps.tui.textual_private import PrerenderedStrip

    def line(y: int, width: int, phase: int) -> Strip:
        run = max(width // segments, 1)
        styles = [Style.from_color(Color.from_rgb((7 * x + y + phase) % 256, 60, 90),
                                   Color.from_rgb(20, (3 * x + phase) % 256, 40))
                  for x in range(0, width, run)]
        parts = [Segment("▀" * min(run, width - x), style)
                 for x, style in zip(range(0, width, run), styles)]
        if not prerendered:
            return Strip(parts, width)
        text = "".join(f"{codes(part.style, 'truecolor')}{part.text}{RESET}" for part in parts)
        return PrerenderedStrip(lambda: parts, width, text, "truecolor")

    class Picture(Widget):
        DEFAULT_CSS = "Picture { width: 1fr; height: 1fr; }"

        def __init__(self) -> None:
            super().__init__()
            self.turns = 0
            self.pictures: dict[int, list[Strip]] = {}

        def render_line(self, y: int) -> Strip:
            width, height = self.size
            if y == 0:
                return Strip([Segment(f"yaw {self.turns * TURN_STEP:g}°")]).extend_cell_length(
                    width)
            phase = self.turns % 2
            picture = self.pictures.get(phase)
            if picture is None or len(picture) != height or picture[0].cell_length != width:
                picture = self.pictures[phase] = [line(y, width, phase) for y in range(height)]
            return picture[y]

        def render_lines(self, crop: Region) -> list[Strip]:
            if not prerendered:
                return super().render_lines(crop)
            return [self.render_line(y).crop(*crop.column_span) for y in crop.line_range]

    class FloorApp(App[None]):
        BINDINGS = [("right", "turn", "Turn")]

        def compose(self) -> ComposeResult:
            yield Picture()

        def action_turn(self) -> None:
            picture = self.query_one(Picture)
            picture.turns += 1
            picture.refresh()

    FloorApp().run()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--size", default="200x60")
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--segments", type=int, default=12, help="coloured segments a line")
    parser.add_argument("--prerendered", action="store_true",
                        help="lines that carry their text, framed as the viewport does")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--output", type=Path, help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.child:
        # Behind app_profile's signals too, which ask for the thread names.
        from app_profile import listen

        listen(arguments.output)
        run_floor_app(arguments.segments, arguments.prerendered)
        return
    size = tuple(map(int, arguments.size.split("x")))
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "profile.pstat"
        argv = [sys.executable, str(Path(__file__).resolve()), "--child", "--output",
                str(output), "--segments", str(arguments.segments)]
        if arguments.prerendered:
            argv.append("--prerendered")
        runs, loads = [], []
        for _ in range(arguments.runs):
            runs.append(measure_threads(argv, size, arguments.seconds, output))
            loads.append(os.getloadavg()[0])
        print(f"one widget of {size[0]}x{size[1]} cells, {arguments.segments} segments a "
              f"line{', prerendered' if arguments.prerendered else ''}, key at {FLOOD:g}/s, "
              f"load {min(loads):.2f} to {max(loads):.2f}")
        report("textual", runs)


if __name__ == "__main__":
    main()
