"""The first run's compilations, two at a time.

With an empty numba cache (the first run after installing or upgrading) a picture waits
while numba compiles its kernels, the vertex stage and then the rasterizer, one after the
other: numba compiles in Python under the GIL, so a thread cannot take half of the work,
but a forked child process can. It compiles into the cache, and this process then loads
from there what the child compiled.

Everything about it is here; the rest of the program makes one call:

- ``biceps snapshot`` calls :func:`prepare_kernels`: the child compiles the rasterizer
  while this process compiles the vertex stage. With a warm cache the child would only
  load what the first frame loads anyway, so once the vertex stage has come from the
  cache the child is stopped rather than waited for.
- The app calls :func:`compile_aside` with a job that draws a tiny frame: the child
  compiles a whole frame's kernels while this process starts Textual. Every
  :class:`~biceps.engine.scene.SceneRenderer` calls :func:`wait_for_aside` before its
  first frame, so the render thread loads what the child compiled instead of compiling
  it again beside it.
"""

from __future__ import annotations

import gc
import os
import signal
import threading
import time
import warnings
from typing import Callable



class Aside:
    """A forked child process compiling kernels into numba's cache. Thread-safe: one thread
    may wait for it while another stops it."""

    def __init__(self, pid: int) -> None:
        self._pid = pid
        self._running = True
        self._lock = threading.Lock()

    def wait(self, timeout: float = 120.0) -> None:
        """Return once the child has ended; after ``timeout`` seconds, stop it first."""
        deadline = time.monotonic() + timeout
        while not self._ended():
            if time.monotonic() > deadline:
                self.stop()
            else:
                time.sleep(0.02)

    def stop(self) -> None:
        """End the child now: whatever it has not saved, this process compiles itself.
        numba replaces cache files atomically, so none is left half-written."""
        with self._lock:
            if self._running:
                os.kill(self._pid, signal.SIGKILL)
                os.waitpid(self._pid, 0)
                self._running = False

    def _ended(self) -> bool:
        with self._lock:
            if self._running and os.waitpid(self._pid, os.WNOHANG)[0]:
                self._running = False
            return not self._running


_aside: Aside | None = None
"""The child started by :func:`compile_aside`, until someone has waited for it."""
_aside_lock = threading.Lock()


def compile_aside(job: Callable[[], None]) -> Aside | None:
    """Run ``job`` (a function that compiles, or loads, kernels) in a forked child, where
    that helps and is safe: where processes fork, with two cores or more, and with no
    other thread running (a fork copies only the calling thread, and a lock held by
    another would stay held in the child for ever). Elsewhere: None, and this process
    compiles what it needs as it goes.

    It freezes the heap (``gc.freeze``) before forking, as Python's documentation advises,
    so that the collector does not write to every object and copy every page the two
    processes share: what exists by then is never collected, so call it early in a
    process, or in one that ends soon after.

    The child is kept for :func:`wait_for_aside`, which every renderer calls before its
    first frame.
    """
    global _aside
    if not hasattr(os, "fork") or _cores() < 2 or threading.active_count() > 1:
        return None
    gc.freeze()
    pid = os.fork()
    if pid == 0:
        try:
            warnings.simplefilter("ignore")  # the parent speaks for both
            job()
        finally:
            os._exit(0)  # never back into the caller's code, its exit handlers or buffers
    with _aside_lock:
        _aside = Aside(pid)
    return _aside


def wait_for_aside() -> None:
    """Return once the child started by :func:`compile_aside`, if any, has ended, so that
    what it compiled is loaded from the cache rather than compiled again. Cheap when there
    is none. A child that never ends is stopped after :meth:`Aside.wait`'s time limit; one
    whose process quits first finishes its compilation, and the next start is warm."""
    global _aside
    with _aside_lock:
        aside, _aside = _aside, None
    if aside is not None:
        aside.wait()


def prepare_kernels(shading: str, ssaa: int = 1) -> None:
    """Compile, or load from the cache, the kernels of a frame in ``shading`` with ``ssaa``
    supersampling, the rasterizer's in a child process (see :func:`compile_aside`) while
    this one does the vertex stage."""
    from numba.core import event  # numba, only once a picture is to be made

    from biceps.engine.render import Renderer

    aside = compile_aside(lambda: Renderer().prepare(shading, ssaa, vertex_stage=False))
    if aside is None:
        return  # the first frame compiles what it needs
    try:
        with event.install_recorder("numba:compile") as compiled:
            Renderer().prepare(shading, rasterizer=False)
    except BaseException:  # an interrupt, say: no use waiting for the child
        aside.stop()
        raise
    if not compiled.buffer:  # all from the cache: so, most likely, is the rasterizer
        aside.stop()
    wait_for_aside()


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1
