"""When the next frame may be made: once the terminal has taken the last one, and no sooner
than the frame-rate cap allows.

Textual's writer thread takes many whole frames ahead of the terminal, so over a slow link
a picture redrawn on every key falls seconds behind the keys. Instead, after each frame the
app asks the terminal where its cursor is (DSR, ``CSI 6 n``). A terminal answers (CPR) only
once it has read everything written before the question, so the answer says the frame has
arrived, and only then is the next one made: a slow link lowers the frame rate instead of
building a backlog. Keys are handled at once all along; only pictures wait, and each one
shows the latest state.

Each question is numbered by the column it puts the cursor in (saved and restored around
it), so that an answer arriving after its question was given up on is not taken for the
answer to a later one.

Nothing waits for ever. A terminal that has answered before is waited for up to three
seconds, as a big frame over a slow link may take a while; one that has not (or has just
missed an answer) for a second. After that the terminal is taken not to answer, and frames
are paced by the cap alone (the app's is Textual's limit, 60 a second), until an answer to a
question given up on shows that it does, only slowly.
"""

from __future__ import annotations

import asyncio
from time import monotonic
from typing import Callable, Protocol

FIRST_ANSWER = 1.0  # seconds to wait for an answer from a terminal not known to answer
ANSWER = 3.0  # seconds to wait for one that has answered before
TAGS = 8  # columns the questions are numbered by


class Timer(Protocol):
    def stop(self) -> None: ...


Release = Callable[[], None]
SetTimer = Callable[[float, Release], Timer]


class LoopTimer:
    """``callback`` in ``delay`` seconds, on the running asyncio loop: Textual's
    ``set_timer`` without the task it runs for each timer (the pacer sets one or two a
    frame). For callbacks that need nothing of Textual's."""

    def __init__(self, delay: float, callback: Release) -> None:
        self._handle = asyncio.get_running_loop().call_later(delay, callback)

    def stop(self) -> None:
        self._handle.cancel()


def cursor_question(column: int) -> str:
    """Ask where the cursor is after moving it to ``column`` (0-based) of the first row."""
    # DECSC and DECRC save and restore the cursor, so Textual's own placement stands.
    return f"\x1b7\x1b[1;{column + 1}H\x1b[6n\x1b8"


class Pacer:
    """Releases one frame at a time: see the module's docstring."""

    def __init__(
        self,
        ask: Callable[[int], bool],
        set_timer: SetTimer,
        fps: float | None = None,
        clock: Callable[[], float] = monotonic,
    ) -> None:
        """``ask(column)`` writes :func:`cursor_question` to the terminal, or returns False
        if there is no terminal to ask; ``set_timer(delay, callback)`` calls back later;
        ``fps``, if given, is the most frames a second."""
        self._ask = ask
        self._set_timer = set_timer
        self.fps = fps
        self._clock = clock
        self.answers: bool | None = None  # whether the terminal answers; None: not sure
        self._asked = 0
        self._waiting: tuple[int, Release, Timer] | None = None
        self._given_up: set[int] = set()  # columns of the questions given up on
        self._released = float("-inf")

    def after_frame(self, release: Release) -> None:
        """Call ``release`` once the terminal has read all that has been written so far.

        One frame at a time: the next call comes only after ``release``.
        """
        if self.answers is not False:
            self._asked += 1
            column = self._asked % TAGS
            if self._ask(column):
                timeout = ANSWER if self.answers else FIRST_ANSWER
                self._waiting = (column, release, self._set_timer(timeout, self._give_up))
                return
        self._capped(release)

    def answered(self, x: int, y: int) -> None:
        """The terminal reported its cursor at column ``x``, row ``y`` (0-based)."""
        if y != 0:
            return  # not one of the pacer's questions
        if self._waiting is not None and x == self._waiting[0]:
            _, release, timer = self._waiting
            self._waiting = None
            timer.stop()
            self.answers = True
            self._capped(release)
        elif x in self._given_up:  # it does answer, only slowly: ask again from now on
            self._given_up.discard(x)
            self.answers = True

    def _give_up(self) -> None:
        if self._waiting is None:
            return
        column, release, _ = self._waiting
        self._waiting = None
        self._given_up.add(column)
        # One answer missed (a slow link?): not sure any more. Two in a row: it does not answer.
        self.answers = None if self.answers else False
        self._capped(release)

    def _capped(self, release: Release) -> None:
        now = self._clock()
        at = now if self.fps is None else max(now, self._released + 1 / self.fps)
        self._released = at
        if at > now:
            self._set_timer(at - now, release)
        else:
            release()
