"""Flow control: the next frame waits for the terminal to answer, or for the cap; it is
drawn meanwhile."""

from __future__ import annotations

import asyncio

import pytest
from click.testing import CliRunner
from textual import events
from textual.constants import MAX_FPS

import biceps.tui.pacing
import biceps.tui.rendering
from biceps.cli import main
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.app import AppProcess, BicepsApp
from biceps.tui.changes import TURN_STEP
from biceps.tui.pacing import LoopTimer, Pacer, cursor_question
from biceps.tui.widgets.viewport import Viewport
from waiting import until


class Timers:
    """Timers that fire only when told to, and a clock that moves only when told to."""

    def __init__(self) -> None:
        self.now = 100.0
        self.pending: list[tuple[float, object, list[bool]]] = []

    def set_timer(self, delay, callback):
        stopped = [False]
        self.pending.append((delay, callback, stopped))

        class Handle:
            def stop(self) -> None:
                stopped[0] = True

        return Handle()

    def fire(self) -> list[float]:
        """Run every timer not stopped; return their delays."""
        pending, self.pending = self.pending, []
        fired = [(delay, callback) for delay, callback, stopped in pending if not stopped[0]]
        for _, callback in fired:
            callback()
        return [delay for delay, _ in fired]


@pytest.fixture
def timers() -> Timers:
    return Timers()


def _pacer(timers: Timers, answers: bool = True, fps: float | None = None):
    asked: list[int] = []

    def ask(column: int) -> bool:
        asked.append(column)
        return answers

    pacer = Pacer(ask, timers.set_timer, fps, clock=lambda: timers.now)
    return pacer, asked


async def test_a_loop_timer_calls_back_when_its_time_is_up_unless_stopped():
    called = []
    LoopTimer(0.01, lambda: called.append("kept"))
    LoopTimer(0.01, lambda: called.append("stopped")).stop()
    await asyncio.sleep(0.05)
    assert called == ["kept"]


def test_the_question_moves_the_cursor_to_its_column_and_back():
    assert cursor_question(2) == "\x1b7\x1b[1;3H\x1b[6n\x1b8"


def test_the_next_frame_waits_for_the_answer(timers):
    pacer, asked = _pacer(timers)
    released = []
    pacer.after_frame(lambda: released.append(1))
    assert len(asked) == 1 and released == []
    pacer.answered(asked[0] + 1, 0)  # another question's answer
    pacer.answered(asked[0], 3)  # not one of the pacer's rows
    assert released == []
    pacer.answered(asked[0], 0)
    assert released == [1]
    assert pacer.answers is True


def test_each_question_has_its_own_column(timers):
    pacer, asked = _pacer(timers)
    for _ in range(3):
        pacer.after_frame(lambda: None)
        pacer.answered(asked[-1], 0)
    assert len(set(asked)) == 3


def test_an_answer_after_giving_up_does_not_release_the_next_frame(timers):
    pacer, asked = _pacer(timers)
    pacer.after_frame(lambda: None)
    pacer.answered(asked[-1], 0)  # the terminal answers...
    released = []
    pacer.after_frame(lambda: released.append("late"))
    assert timers.fire() == [biceps.tui.pacing.ANSWER]  # ...but not this time, for long
    assert released == ["late"]
    pacer.after_frame(lambda: released.append("next"))
    pacer.answered(asked[-2], 0)  # the answer to the question given up on
    assert released == ["late"]
    pacer.answered(asked[-1], 0)
    assert released == ["late", "next"]


def test_a_terminal_that_misses_an_answer_has_a_second_for_the_next(timers):
    pacer, asked = _pacer(timers)
    pacer.after_frame(lambda: None)
    pacer.answered(asked[-1], 0)
    pacer.after_frame(lambda: None)
    assert timers.fire() == [biceps.tui.pacing.ANSWER]
    pacer.after_frame(lambda: None)
    assert timers.fire() == [biceps.tui.pacing.FIRST_ANSWER]
    assert pacer.answers is False


def test_a_late_answer_shows_the_terminal_answers_after_all(timers):
    pacer, asked = _pacer(timers)
    released = []
    pacer.after_frame(lambda: released.append(1))
    timers.fire()
    pacer.after_frame(lambda: released.append(2))
    assert released == [1, 2] and len(asked) == 1  # not asked: taken not to answer
    pacer.answered(asked[0], 0)  # the first answer, at last
    pacer.after_frame(lambda: released.append(3))
    assert len(asked) == 2 and released == [1, 2]
    pacer.answered(asked[1], 0)
    assert released == [1, 2, 3]


