"""Tens of thousands of random keys, pastes, bytes that are not UTF-8, escape sequences,
mouse reports and resizes, in bursts: the app never ends on an error, and the model it is
left with keeps its rules (its volume, its length and the elbow's angle agree).

The bursts are bytes, as a terminal sends them, read the way the app reads its terminal
(with tui/terminal_input.py's decoder and parser, Textual's made lenient) and handed to the
app's driver as events, so an invalid byte or a broken sequence reaches the app as it would
for real. Hypothesis draws the bursts: each example is one run of the app on a copy of the
bundled model, of 20 bursts of 150 inputs; the examples are shared out among a few tests, so
that the test run's workers take them side by side. Each burst is drawn as a seed that a generator
turns into its inputs, as tests/engine/test_muscle.py draws lengths: hypothesis can then
draw, and shrink, a run of thousands of inputs, which it could not draw one by one.
"""

import asyncio
import io
import math
import random
import shutil
import time

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from rich.console import Console
from textual import events

from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.tui import app as app_module
from biceps.tui.app import BicepsApp
from biceps.tui.parse import parse_path
from biceps.tui.terminal_input import decode_leniently, lenient_parser
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.stats import Stats

EVENTS = 20_000  # at least, over all the examples
EXAMPLES = 6
PARTS = 3  # tests the examples are shared out among
BURSTS = 20  # a burst (and at times a resize), then a wait for the app to take it, ...
BURST = 150  # inputs in a burst (each a key, a paste, a sequence, or a few random bytes)

ESC = b"\x1b"
# What a person does with this app, as the bytes a terminal sends for it. Quitting is left
# out (and a quit asked for otherwise, from the palette say, does not end the run), so that
# every run lasts.
KEYS = [
    b"c", b"C", b"x", b"X", b"c", b"x",  # the keys the model changes with, twice as likely
    ESC + b"[A", ESC + b"[B", ESC + b"[C", ESC + b"[D", ESC + b"[1;2A", ESC + b"[1;2D",
    b"[", b"]", b"w", b"a", b"s", b"d", b"+", b"-", b"=", b"j", b"l", b"i", b"k", b"u", b"o",
    b"r", b"g", b"m", b"e", b"?", ESC + b"OP", b"\x13", b"\x04", b"\x0f", b"\x10", b"\t",
    ESC + b"[Z", b"\r", b"\r", ESC, ESC, b"\x7f", ESC + b"[3~", ESC + b"[2~", b"n", b"/",
    ESC + b"[5~", ESC + b"[6~", ESC + b"[H", ESC + b"[F", b"y", b"0", b"1", b"5", b".",
    b"e", b"-", b"\x03", b" ", b"\x1a", ESC + b"[I", ESC + b"[O",
    b">", b"<", b"}", b"{", b"b",  # the muscles asked to work, a weight, their colours
]
NOT_UTF8 = [b"\xff", b"\xc3a", b"\xe2\x82", b"\x80", b"\xf0\x9f\x92", b"\xed\xa0\x80"]


# What a paste may hold: text, control characters, characters beyond the BMP, and lone
# surrogates, which come out as bytes that are not UTF-8.
PASTED = "aé/ .~\t\n\r\x00\x07\x1b[]{}\x7f\x9b\u202e\U0001f4aa\udcff"


def _inputs(seed: int) -> list[bytes]:
    """The BURST inputs the generator seeded with ``seed`` makes: mostly keys, and of
    everything else a terminal may send a little."""
    rng = random.Random(seed)
    made = []
    for _ in range(BURST):
        kind = rng.random()
        if kind < 0.70:
            made.append(rng.choice(KEYS))
        elif kind < 0.76:
            made.append(rng.choice(NOT_UTF8))
        elif kind < 0.82:  # anything at all
            made.append(rng.randbytes(rng.randint(1, 6)))
        elif kind < 0.88:  # a sequence broken off, or nonsense after its start
            made.append(ESC + b"[" + rng.randbytes(rng.randint(0, 6)))
        elif kind < 0.96:  # the mouse: buttons, moves, drags and the wheel
            button = rng.choice([0, 1, 2, 32, 34, 64, 65])
            x, y = rng.randint(1, 130), rng.randint(1, 45)
            made.append(ESC + f"[<{button};{x};{y}{rng.choice('Mm')}".encode())
        else:
            text = "".join(rng.choice(PASTED) for _ in range(rng.randint(0, 30)))
            made.append(ESC + b"[200~" + text.encode("utf-8", "surrogatepass") + ESC + b"[201~")
    return made


resize = st.tuples(st.integers(10, 120), st.integers(4, 36))  # the terminal's new size
no_resize = st.none()
bursts = st.lists(st.tuples(st.integers(0, 2**32 - 1),
                            st.one_of(no_resize, no_resize, no_resize, no_resize, resize)),
                  min_size=BURSTS, max_size=BURSTS)


