"""A one-place hand-over between the UI thread and a worker thread where the latest item wins.

The UI puts requests as fast as keys repeat or the mouse moves; the worker takes them as
fast as it can serve them. A new request replaces one not yet taken, so a burst never
queues up: the worker always goes straight to the newest. The worker also waits for the UI
to say it is ``done`` with the previous result before taking another, so at most one
result is ever waiting in the UI's message queue.
"""

from __future__ import annotations

import threading
from typing import Generic, TypeVar

T = TypeVar("T")


class LatestOnly(Generic[T]):
    def __init__(self) -> None:
        self._item: T | None = None
        self._busy = False
        self._closed = False
        self._changed = threading.Condition()

    def put(self, item: T) -> None:
        """Offer ``item`` to the worker, replacing any item it has not taken yet."""
        with self._changed:
            self._item = item
            self._changed.notify()

    def take(self) -> T | None:
        """Wait for an item and for the previous one to be done; ``None`` once closed."""
        with self._changed:
            self._changed.wait_for(
                lambda: self._closed or (self._item is not None and not self._busy)
            )
            if self._closed:
                return None
            item, self._item = self._item, None
            self._busy = True
            return item

    def done(self) -> None:
        """The result of the last item taken has been used: the worker may take another."""
        with self._changed:
            self._busy = False
            self._changed.notify()

    def close(self) -> None:
        """Release the worker: :meth:`take` returns ``None`` from now on."""
        with self._changed:
            self._closed = True
            self._changed.notify()

