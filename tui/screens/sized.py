"""Screens laid out for the terminal's size as it is, not as it was.

The app hands each resize it lays out to every screen on its stack, the main screen and
each dialog over it, and each screen queues it behind its own messages. Behind a storm of
resizes a screen's queue held hundreds, each a whole layout, and keys waited minutes
behind them. A screen skips a resize the terminal has since left (tui/behind.py's
``outdated``): the one to its size now is still on its way.
"""

from __future__ import annotations

from typing import TypeVar

from textual import events
from textual.screen import Screen

from biceps.tui.behind import outdated

Result = TypeVar("Result")


class LatestSize(Screen[Result]):
    """A screen that lays itself out only for the terminal's latest size."""

    async def on_event(self, event: events.Event) -> None:
        if isinstance(event, events.Resize) and outdated(self.app, event.size):
            return
        await super().on_event(event)
