"""The first run's compilations, on every core.

With an empty numba cache (the first run after installing or upgrading) a picture waits
while numba compiles its kernels, the vertex stage and then the rasterizer, one after the
other: numba compiles in Python under the GIL, so a thread cannot take half of the work,
but a forked child process can. It compiles into the cache, and this process then loads
from there what the child compiled.

Everything about it is here; the rest of the program makes one call:

- ``biceps snapshot`` calls :func:`prepare_kernels`: the child compiles the rasterizer
  while this process compiles the vertex stage. With a warm cache the child would only
  load what the first frame loads anyway, so once the vertex stage has come from the
  cache the child is stopped rather than waited for (:func:`try_here_first`).
- The app calls :func:`compile_aside` with the jobs of a frame (``tui/ahead.py``): a child
  each, compiling while this process starts Textual. Every
  :class:`~biceps.engine.scene.SceneRenderer` calls :func:`wait_for_aside` before its
  first frame, so the render thread loads what the children compiled instead of compiling
  it again beside them. What the app can do without until later, it gives
  :func:`compile_later`: a child that takes a core only when nothing else wants it.
"""

from __future__ import annotations

import functools
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


_asides: list[Aside] = []
"""The children started by :func:`compile_aside`, until someone has waited for them."""
_later: list[Aside] = []
"""The children started by :func:`compile_later`, until the probe has run."""
_probe: Callable[[], None] | None = None
"""The job :func:`wait_for_aside` tries here first (see :func:`try_here_first`)."""
_asides_lock = threading.Lock()

LATER = 19
"""The niceness of :func:`compile_later`'s children: the least share of a core Linux gives."""


def compile_aside(job: Callable[[], None]) -> Aside | None:
    """Run ``job`` (a function that compiles, or loads, kernels) in a forked child, where
    that helps and is safe: where processes fork, with two cores or more, and with no
    other thread running (a fork copies only the calling thread, and a lock held by
    another would stay held in the child for ever). Elsewhere: None, and this process
    compiles what it needs as it goes.

    It freezes the heap (``gc.freeze``) before forking, as Python's documentation advises,
    so that the collector does not write to every object and copy every page the
    processes share: what exists by then is never collected, so call it early in a
    process, or in one that ends soon after.

    The child is kept for :func:`wait_for_aside`, which every renderer calls before its
    first frame. Call it once for each of the jobs that take long, the longest first:
    after the first fork this process makes numba ready to compile, and the children
    forked after it start from there (`_ready_to_compile`).
    """
    aside = _fork(job, 0)
    if aside is not None:
        with _asides_lock:
            _asides.append(aside)
    return aside


def compile_later(job: Callable[[], None]) -> Aside | None:
    """Run ``job`` as :func:`compile_aside` does, but at the lowest priority (niceness
    :data:`LATER`), for kernels wanted after the first picture: the child runs while
    the others leave a core idle, and barely slows them when they do not. Renderers do
    not wait for it; whoever wants its kernels waits for the child returned, which a warm
    cache stops as it does the others: on a busy machine it might not run for seconds,
    where this process loads its kernels from the cache in milliseconds."""
    aside = _fork(job, LATER)
    if aside is not None:
        with _asides_lock:
            _later.append(aside)
    return aside


def try_here_first(probe: Callable[[], None]) -> None:
    """Have :func:`wait_for_aside` run ``probe``, a small part of the children's work, in
    the waiting thread first. If numba compiles nothing for it, the cache is warm: the
    children would only load what this process loads anyway (numba's first load in a
    process costs a tenth of a second), so they are stopped rather than waited for."""
    global _probe
    _probe = probe


def _fork(job: Callable[[], None], niceness: int) -> Aside | None:
    """`compile_aside`'s child, at ``niceness``; None where a fork would not help."""
    if not hasattr(os, "fork") or _cores() < 2 or threading.active_count() > 1:
        return None
    gc.freeze()
    pid = os.fork()
    if pid == 0:
        try:
            os.nice(niceness)
            warnings.simplefilter("ignore")  # the parent speaks for all
            job()
        finally:
            os._exit(0)  # never back into the caller's code, its exit handlers or buffers
    _ready_to_compile()  # once the first child is on its way: the rest start from here
    return Aside(pid)


def wait_for_aside() -> None:
    """Return once the children started by :func:`compile_aside`, if any, have ended, so
    that what they compiled is loaded from the cache rather than compiled again; with a
    warm cache, once the probe (:func:`try_here_first`) has shown it. Cheap when there
    are none. A child that never ends is stopped after :meth:`Aside.wait`'s time limit;
    one whose process quits first finishes its compilation, and the next start is warm."""
    global _probe
    with _asides_lock:
        asides, later, probe = _asides[:], _later[:], _probe
        _asides.clear()
        _later.clear()
        _probe = None
    if not asides:
        return
    try:
        warm = probe is not None and _compiles_nothing(probe)
    except BaseException:  # an interrupt, say: no use waiting for the children
        warm = True
        raise
    finally:
        for aside in (asides + later) if warm else asides:
            if warm:
                aside.stop()
            else:
                aside.wait()


@functools.cache
def _ready_to_compile() -> None:
    """Compile a function of nothing: numba's first compilation in a process makes its
    target ready (its registries of types and implementations, LLVM), a tenth of a second
    that children forked after it, and this process, then do not spend again."""
    import numba

    numba.njit(lambda: None)()


def _compiles_nothing(job: Callable[[], None]) -> bool:
    """Run ``job``; whether numba compiled nothing for it (it all came from the cache)."""
    from numba.core import event  # numba, only once a picture is to be made

    with event.install_recorder("numba:compile") as compiled:
        job()
    return not compiled.buffer


def compile_rasterizer_aside(shading: str) -> Aside | None:
    """Start a child compiling the rasterizer of ``shading`` (:func:`compile_aside`): much
    the longest compilation of a frame, so the first to start."""
    from biceps.engine.render import Renderer

    return compile_aside(lambda: Renderer().prepare(shading, vertex_stage=False))


def prepare_kernels(shading: str, ssaa: int = 1) -> None:
    """Compile, or load from the cache, the kernels of a frame in ``shading`` with ``ssaa``
    supersampling, the rasterizer's in a child process (see :func:`compile_aside`) while
    this one does the vertex stage and the downsampling: with a warm cache, once the
    vertex stage has come from there, so, most likely, has the rasterizer, and the child
    is stopped."""
    from biceps.engine.render import Renderer

    compile_rasterizer_aside(shading)
    try_here_first(lambda: Renderer().prepare(shading, ssaa, rasterizer=False))
    wait_for_aside()


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1