def test_a_terminal_that_never_answers_gets_a_second_then_frames_follow_at_once(timers):
    pacer, asked = _pacer(timers)
    released = []
    pacer.after_frame(lambda: released.append(1))
    assert timers.fire() == [biceps.tui.pacing.FIRST_ANSWER]
    assert released == [1] and pacer.answers is False
    pacer.after_frame(lambda: released.append(2))
    assert released == [1, 2]
    assert len(asked) == 1  # asked no more


def test_without_a_terminal_frames_follow_at_once(timers):
    pacer, asked = _pacer(timers, answers=False)
    released = []
    pacer.after_frame(lambda: released.append(1))
    assert released == [1] and timers.pending == []


def test_the_cap_spaces_the_frames(timers):
    pacer, _ = _pacer(timers, answers=False, fps=20)
    released = []
    pacer.after_frame(lambda: released.append(1))
    assert released == [1]
    timers.now += 0.01
    pacer.after_frame(lambda: released.append(2))
    assert released == [1]
    assert timers.fire() == [pytest.approx(0.04)]
    assert released == [1, 2]
    timers.now += 0.2  # long after: at once
    pacer.after_frame(lambda: released.append(3))
    assert released == [1, 2, 3]


def test_the_cap_applies_after_the_answer_too(timers):
    pacer, asked = _pacer(timers, fps=10)
    released = []
    pacer.after_frame(lambda: released.append(1))
    pacer.answered(asked[-1], 0)
    pacer.after_frame(lambda: released.append(2))
    timers.now += 0.03
    pacer.answered(asked[-1], 0)
    assert released == [1]
    assert timers.fire() == [pytest.approx(0.07)]
    assert released == [1, 2]


# The gate in the app: the render thread hands the next frame over only once the terminal
# answers, and draws it meanwhile.


@pytest.fixture
def patient(monkeypatch) -> None:
    """The pacer waits for the stand-in terminal's answers as long as a test may take to
    give them: under load, seconds can pass between a question and the test's answer, and
    a pacer that gave up would take the terminal not to answer and ask no more."""
    monkeypatch.setattr(biceps.tui.pacing, "FIRST_ANSWER", 600.0)
    monkeypatch.setattr(biceps.tui.pacing, "ANSWER", 600.0)


class Terminal:
    """Stands in for a terminal behind a headless app: records questions, answers on cue."""

    def __init__(self, app: BicepsApp) -> None:
        self.app = app
        self.questions: list[int] = []
        self.answered = 0
        app.pacer = Pacer(self._ask, app.set_timer)

    def _ask(self, column: int) -> bool:
        self.questions.append(column)
        return True

    def answer(self) -> None:
        """Answer the last question."""
        self.answered = len(self.questions)
        self.app.post_message(events.CursorPosition(x=self.questions[-1], y=0))

    async def catch_up(self, pilot, viewport: Viewport) -> None:
        """Answer every question until the picture shows the latest scene."""
        for _ in range(1000):
            if len(self.questions) > self.answered:
                self.answer()
            elif viewport.up_to_date:
                return
            await pilot.pause(0.01)
        raise AssertionError("the picture never caught up")


async def _a_while(pilot) -> None:
    for _ in range(20):
        await pilot.pause(0.01)


async def test_no_frame_is_shown_until_the_terminal_has_taken_the_last(private_path, config,
                                                                      patient):
    app = BicepsApp(config)
    terminal = Terminal(app)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport = app.screen.query_one(Viewport)
        await terminal.catch_up(pilot, viewport)
        await pilot.press("right")  # a frame for this, then a question
        await until(pilot, lambda: len(terminal.questions) > terminal.answered)
        asked, shown = len(terminal.questions), viewport.border_title
        await pilot.press("right", "right")
        await _a_while(pilot)
        assert not viewport.up_to_date  # the scene has moved on, the picture waits
        assert viewport.border_title == shown
        assert len(terminal.questions) == asked
        terminal.answer()
        await until(pilot, lambda: viewport.up_to_date)
        assert viewport.border_title.startswith(f"yaw {app.scene.view.yaw:g}°")


class Draws:
    """Counts the frames the app's renderers draw."""

    def __init__(self, monkeypatch) -> None:
        self.count = 0
        render = SceneRenderer.render

        def counted(renderer, *arguments, **options):
            self.count += 1
            return render(renderer, *arguments, **options)

        monkeypatch.setattr(SceneRenderer, "render", counted)


