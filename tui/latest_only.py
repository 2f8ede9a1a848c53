"""A one-place hand-over between the UI thread and a worker thread where the latest item wins.

The UI puts requests as fast as keys repeat or the mouse moves; the worker takes them as
fast as it can serve them. A new request replaces one not yet taken, so a burst never
queues up: the worker always goes straight to the newest.

The worker may take the next item while the UI is still using the last result, and work
on it ahead; but it hands a result over only once the UI says it is ``done`` with the
previous one (:meth:`LatestOnly.hand_over`), so at most one result is ever waiting in the
UI's message queue, and results arrive in the order they were made.
"""

from __future__ import annotations

import threading
from typing import Generic, TypeVar

T = TypeVar("T")


class LatestOnly(Generic[T]):
    def __init__(self) -> None:
        self._item: T | None = None
        self._busy = False  # a result has been handed over and the UI is not done with it
        self._closed = False
        self._changed = threading.Condition()

    def put(self, item: T) -> None:
        """Offer ``item`` to the worker, replacing any item it has not taken yet."""
        with self._changed:
            self._item = item
            self._changed.notify()

    def take(self) -> T | None:
        """Wait for an item and take it; ``None`` once closed. The UI may still be using
        the last result: :meth:`hand_over` waits for that."""
        with self._changed:
            self._changed.wait_for(lambda: self._closed or self._item is not None)
            return None if self._closed else self._take()

    def newer(self) -> T | None:
        """Take the item put since the last one was taken, if there is one, without
        waiting; ``None`` if there is none or once closed."""
        with self._changed:
            return None if self._closed or self._item is None else self._take()

    def _take(self) -> T:
        item, self._item = self._item, None
        return item

    def hand_over(self) -> bool:
        """Wait until the UI is done with the last result handed over, then count the next
        one as handed over; ``False`` once closed (hand nothing over then)."""
        with self._changed:
            self._changed.wait_for(lambda: self._closed or not self._busy)
            if self._closed:
                return False
            self._busy = True
            return True

    def done(self) -> None:
        """The last result handed over has been used: the worker may hand over another."""
        with self._changed:
            self._busy = False
            self._changed.notify()

    def close(self) -> None:
        """Release the worker: :meth:`take` returns ``None`` and :meth:`hand_over`
        ``False`` from now on."""
        with self._changed:
            self._closed = True
            self._changed.notify()
