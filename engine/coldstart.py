"""The first run's compilations, on every core.

With an empty numba cache (the first run after installing or upgrading) a picture waits
while numba compiles its kernels, the vertex stage and then the rasterizer, one after the
other: numba compiles in Python under the GIL, so a thread cannot take half of the work,
but a forked child process can. It compiles into the cache, and this process then loads
from there what the child compiled.

Everything about it is here, and only the commands start it (a process that is theirs
alone, ``biceps/cli.py``): the engine used as a library forks nothing. They make a few
calls:

- ``biceps snapshot`` and ``animate`` call :func:`prepare_kernels`: the child compiles the
  rasterizer while this process compiles the vertex stage. With a warm cache the child
  would only load what the first frame loads anyway, so once the vertex stage has come
  from the cache the child is stopped rather than waited for
  (:meth:`Asides.stop_if_cached`).
- The app's command makes an :class:`Asides` and starts the rasterizer's child as soon as
  it has read its config (:meth:`Asides.start_rasterizer`); the app then probes the cache
  and, if it is cold, gives the rest of a frame's kernels to another child and what it
  can do without until after the first picture to :func:`compile_later`
  (``tui/ahead.py``). The app's renderers are given :meth:`Asides.wait` to call before
  their first frame (:class:`~biceps.engine.scene_renderer.SceneRenderer`), so the render
  thread loads what the children compiled instead of compiling it again beside them.
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

    def __init__(self, pid: int, what: str = "") -> None:
        self._pid = pid
        self.what = what  # what it compiles, in words: "the rasterizer"
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

    @property
    def ended(self) -> bool:
        """Whether the child has ended (its job done, or stopped)."""
        return self._ended()

    def _ended(self) -> bool:
        with self._lock:
            if self._running and os.waitpid(self._pid, os.WNOHANG)[0]:
                self._running = False
            return not self._running


LATER = 19
"""The niceness of :func:`compile_later`'s children: the least share of a core Linux gives."""


class Asides:
    """The children compiling the kernels of this process's first frame, which its
    renderers wait for (:meth:`wait`). Thread-safe."""

    def __init__(self) -> None:
        self._children: list[Aside] = []
        self._lock = threading.Lock()

    def start(self, job: Callable[[], None], what: str = "") -> Aside | None:
        """Run ``job`` (a function that compiles, or loads, kernels) in a forked child,
        where that helps and is safe: where processes fork, with two cores or more, and
        with no other thread running (a fork copies only the calling thread, and a lock
        held by another would stay held in the child for ever). Elsewhere: None, and this
        process compiles what it needs as it goes.

        It freezes the heap (``gc.freeze``) before forking, as Python's documentation
        advises, so that the collector does not write to every object and copy every page
        the processes share: what exists by then is never collected, so call it early in a
        process, or in one that ends soon after (a command's own).

        Call it once for each of the jobs that take long; ``what``: what the job compiles,
        in words, for a person waiting.
        """
        aside = _fork(job, 0, what)
        if aside is not None:
            with self._lock:
                self._children.append(aside)
        return aside

    def start_rasterizer(self, shading: str) -> Aside | None:
        """Start a child compiling the rasterizer of ``shading`` (:meth:`start`): much the
        longest compilation of a frame, so the first to start."""
        from biceps.engine.render import Renderer

        return self.start(lambda: Renderer().prepare(shading, vertex_stage=False),
                          "the rasterizer")

    @property
    def children(self) -> list[Aside]:
        """The children started, ended or not."""
        with self._lock:
            return self._children[:]

    def stop_if_cached(self, probe: Callable[[], None]) -> bool:
        """Run ``probe``, a small part of the children's work, here; if numba compiled
        nothing for it, the cache is warm: stop the children (they would only load what
        this process loads anyway, each spending the tenth of a second numba's first load
        in a process takes) and return True."""
        from numba.core import event  # numba, only once a picture is to be made

        try:
            with event.install_recorder("numba:compile") as compiled:
                probe()
        except BaseException:  # an interrupt, say: no use waiting for the children
            self._stop()
            raise
        if compiled.buffer:
            return False
        self._stop()
        return True

    def wait(self) -> None:
        """Return once the children, if any, have ended, so that what they compiled is
        loaded from the cache rather than compiled again. Cheap once they have. A child
        that never ends is stopped after :meth:`Aside.wait`'s time limit; one whose process
        quits first finishes its compilation, and the next start is warm."""
        for aside in self.children:
            aside.wait()

    def _stop(self) -> None:
        for aside in self.children:
            aside.stop()


def compile_later(job: Callable[[], None]) -> Aside | None:
    """Run ``job`` as :meth:`Asides.start` does, but at the lowest priority (niceness
    :data:`LATER`), for kernels wanted after the first picture: the child runs while
    the others leave a core idle, and barely slows them when they do not. Renderers do
    not wait for it; whoever wants its kernels waits for the child returned."""
    return _fork(job, LATER)


def _fork(job: Callable[[], None], niceness: int, what: str = "") -> Aside | None:
    """`Asides.start`'s child, at ``niceness``; None where a fork would not help."""
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
    return Aside(pid, what)


def prepare_outline() -> None:
    """Compile, or load from the cache, the kernel that outlines a mesh for framing
    (``engine/framing.py``'s outline), on arrays of the kinds a frame passes it: the
    smallest of a frame's kernels, a tenth of a second cold (the app's probe of the cache,
    ``tui/ahead.py``)."""
    import numpy as np

    from biceps.engine.framing import outline

    outline(np.zeros((1, 3)))


def prepare_framing() -> None:
    """:func:`prepare_outline`, and the kernel that aims the camera at the outline
    (``engine/framing.py``'s fit_points)."""
    import numpy as np

    from biceps.engine.framing import fit_points

    prepare_outline()
    fit_points(np.zeros((1, 3)), 1.0)


def prepare_around_the_rasterizer(shading: str, ssaa: int = 1) -> None:
    """Compile, or load from the cache, what a frame in ``shading`` with ``ssaa``
    supersampling runs before and after the rasterizer: the framing, the vertex stage,
    the clearing and the downsampling; and what lays arm26's muscles round the humerus
    (``engine/layers.py``), which a pose of the elbow's needs before its first frame."""
    from biceps.engine.layers import prepare as prepare_layers
    from biceps.engine.render import Renderer

    prepare_framing()
    prepare_layers()
    Renderer().prepare(shading, ssaa, rasterizer=False)


def prepare_kernels(shading: str, ssaa: int = 1) -> None:
    """Compile, or load from the cache, the kernels of a frame in ``shading`` with ``ssaa``
    supersampling, the rasterizer's in a child process (see :meth:`Asides.start`) while
    this one does the rest: with a warm cache, once the rest has come from there, so,
    most likely, has the rasterizer, and the child is stopped."""
    asides = Asides()
    asides.start_rasterizer(shading)
    if not asides.stop_if_cached(lambda: prepare_around_the_rasterizer(shading, ssaa)):
        asides.wait()


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1
