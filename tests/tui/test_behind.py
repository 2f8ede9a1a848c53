"""Input the app is too far behind to answer is left out (tui/behind.py)."""

import os
import shutil

from textual import events
from textual.geometry import Size
from textual.message import Message
from textual.screen import Screen

from biceps.tui.app import BicepsApp
from biceps.tui.behind import Backlog
from biceps.tui.screens.help import HelpScreen
from biceps.tui.screens.main import MainScreen
from waiting import until


def test_input_answered_while_the_app_keeps_up():
    backlog = Backlog(patience=2.0)
    assert all(backlog.answer(made, now=made + 1.9) for made in range(100))
    assert backlog.report() is None


def test_once_an_input_waited_too_long_all_queued_by_then_is_left_out():
    backlog = Backlog(patience=2.0)
    assert not backlog.answer(0.0, now=2.5)  # waited 2.5 s: the app is behind
    assert not backlog.answer(1.0, now=2.6)  # queued before: left out, though only 1.6 s
    assert not backlog.answer(2.5, now=2.7)  # queued by the time the app was found behind
    assert backlog.answer(2.51, now=2.7)  # after: answered
    assert backlog.report() == ("Input came faster than the app could answer: 3 keys, "
                                "clicks and pastes queued over 2 s were left out.")
    assert backlog.report() is None  # each counted once


def test_of_the_focus_changes_left_out_the_latest_is_kept_and_not_counted():
    backlog = Backlog(patience=2.0)
    assert not backlog.answer(0.0, focus=False, now=3.0)
    assert not backlog.answer(0.1, focus=True, now=3.0)
    assert backlog.focus is True
    assert backlog.report() is None


async def test_a_flood_is_left_out_the_user_told_and_the_next_key_answered(config,
                                                                          monkeypatch):
    app = BicepsApp(config)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, MainScreen))
        monkeypatch.setattr(BicepsApp, "is_headless", property(lambda app: False))
        told = []
        notify = app.notify
        monkeypatch.setattr(app, "notify", lambda message, **options: (
            told.append(message), notify(message, **options))[1])
        flood = []
        for _ in range(2_000):  # what a flood leaves in the queue: old, and opening dialogs
            for key in ("question_mark", "e", "ctrl+o", "c"):
                event = events.Key(key, None)
                event.time -= 60.0
                flood.append(event)
        focused = app.app_focus
        change = events.AppBlur() if focused else events.AppFocus()
        change.time -= 60.0
        for event in (*flood, change):
            app.post_message(event)
        await until(pilot, lambda: any("8,000 keys" in message for message in told))
        assert isinstance(app.screen, MainScreen)  # none of the flood's dialogs open
        assert app.app_focus is not focused  # left out, but caught up with
        await pilot.press("p")  # answered at once
        assert app.screen.query_one("#plots").display


async def test_a_resize_the_terminal_has_since_left_is_not_laid_out(config, monkeypatch):
    # A window dragged by its corner sends dozens of resizes a second, and a storm of
    # them left minutes of layouts queued: only the terminal's size now is laid out.
    app = BicepsApp(config)
    async with app.run_test(size=(100, 30)) as pilot:
        monkeypatch.setattr(BicepsApp, "is_headless", property(lambda app: False))
        monkeypatch.setattr(shutil, "get_terminal_size",
                            lambda *fallback: os.terminal_size((120, 40)))
        for width in range(60, 120):
            app.post_message(events.Resize(Size(width, 30), Size(width, 30)))
        app.post_message(events.Resize(Size(120, 40), Size(120, 40)))
        await until(pilot, lambda: app.size == (120, 40))
        seen = set()
        monkeypatch.setattr(MainScreen, "on_resize",
                            lambda screen, event: seen.add(tuple(event.size)))
        app.post_message(events.Resize(Size(80, 24), Size(80, 24)))  # gone by now
        app.post_message(events.Resize(Size(120, 40), Size(120, 40)))
        await until(pilot, lambda: seen)
        assert seen == {(120, 40)} and app.size == (120, 40)


class Between(Message):
    """A message that nothing handles."""


async def test_a_screen_skips_a_resize_the_terminal_has_since_left(config, monkeypatch):
    # The app hands each resize it lays out to every screen on its stack, and each queues
    # it behind its own messages: behind a storm, a dialog and the main screen under it held
    # hundreds of layouts each. A screen lays out only the terminal's size now.
    app = BicepsApp(config)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("question_mark")
        await until(pilot, lambda: isinstance(app.screen, HelpScreen))
        monkeypatch.setattr(BicepsApp, "is_headless", property(lambda app: False))
        monkeypatch.setattr(shutil, "get_terminal_size",
                            lambda *fallback: os.terminal_size((100, 30)))
        seen = []
        monkeypatch.setattr(Screen, "_on_resize", lambda screen, event: seen.append(
            (type(screen).__name__, tuple(event.size))))
        for screen in app.screen_stack:
            for width in range(60, 100):
                screen.post_message(events.Resize(Size(width, 30), Size(width, 30)))
                screen.post_message(Between())  # else a resize replaces the one before
            screen.post_message(events.Resize(Size(100, 30), Size(100, 30)))
        await until(pilot, lambda: len(seen) >= 2)
        await pilot.pause()
        assert sorted(seen) == [("HelpScreen", (100, 30)), ("MainScreen", (100, 30))]
