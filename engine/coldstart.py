"""The first run's compilations, two at a time.

With an empty numba cache (the first run after installing or upgrading) a picture waits
while numba compiles its kernels: about 0.7 s for the vertex stage, then 1.2 s for the
rasterizer, one after the other, as numba compiles in Python under the GIL. A forked child
process can take one of them: it compiles the rasterizer into the cache while this process
compiles the vertex stage, and this process then loads the rasterizer from the cache.

With a warm cache the child would only load what the first frame loads anyway, so once the
vertex stage has come from the cache the child is stopped rather than waited for.
"""

from __future__ import annotations

import gc
import os
import signal
import threading
import warnings

from numba.core import event

from engine.render import Renderer


def prepare_kernels(shading: str) -> None:
    """Compile, or load from the cache, the kernels of a frame in ``shading``, two processes
    at a time where that helps and is safe: where processes fork, with two cores or more,
    and with no other thread running (a fork copies only the calling thread, and a lock
    held by another would stay held in the child for ever). Elsewhere it does nothing, and
    the first frame compiles what it needs as it goes.

    For a process that ends soon after, such as the ``biceps snapshot`` command's: it
    freezes the heap (``gc.freeze``) before forking, as Python's documentation advises, so
    that the collector does not write to every object and copy every page the two
    processes share; what exists then is never collected.
    """
    if not hasattr(os, "fork") or _cores() < 2 or threading.active_count() > 1:
        return
    gc.freeze()
    child = os.fork()
    if child == 0:
        try:
            warnings.simplefilter("ignore")  # this process speaks for both
            Renderer().prepare(shading, vertex_stage=False)
        finally:
            os._exit(0)  # never back into the caller's code, its exit handlers or buffers
    try:
        with event.install_recorder("numba:compile") as compiled:
            Renderer().prepare(shading, rasterizer=False)
        if not compiled.buffer:  # all from the cache: so, most likely, is the rasterizer
            os.kill(child, signal.SIGKILL)
    finally:
        os.waitpid(child, 0)


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1