async def _waiting_for_an_answer(app, pilot, terminal: Terminal) -> Viewport:
    """Answer the terminal's questions until the picture on screen is that of the latest
    scene and the question after it is out, unanswered."""
    viewport = app.screen.query_one(Viewport)
    for _ in range(1000):
        asked = len(terminal.questions) > terminal.answered
        if asked and viewport.up_to_date:
            return viewport  # (the question after an earlier frame would hold this one back)
        if asked:
            terminal.answer()
        await pilot.pause(0.01)
    raise AssertionError("the picture never caught up")


async def test_the_next_frame_is_drawn_while_the_terminal_takes_the_last(private_path, config,
                                                                       monkeypatch, patient):
    draws = Draws(monkeypatch)
    app = BicepsApp(config)
    terminal = Terminal(app)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport = await _waiting_for_an_answer(app, pilot, terminal)
        shown, drawn = viewport.border_title, draws.count
        await pilot.press("right")
        await until(pilot, lambda: draws.count == drawn + 1)  # drawn ahead...
        await _a_while(pilot)
        assert viewport.border_title == shown  # ...and kept until the terminal answers
        terminal.answer()
        await until(pilot, lambda: viewport.up_to_date)
        assert viewport.border_title.startswith(f"yaw {app.scene.view.yaw:g}°")
        assert draws.count == drawn + 1  # shown as drawn, not drawn again


@pytest.mark.parametrize("stale_after, first_shown", [(60.0, 1), (0.0, 2)])
async def test_a_frame_drawn_ahead_too_long_ago_is_drawn_again_from_the_newest_scene(
        private_path, config, monkeypatch, patient, stale_after, first_shown):
    # Over a slow link the answer takes a while: by then the frame drawn ahead is old, and
    # if the keys have moved on since, it would show them that late.
    monkeypatch.setattr(biceps.tui.rendering, "STALE_AFTER", stale_after)
    draws = Draws(monkeypatch)
    app = BicepsApp(config)
    terminal = Terminal(app)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport = await _waiting_for_an_answer(app, pilot, terminal)
        yaw, drawn = app.scene.view.yaw, draws.count
        await pilot.press("right")
        await until(pilot, lambda: draws.count == drawn + 1)
        await pilot.press("right")  # a newer scene, waiting
        terminal.answer()
        await until(pilot, lambda: len(terminal.questions) > terminal.answered)
        assert viewport.border_title.startswith(f"yaw {yaw + first_shown * TURN_STEP:g}°")
        assert viewport.up_to_date == (first_shown == 2)


async def test_a_terminal_that_never_answers_still_gets_every_frame(config, monkeypatch):
    monkeypatch.setattr(biceps.tui.pacing, "FIRST_ANSWER", 0.05)
    app = BicepsApp(config)
    terminal = Terminal(app)
    async with app.run_test(size=(100, 30)) as pilot:
        viewport = app.screen.query_one(Viewport)
        await until(pilot, lambda: app.pacer.answers is False)
        for _ in range(3):
            await pilot.press("right")
            await until(pilot, lambda: viewport.up_to_date)
        assert len(terminal.questions) == 1


@pytest.mark.parametrize("fps, cap", [(12, 12), (None, MAX_FPS), (10 * MAX_FPS, MAX_FPS)])
def test_the_app_takes_a_frame_rate_cap_up_to_textual_s_limit(config, fps, cap):
    # Textual paints at most MAX_FPS times a second (TEXTUAL_FPS), but the viewport writes
    # most frames itself: the pacer keeps them to that too.
    assert BicepsApp(config, fps=fps).pacer.fps == cap


def test_the_command_line_passes_the_cap_to_the_app(monkeypatch):
    runs = []
    monkeypatch.setattr("biceps.tui.app.run_app", lambda config, **options: runs.append(options))
    monkeypatch.setattr("biceps.cli._check_terminal", lambda: None)  # the runner has none
    result = CliRunner().invoke(main, ["app", "--fps", "30"])
    assert result.exit_code == 0, result.output
    # Not the command's own process (a test's): nothing is forked, no pool or heap is set up.
    assert runs == [{"colors": "auto", "fps": 30, "graphics": None, "pixel_scale": 1.0,
                     "process": AppProcess()}]
    assert CliRunner().invoke(main, ["app", "--fps", "0"]).exit_code == 2
