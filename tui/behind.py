"""Input the app is too far behind to answer is left out, and the user told how much.

Textual queues everything a terminal sends and answers it in order. A person never types
faster than the app answers; a flood can (a stuck key over a slow link, a paste into a
terminal without bracketed paste, a cat of a binary file, a fuzzer): a key that opens a
dialog costs a layout, and behind a minute of flood the queue held minutes of work, so a
`q` typed afterwards was answered minutes late. So once an input is found to have waited
longer than :data:`PATIENCE`, everything queued by then is left out, as a terminal
program flushes its type-ahead (curses' ``flushinp``): the queue drains at once, and the
next key is answered as it comes. The count left out is reported once the flood ends.

Resizes are not left out but skipped when the terminal has been resized again since
(:func:`outdated`): another is on its way, and each costs a layout of every screen.
"""

from __future__ import annotations

import shutil
from time import monotonic
from typing import Protocol

# Many times the app's answer to a key (a tenth of a second), so that a person's type-ahead
# is kept; short enough that after a flood the app is soon itself again.
PATIENCE = 2.0


class Backlog:
    """Which queued input to answer: none that was queued when an input was found to have
    waited over :data:`PATIENCE` seconds."""

    def __init__(self, patience: float = PATIENCE) -> None:
        self.patience = patience
        self.left_out = 0  # keys, clicks and pastes, since the last report
        # The latest focus change left out (the terminal's window gained the focus: True,
        # lost it: False), for the app to catch up with once the flood is over.
        self.focus: bool | None = None
        self._flushed_until = float("-inf")  # input made before this is left out

    def answer(self, made: float, *, focus: bool | None = None,
               now: float | None = None) -> bool:
        """Whether to answer an input made at ``made`` (monotonic seconds, as Textual's
        ``Message.time``) and answered ``now``; if not, it is counted, or if it is a change
        of focus (``focus`` not None), kept as the latest one."""
        now = monotonic() if now is None else now
        if now - made > self.patience:
            self._flushed_until = now  # all queued so far: made by now
        elif made > self._flushed_until:
            return True
        if focus is None:
            self.left_out += 1
        else:
            self.focus = focus
        return False

    def report(self) -> str | None:
        """What was left out since the last report, in words, or None if nothing was."""
        if not self.left_out:
            return None
        count, self.left_out = self.left_out, 0
        return (f"Input came faster than the app could answer: {count:,} keys, clicks and "
                f"pastes queued over {self.patience:g} s were left out.")


class Sized(Protocol):
    """The app, as far as :func:`outdated` asks it."""

    is_headless: bool
    is_web: bool


def outdated(app: Sized, size: tuple[int, int]) -> bool:
    """Whether the terminal has been resized again since a resize to ``size`` (columns,
    rows): then another resize is on its way, and laying out for this one is wasted (a
    window dragged by its corner sends dozens a second, a storm hundreds, each a layout of
    every screen)."""
    if app.is_headless or app.is_web:  # sized by their driver, not by a terminal
        return False
    return tuple(size) != tuple(shutil.get_terminal_size())