@pytest.mark.parametrize("part", range(PARTS))
def test_no_input_ends_the_app_and_the_model_keeps_its_rules(tmp_path, monkeypatch, part):
    monkeypatch.chdir(tmp_path)  # exports and saves land here
    # Whatever name is typed, the file goes in this folder.
    monkeypatch.setattr(app_module, "parse_path", lambda text: tmp_path / parse_path(text).name)
    delivered = []

    # No shrinking: each run takes seconds, and shrinking one takes many minutes, so a
    # failure is reported as found (its seeds reproduce it, and the example database
    # replays it first next time).
    @settings(max_examples=EXAMPLES // PARTS, deadline=None,
              phases=[Phase.explicit, Phase.reuse, Phase.generate],
              suppress_health_check=[HealthCheck.too_slow])
    @given(bursts)
    def run(bursts):
        delivered.append(asyncio.run(_drive(tmp_path, bursts)))

    run()
    print(f"{sum(delivered):,} events in {len(delivered)} runs")
    assert sum(delivered) >= EVENTS / PARTS


DEEPEST = 6  # the main screen, the help, a palette, a dialog and its question, a palette


async def _drive(folder, bursts) -> int:
    path = folder / "model.toml"
    shutil.copy(DEFAULT_CONFIG, path)
    app = BicepsApp(load_config(path))
    quits = []
    app.exit = lambda *args, **kwargs: quits.append(args)  # a quit is counted, not done
    app._export_size = "64x36"  # not 1920x1080: exports are many, and each is drawn whole
    decode, parser, count = decode_leniently(), lenient_parser()(), 0
    async with app.run_test(size=(80, 24)) as pilot:
        for seed, size in bursts:
            for data in _inputs(seed):
                text = decode(data)
                if not text:  # the start of a character, kept for the next read
                    continue  # (as the driver does: an empty feed would end the parser)
                for event in parser.feed(text):
                    if not isinstance(event, events.Key) or event.key not in ("q", "ctrl+q"):
                        app._driver.process_message(event)
                        count += 1
            if size is not None:
                await pilot.resize_terminal(*size)
            await _taken(app)
            assert app.failure is None
            # One dialog at a time (of the app's own, which may ask a second question), and
            # the help and a palette each at most once, under or over it: a stack that grew
            # with the keys ended, at about 45 screens, in Textual's RecursionError.
            assert len(app.screen_stack) <= DEEPEST, app.screen_stack
        await pilot.resize_terminal(80, 24)
        await _taken(app)
        await pilot.pause()
        await _check_model(app)
    assert app.failure is None and app.return_code in (None, 0)
    return count


async def _taken(app: BicepsApp) -> None:
    """Wait until the app and every widget have handled what they were sent: quicker than
    the pilot's pause, which waits for the process to be idle (the picture's thread too).
    However long a loaded machine takes (given up after five seconds, a burst's last edits
    were still queued when the model was checked against the numbers shown), but not for
    ever: an app that never stops sending itself messages is a fault (the footer did)."""
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        nodes = [app, *app.screen_stack, *app.screen.walk_children()]
        if not any(node._message_queue.qsize() for node in nodes):
            return
        await asyncio.sleep(0.001)
    raise AssertionError("the app has not taken its input in two minutes")


async def _check_model(app: BicepsApp) -> None:
    arm = app.scene.arm
    muscle, skeleton = arm.muscle, arm.skeleton
    assert muscle.volume_error < 1e-12
    low, high = arm.length_range()
    assert low - 1e-9 <= arm.length <= high + 1e-9
    assert skeleton.min_flexion - 1e-9 <= arm.flexion <= skeleton.max_flexion + 1e-9
    assert math.isclose(skeleton.length_at(arm.flexion), arm.length, rel_tol=1e-9)
    assert muscle.radii.min() > 0
    # The numbers follow a burst once it is handled (MainScreen._show_numbers, put on the
    # app's queue by the last edit), which may be after the queues were last seen empty:
    # given time to come, and wrong if they never do.
    deadline = time.monotonic() + 60
    while (shown := _numbers_shown(app)) != _numbers_of(app) and time.monotonic() < deadline:
        await asyncio.sleep(0.01)
    assert shown == _numbers_of(app)


def _numbers_of(app: BicepsApp) -> tuple[str, int, tuple[str, str]]:
    """The length, node count and last node's place and radius the model has."""
    muscle = app.scene.arm.muscle
    return (f"length {app.scene.arm.length:.2f} cm", muscle.node_count,
            (f"{app.scene.arm.length:.2f}", f"{muscle.radii[-1]:.3f}"))


def _numbers_shown(app: BicepsApp) -> tuple[str, int, tuple[str, str]]:
    """The same as the side panel and the node table show them (the length's row with its
    spaces closed up: with the forces shown at 80x24 the numbers are brief, their first
    column narrower)."""
    main = app.screen_stack[0]
    shown = Console(width=40, file=io.StringIO(), record=True)
    shown.print(main.query_one(Stats).content)
    length = next((" ".join(line.split()) for line in shown.export_text().splitlines()
                   if line.strip().startswith("length ")), "")
    table = main.query_one(NodeTable)
    last = table.row(table.row_count - 1)[1:3] if table.row_count else ()
    return length, table.row_count, last
