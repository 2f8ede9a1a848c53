"""The app driven by a pilot."""

from __future__ import annotations

from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from typing import AsyncIterator

import pytest
from textual.notifications import Notification, Notify
from textual.pilot import Pilot
from textual.screen import ModalScreen

from biceps.engine.config import Config
from biceps.tui.app import BicepsApp
from biceps.tui.screens.prompt import Prompt
from biceps.tui.widgets.viewport import Viewport
from waiting import until


def screen_rows(app: BicepsApp) -> list[str]:
    """The text of every row of the screen in front, as the terminal shows it."""
    return [strip.text for strip in app.screen._compositor.render_strips()]


@dataclass
class Session:
    """A running app, the pilot driving it and every notification it has shown."""

    app: BicepsApp
    pilot: Pilot
    notes: list[Notification] = field(default_factory=list)

    @property
    def warnings(self) -> list[str]:
        return [note.message for note in self.notes if note.severity != "information"]

    async def run_command(self, text: str) -> None:
        """Type ``text`` into the command palette and run the first command it finds."""
        from textual.command import CommandList

        await self.pilot.press("ctrl+p", *text)
        commands = self.app.screen.query_one(CommandList)
        # The palette searches in the background.
        await until(self.pilot, lambda: commands.option_count, f"a command for {text!r}")
        await self.pilot.press("enter")
        await self.settle()

    async def settle(self) -> None:
        """Wait until a dialog has checked what was typed in it, what the dialogs do (a save,
        say) is done or asks a question, the picture shows the latest scene and every export
        is written."""
        app, pilot = self.app, self.pilot
        await pilot.pause()
        await until(pilot, lambda: not (isinstance(app.screen, Prompt) and app.screen.checking))
        await until(pilot, lambda: isinstance(app.screen, ModalScreen) or not any(
            worker.group == "dialogs" and not worker.is_finished for worker in app.workers))
        exports = [worker for worker in app.workers if worker.group == "export"]
        if exports:  # an empty list would mean every worker, the render loop among them
            await app.workers.wait_for_complete(exports)
        viewport = app.screen_stack[0].query_one(Viewport)
        await until(pilot, lambda: viewport.up_to_date, "the picture caught up with the scene")
        await pilot.pause()


@pytest.fixture
def biceps(config: Config):
    """Start the app on ``config``: ``async with biceps() as session: ...``."""

    @asynccontextmanager
    async def start(
        size: tuple[int, int] = (100, 30), on: Config = config
    ) -> AsyncIterator[Session]:
        app = BicepsApp(on)
        notes: list[Notification] = []

        def record(message: object) -> None:
            if isinstance(message, Notify):
                notes.append(message.notification)

        async with app.run_test(size=size, message_hook=record) as pilot:
            session = Session(app, pilot, notes)
            await session.settle()
            yield session

    return start

