"""The software rasterizer: numba kernels that take arrays and scalars, write into output
buffers and return nothing. ``engine/render.py`` calls them once each per frame (steps 1
to 3 once per share of a large mesh's vertices, a thread each):

1. ``vertex.transform_vertices``: model to world space, positions and (inverse-transpose)
   normals.
2. ``vertex.project_vertices``: world to clip space; an outcode per vertex (the clipping
   planes it is outside); for vertices inside them all, the screen position snapped to
   fixed point.
3. ``vertex.light_vertices`` (Gouraud) or ``vertex.phong_vertices`` (Phong): the per-vertex
   attributes the rasterizer interpolates (Phong's first six rows are step 1's output).
4. Only when some vertex is outside a clipping plane: ``clipping.clip_triangles`` cuts the
   triangles that cross one into a small mesh already in screen space, drawn after the
   others by the same kernels.
5. Band by band, a thread each (``bands``): clear what the last frame drew on the band's
   rows (``draw.clear_drawn``), then ``draw.rasterize_gouraud``, ``rasterize_phong`` or
   ``rasterize_overdraw`` on them: per triangle, reject, cull, cover (``coverage``) and
   shade (``shading``); then ``resample.downsample`` averages supersampled pixels.

Spaces are those of ``engine/transforms.py``: OpenGL clip space, then screen space with
``x`` right and ``y`` down in pixels, pixel ``(x, y)`` centred at ``(x + 0.5, y + 0.5)``,
depth reversed: 1 on the near plane, 0 on the far one, larger is nearer. Float32 is densest
near 0, and the usual depth crowds near 1 (it goes as 1 - near / distance), so the reversed
one keeps float32's precision at any distance (Reed, "Depth Precision Visualized", 2015).

Layouts. Per-vertex arrays are component-major, ``(3, n)`` rather than the mesh's
``(n, 3)``: with every matrix read into registers first, LLVM then vectorises the vertex
loops (AVX), several times faster than loops over rows. The frame buffers are passed
flattened, ``pixels: (3 h w,) uint8`` and ``depths: (h w,) float32`` (views of the
``(h, w, 3)`` and ``(h, w)`` buffers), so that the inner loops index them with one unsigned
offset: numba adds a negative-index fix-up to every signed index, which costs as much as
the rest of a pixel.

Editing. numba keeps each kernel's machine code on disk (``engine/jit.py``) and checks only
the file that defines the kernel for changes, not the modules its helpers and constants
come from (numba's documentation, "Notes on caching"; numba/numba#1833): after changing a
module here, delete ``engine/raster/__pycache__`` so that the kernels of the others are
compiled again.
"""

from biceps.engine.raster.clipping import (BOTTOM, CLIP_MASK, FAR, INVALID, LEFT, MAX_POLYGON,
                                           NEAR, RIGHT, TOP, clip_triangles)
from biceps.engine.raster.coverage import band_spans, triangle_spans
from biceps.engine.raster.draw import (clear_drawn, rasterize_gouraud, rasterize_overdraw,
                                       rasterize_phong)
from biceps.engine.raster.resample import downsample
from biceps.engine.raster.shading import Lighting, highlight_threshold
from biceps.engine.raster.vertex import (light_vertices, phong_vertices, project_vertices,
                                         transform_vertices)

__all__ = [
    "BOTTOM", "CLIP_MASK", "FAR", "INVALID", "LEFT", "MAX_POLYGON", "NEAR", "RIGHT", "TOP",
    "Lighting", "band_spans", "clear_drawn", "clip_triangles", "downsample",
    "highlight_threshold", "light_vertices", "phong_vertices", "project_vertices",
    "rasterize_gouraud", "rasterize_overdraw", "rasterize_phong", "transform_vertices",
    "triangle_spans",
]
