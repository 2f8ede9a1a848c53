"""Bands: a frame drawn on every core, as horizontal bands of rows, one thread each.

The kernels release the GIL (``engine/jit.py``), so plain Python threads run them at once.
Each band is cleared, rasterized and (when supersampled) averaged down by one thread, which
alone writes its rows: no two threads ever touch one pixel. Every band draws the triangles
in the same order and a span's pixels do not depend on where the band starts
(`coverage.band_spans`), so the picture is the same, byte for byte, on any number of
threads. Each band tests every triangle against its rows first, the cheapest test; culling
them once for all bands, a share per thread, took a kernel of its own, which added half a
second to the first run's compilation for no gain measurable on two cores.

Threads rather than numba's ``parallel=True``: its default thread pool (workqueue) aborts
the process when two threads start parallel kernels at once, which the app does (a frame
rendering while a picture is exported or a video recorded), and parallel kernels take
several times as long to compile, on the cold first run the app is to start within 3.5 s.

How many threads: ``BICEPS_THREADS`` in the environment (``engine/settings.py``), or else
every core this process may run on; 1 keeps everything on the calling thread. Whose
threads: a pool of the renderer's own, shut down with it, unless it is given one to share
(the app's renderers share one, which its command starts and stops).
"""

from __future__ import annotations

import os
from concurrent.futures import Executor, ThreadPoolExecutor

import numpy as np

from biceps.engine.settings import drawing_threads


SMALL_PICTURE = 100_000
"""Pixels (supersampled) below which a frame is drawn in one band, on the calling thread:
handing a band to another thread and waiting for it costs about as much as drawing a small
picture. The app's picture at 200x60 cells (about 72,000 pixels at 2x2) drawn in one band
took 0.3 ms less CPU a frame under a held key than in two, with no later a picture
(``benchmarks/app_profile.py``, ``benchmarks/tui_pty.py``)."""

HITS = 4096
"""The pixels Phong lists before it lights them (``engine/raster/shading.py``), at least:
enough for most triangles' whole share of a band, few enough to stay in the L1 and L2
caches."""


def default_threads() -> int:
    """The threads ``BICEPS_THREADS`` asks for (`settings.drawing_threads`, which refuses
    what is not a whole number from 1), else this process's cores."""
    asked = drawing_threads(os.environ)
    if asked is not None:
        return asked
    if hasattr(os, "sched_getaffinity"):
        return max(len(os.sched_getaffinity(0)), 1)
    return max(os.cpu_count() or 1, 1)


def band_pool(threads: int | None = None) -> ThreadPoolExecutor:
    """A pool for renderers of ``threads`` threads (`default_threads` if None) to share,
    one thread fewer, as the calling thread draws a band too. Its threads only ever run
    tasks to the end, never wait on another, so renderers sharing it cannot deadlock,
    whatever their number of bands. Its owner shuts it down."""
    threads = default_threads() if threads is None else threads
    return ThreadPoolExecutor(max_workers=max(threads - 1, 1), thread_name_prefix="biceps-band")


class Bands:
    """The split of frames into bands, and each band's scratch buffers."""

    def __init__(self, threads: int | None = None, pool: Executor | None = None):
        """``threads``: the bands of a large frame (`default_threads` if None); ``pool``:
        where the bands but the first are drawn (shared, see `band_pool`, and shut down by
        its owner), or None for a pool of this object's own, started at the first frame
        that needs it and shut down by :meth:`close`."""
        threads = default_threads() if threads is None else threads
        if not (isinstance(threads, (int, np.integer)) and threads >= 1):
            raise ValueError(f"threads must be a positive integer, got {threads!r}")
        self.threads = int(threads)
        self._pool = pool
        self._own_pool: ThreadPoolExecutor | None = None
        self._shape: tuple | None = None

    def run(self, tasks) -> None:
        """Run every callable of ``tasks``, the first on this thread and the rest on the
        pool's, and return once all have, raising the first error any raised."""
        tasks = list(tasks)
        pool = self._pool
        if pool is None and len(tasks) > 1:
            if self._own_pool is None:
                self._own_pool = band_pool(self.threads)
            pool = self._own_pool
        futures = [pool.submit(task) for task in tasks[1:]]
        try:
            tasks[0]()
        finally:
            for future in futures:
                future.result()

    def close(self) -> None:
        """Shut down the pool of this object's own, if it started one (a shared pool is
        its owner's to shut down); a later frame starts another."""
        if self._own_pool is not None:
            self._own_pool.shutdown()
            self._own_pool = None

    def reserve(self, height: int, width: int, ssaa: int) -> None:
        """Split a frame of ``height`` x ``width`` pixels drawn ``ssaa`` times finer into
        bands, each a whole number of output rows, and allocate their scratch."""
        if self._shape == (height, width, ssaa):
            return
        count = self.threads if height * width * ssaa * ssaa >= SMALL_PICTURE else 1
        count = min(count, height)
        edges = [round(height * k / count) for k in range(count + 1)]
        self.rows = [(ssaa * low, ssaa * high) for low, high in zip(edges, edges[1:])]
        fine_h, fine_w = height * ssaa, width * ssaa
        hits = max(2 * fine_w, HITS)
        self.scratch = [
            (np.empty((4, fine_h), np.int64), np.empty((11, 3)), np.empty(hits, np.int64),
             np.empty((8, hits), np.float32), np.empty(3 * fine_w, np.int32))
            for _ in self.rows
        ]
        self._shape = (height, width, ssaa)
        self.forget_drawn()

    def forget_drawn(self) -> None:
        """Have the next frame clear every row whole, as if the last had drawn on all of
        them (``draw.clear_drawn``): the buffers are new, or the background is not the
        last frame's."""
        _, width, ssaa = self._shape
        for spans, *_ in self.scratch:
            spans[2], spans[3] = 0, width * ssaa

    def draw(self, draw_band) -> None:
        """Call ``draw_band(start, end, scratch)`` for every band at once: its rows
        ``start <= y < end`` of the fine frame, and its scratch (spans, planes, hits,
        shaded, columns; the spans' last two rows kept from frame to frame)."""
        self.run(lambda rows=rows, scratch=scratch: draw_band(*rows, scratch)
                 for rows, scratch in zip(self.rows, self.scratch))
