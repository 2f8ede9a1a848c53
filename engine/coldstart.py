"""The first run's compilations, two at a time.

With an empty numba cache (the first run after installing or upgrading) a picture waits
while numba compiles its kernels: about 0.7 s for the vertex stage, then 1.2 s for the
rasterizer, one after the other, as numba compiles in Python under the GIL: a thread
cannot take half of the work, but a forked child process can. It compiles into the cache,
and this process then loads from there what the child compiled.

- ``biceps snapshot`` (:func:`prepare_kernels`): the child compiles the rasterizer while
  this process compiles the vertex stage. With a warm cache the child would only load
  what the first frame loads anyway, so once the vertex stage has come from the cache the
  child is stopped rather than waited for.
- The app: the child compiles a whole frame's kernels while this process starts Textual
  (which compiles the SGR rewriter), and the render thread waits for it before its first
  frame.
"""

from __future__ import annotations

import gc
import os
import signal
import threading
import time
import warnings
from typing import Callable

from numba.core import event

from biceps.engine.render import Renderer


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
    """
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
    return Aside(pid)


def prepare_kernels(shading: str, ssaa: int = 1) -> None:
    """Compile, or load from the cache, the kernels of a frame in ``shading`` with ``ssaa``
    supersampling, the rasterizer's in a child process (see :func:`compile_aside`) while
    this one does the vertex stage."""
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
    aside.wait()


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1
