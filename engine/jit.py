"""The one decorator every numba kernel in the engine is compiled with.

``cache=True`` keeps compiled machine code on disk (``__pycache__``), so a new process loads
the kernels instead of compiling them again; ``nogil=True`` lets a worker thread render
while the UI thread stays responsive.

Fast-math is on, but only with the flags that cannot change what is drawn:

- ``contract`` (fused multiply-add), ``arcp`` (``x / y`` as ``x * (1 / y)``) and ``afn``
  (approximate ``sqrt``, ``pow``) change results in the last bits at most. Coverage does
  not depend on them: it is decided by exact integer edge functions on vertex positions
  snapped once per vertex (see ``engine/raster/coverage.py``), so no fast-math flag can
  open a crack or draw a shared edge twice.
- ``nsz`` (ignore the sign of zero) is harmless for depth and colour.
- Left out: ``nnan`` and ``ninf``, which let the compiler assume there is no NaN or infinity
  and so delete the very tests that keep a NaN vertex or an infinite coordinate from
  reaching an integer conversion; and ``reassoc``, which lets the compiler reorder sums, so
  that the same expression (a clipped vertex shared by two triangles) could come out
  differently in two places.

``error_model="numpy"``: a division by zero gives an infinity or NaN (which the kernels
test for) instead of a check and a Python exception on every division in the inner loops.

``_nrt=False``: no reference counting of arrays in the kernels (numba's runtime, NRT; a
target option its CPU target lists, ``numba/core/cpu.py``). The kernels allocate nothing
(the caller passes every buffer, scratch too), so there is nothing for it to free; but
numba counts references to every array a kernel hands an inlined function, and once that
function branches, reference-count pruning (llvmlite's refprune pass) keeps an atomic
increment and decrement per array per call: a draw loop that skipped the setup of
triangles covering no pixel ran 2.4 times as slow (26 increments in ``rasterize_gouraud``
against 13), where without counting it runs faster than before. A kernel that allocated
an array would not compile.
"""

import numba
from numba.extending import register_jitable

FASTMATH = {"contract", "arcp", "afn", "nsz"}

ngjit = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy", _nrt=False)
"""``@ngjit``: compile a kernel in nopython mode, cached, without the GIL."""

inline = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy",
                    _nrt=False, inline="always")
"""``@inline``: ``@ngjit`` for the few functions called once per triangle or per row of a
triangle, which numba then inlines into their caller (LLVM does not inline across numba
functions: the call, with every array passed as a dozen scalars, cost as much as a short
row of pixels). Inlining lengthens the first compilation, so it is kept to those."""

exact = numba.njit(cache=True, nogil=True, error_model="numpy", _nrt=False)
"""``@exact``: ``@ngjit`` without fast-math, for a kernel that must give what the numpy it
replaces gives, to the last bit (no fused multiply-add, no ``x * (1 / y)`` for ``x / y``)."""

helper = register_jitable(fastmath=FASTMATH, error_model="numpy")
"""``@helper``: a small function called by kernels and compiled into them, as ``@ngjit`` would
compile it, but with no dispatcher of its own: no Python entry point to generate, and no
cache file of its own to write (its machine code is cached with each kernel that calls it),
which makes it cheaper than an ``@ngjit`` helper on the first, cold run (an empty numba
cache), where numba's own passes over each function are most of the time. It stays a
plain Python function for Python callers."""
