"""Rendering: the :class:`Renderer` owns the buffers and wires the raster kernels together.

A frame is one call of each kernel of ``engine/raster/``; Python here only composes the
4x4 matrices and keeps the buffers, allocated once per size and reused.
"""

from __future__ import annotations

from concurrent.futures import Executor

import numpy as np

from biceps.engine import raster
from biceps.engine.raster.bands import Bands
from biceps.engine.transforms import Camera, Light, normal_matrix

RASTERIZERS = {
    "gouraud": raster.rasterize_gouraud,
    "phong": raster.rasterize_phong,
    "overdraw": raster.rasterize_overdraw,
}
"""Shadings by name. "overdraw" is a debugging view: the red channel counts the triangles
that cover each pixel (with no depth test)."""

PARALLEL_VERTICES = 16384
"""Vertices from which the vertex stage, 8 to 11 ns a vertex, pays for more threads (tens
of microseconds to hand each its share)."""


class Renderer:
    """Draws meshes into buffers it keeps from frame to frame.

    Not thread-safe: use one renderer per thread. The kernels release the GIL, so a worker
    thread can render while another runs the UI.

    threads: how many threads draw each frame, in bands (``engine/raster/bands.py``; by
    default ``BICEPS_THREADS`` or every core); the picture is the same on any number.
    pool: where the threads come from (shared, its owner's to shut down), or None for a
    pool of the renderer's own, which :meth:`close` shuts down.
    """

    def __init__(self, threads: int | None = None, pool: Executor | None = None):
        self._frame: tuple | None = None  # (height, width, ssaa)
        self._bands = Bands(threads, pool)
        self._vertex_count = -1
        self._mesh: tuple | None = None  # (vertices, normals, triangles) last copied in
        # The last frame's camera and light and what they gave: frames of an unmoved camera
        # (a turning model, a sweep, an animation) reuse them: a small frame is mostly such
        # fixed costs.
        self._seen: tuple = (None, None)
        self._normals_of: tuple = (b"", None)  # the last model matrix's bytes, its normals'
        self._background: tuple | None = None  # the last frame's (see _draw)

    def close(self) -> None:
        """Stop the threads of the renderer's own pool, if it started one."""
        self._bands.close()

    @property
    def threads(self) -> int:
        """How many threads draw each frame."""
        return self._bands.threads

    def render(self, vertices, normals, triangles, albedo, model_matrix, camera: Camera,
               light: Light, width: int, height: int, shading: str = "gouraud", ssaa: int = 1,
               background=(0, 0, 0), pixel_aspect: float = 1.0) -> np.ndarray:
        """Draw a mesh and return the picture: (height, width, 3) uint8.

        vertices: (n, 3) float64 and normals: (n, 3) float64, model space.
        triangles: (m, 3) int32, counter-clockwise seen from outside.
        albedo: (n, 3) float32 in [0, 1], each vertex's colour (so muscle and bones can be
            one concatenated mesh).
        model_matrix: (4, 4) float64, model to world space; normals follow by its inverse
            transpose. The camera and the light are in world space, so the light does not
            turn with the model.
        shading: "gouraud" (lit at the vertices), "phong" (lit per pixel, with a specular
            highlight) or "overdraw" (see ``RASTERIZERS``).
        ssaa: render at ssaa x ssaa the size and average down (anti-aliasing), 1 for none.
        background: (r, g, b), 0 to 255.
        pixel_aspect: a pixel's width over its height where the picture is shown (a
            terminal's cell of 2 x 3 pixels, say, has pixels narrower than tall).

        The result is a read-only view of the renderer's own buffer: it stays valid until
        the next call, which overwrites it. Copy it to keep it.
        """
        rasterize = RASTERIZERS.get(shading)
        if rasterize is None:
            raise ValueError(f"shading must be one of {sorted(RASTERIZERS)}, got {shading!r}")
        if not (isinstance(ssaa, (int, np.integer)) and ssaa >= 1):
            raise ValueError(f"ssaa must be a positive integer, got {ssaa!r}")
        if width < 1 or height < 1:
            raise ValueError(f"the picture must be at least 1x1 pixels, got {width}x{height}")
        # A mesh's read-only arrays, passed again, are the mesh already checked and copied
        # (held here, so that no other array can take their place in memory meanwhile).
        mesh = (vertices, normals, triangles)
        known = self._mesh is not None and all(
            given is kept and not given.flags.writeable for given, kept in zip(mesh, self._mesh))
        triangles = _read_only(np.ascontiguousarray(triangles, dtype=np.int32))
        model = np.ascontiguousarray(model_matrix, dtype=np.float64)
        if not known:
            self._mesh = None
            _check_mesh(vertices, normals, triangles, albedo)
        else:
            _check_shape("albedo", albedo, len(vertices))
        self._reserve_frame(int(height), int(width), int(ssaa))
        self._reserve_vertices(len(vertices))
        full_h, full_w = self._depth.shape

        view_projection, lighting = self._camera_and_light(camera, light,
                                                           width * pixel_aspect / height)
        if not known:
            # The kernels take per-vertex arrays component-major (engine/raster/__init__.py).
            np.copyto(self._vertices, np.asarray(vertices).T)
            np.copyto(self._normals, np.asarray(normals).T)
            self._mesh = mesh
        attributes = self._transform(shading, light, albedo, model, view_projection, full_w,
                                     full_h)

        if shading == "overdraw":
            background = (0, 0, 0)  # the picture counts from zero
        red, green, blue = (min(max(int(c), 0), 255) for c in background)
        meshes = [(triangles, self._screen_xy, self._screen_z, self._screen_q, self._outcodes,
                   attributes)]
        if np.bitwise_or.reduce(self._outcodes) & raster.CLIP_MASK:
            meshes.append(self._clipped(triangles, attributes, full_w, full_h))
        self._draw(rasterize, meshes, lighting, (red, green, blue))
        return _read_only(self._output if ssaa > 1 else self._colour)

    def prepare(self, shading: str = "gouraud", ssaa: int = 1, *, vertex_stage: bool = True,
                rasterizer: bool = True) -> None:
        """Compile, or load from numba's cache, the kernels a frame in ``shading`` with
        ``ssaa`` supersampling runs, or those of one stage, without drawing anything (see
        ``engine/coldstart.py``). The clearing comes with the vertex stage, and the
        downsampling of a supersampled frame with either stage: the rasterizer, much the
        longest to compile, can then be prepared alone (``ssaa`` 1) while the rest is
        prepared beside.

        Each kernel runs once on buffers of the kinds `render` passes it, for one vertex,
        no triangle and one pixel, so that numba makes the very version `render` calls.
        """
        rasterize = RASTERIZERS[shading]
        self._reserve_frame(1, 1, ssaa)
        self._reserve_vertices(1)
        if vertex_stage:
            self._mesh = None
            self._vertices.fill(0.0)
            self._normals.fill(0.0)
            self._transform(shading, Light(), np.zeros((1, 3), np.float32), np.eye(4),
                            np.eye(4), 1, 1)
        no_triangles = _read_only(np.zeros((0, 3), np.int32))
        meshes = [(no_triangles, self._screen_xy, self._screen_z, self._screen_q,
                   self._outcodes, self._attributes(shading))] if rasterizer else []
        if meshes or vertex_stage or ssaa > 1:
            self._draw(rasterize, meshes, _lighting(Light(), Camera()), (0, 0, 0),
                       clear=vertex_stage)

    def _transform(self, shading, light, albedo, model, view_projection, width, height):
        """The vertex stage, from the vertices and normals copied in: world positions and
        normals, clip space and screen positions, and what the rasterizer interpolates for
        ``shading`` (returned: (a, n) float64); a large mesh's vertices shared among the
        threads, each a range of them through every kernel."""
        attributes = self._attributes(shading)
        normals = self._normal_matrix(model)
        position = np.asarray(light.position, dtype=np.float64)
        albedo = np.asarray(albedo)

        def stage(first, end):
            np.copyto(self._albedo[:, first:end], albedo[first:end].T)
            raster.transform_vertices(self._vertices, self._normals, model, normals,
                                      self._world, self._world_normals, first, end)
            raster.project_vertices(self._world, view_projection, width, height, self._clip,
                                    self._screen_xy, self._screen_z, self._screen_q,
                                    self._outcodes, first, end)
            if shading == "gouraud":
                raster.light_vertices(self._world, self._world_normals, self._albedo, position,
                                      float(light.ambient), float(light.diffuse), attributes,
                                      first, end)
            elif shading == "phong":
                raster.phong_vertices(self._albedo, attributes, first, end)

        count = self._vertex_count
        parts = self.threads if count >= PARALLEL_VERTICES else 1
        edges = [count * k // parts for k in range(parts + 1)]
        self._bands.run(lambda first=first, end=end: stage(first, end)
                        for first, end in zip(edges, edges[1:]))
        return attributes

    def _camera_and_light(self, camera: Camera, light: Light, aspect: float) -> tuple:
        """The view-projection matrix and the kernels' lighting for this frame."""
        key, seen = self._seen
        if not _equal(key, (camera, light, aspect)):
            view_projection = camera.projection_matrix(aspect) @ camera.view_matrix()
            seen = (view_projection, _lighting(light, camera))
            self._seen = ((camera, light, aspect), seen)
        return seen

    def _normal_matrix(self, model: np.ndarray) -> np.ndarray:
        """`_normal_matrix` of ``model``, kept for the frames that follow with the same."""
        key = model.tobytes()
        if self._normals_of[0] != key:
            self._normals_of = (key, _normal_matrix(model))
        return self._normals_of[1]

    def _attributes(self, shading: str) -> np.ndarray:
        """The buffer of what the rasterizer interpolates for ``shading``."""
        buffers = {"gouraud": self._colours, "phong": self._phong_attributes}
        return buffers.get(shading, self._no_attributes)

    def _draw(self, rasterize, meshes, lighting, background, clear: bool = True) -> None:
        """Clear the frame (unless not to ``clear``: see `prepare`), draw ``meshes`` into it
        (each a tuple of triangles, screen_xy, screen_z, screen_q, outcodes, attributes), in
        order, and average it down if it is supersampled: band by band, a thread each
        (``engine/raster/bands.py``)."""
        full_h, full_w = self._depth.shape
        _, width, ssaa = self._frame
        pixels, depths = self._colour.reshape(-1), self._depth.reshape(-1)

        if background != self._background:
            self._background = background
            self._bands.forget_drawn()  # (every pixel of the last frame's background)
        red, green, blue = (np.uint8(channel) for channel in background)

        def draw_band(start, end, scratch):
            spans, planes, hits, shaded, columns = scratch
            if clear:
                raster.clear_drawn(pixels, depths, full_w, start, end, spans, red, green,
                                   blue)
            for triangles, xy, z, q, outcodes, attributes in meshes:
                rasterize(triangles, xy, z, q, outcodes, attributes, lighting, pixels, depths,
                          full_w, start, end, spans, planes, hits, shaded)
            if ssaa > 1:
                raster.downsample(self._colour[start:end].reshape(-1), ssaa,
                                  self._output[start // ssaa:end // ssaa].reshape(-1), width,
                                  columns)

        self._bands.draw(draw_band)

    def _clipped(self, triangles, attributes, width, height) -> tuple:
        """The triangles that cross a clipping plane, clipped into a small mesh in screen
        space: (triangles, screen_xy, screen_z, screen_q, outcodes, attributes). Only frames
        with a vertex outside a clipping plane (the camera close to or inside the model, or
        a huge scale) need it."""
        outside = (self._outcodes & raster.CLIP_MASK) != 0
        crossing = np.count_nonzero(outside[triangles].any(axis=1))
        room = max(crossing, 1) * raster.MAX_POLYGON
        out_xy = np.empty((2, room), np.int64)
        out_z, out_q = np.empty(room), np.empty(room)
        out_attributes = np.empty((attributes.shape[0], room))
        out_triangles = np.empty((room, 3), np.int32)
        counts = np.zeros(2, np.int64)
        polygon = np.empty((2, raster.MAX_POLYGON, 4 + attributes.shape[0]))
        source = np.empty((2, raster.MAX_POLYGON), np.int64)
        raster.clip_triangles(triangles, self._clip, self._screen_xy, self._screen_z,
                              self._screen_q, self._outcodes, attributes, width, height, out_xy,
                              out_z, out_q, out_attributes, out_triangles, counts, polygon,
                              source)
        inside = np.zeros(room, np.uint8)  # every outcode 0: the clipper did its work
        return (_read_only(out_triangles[:counts[1]]), out_xy, out_z, out_q, inside,
                out_attributes)

    def _reserve_frame(self, height: int, width: int, ssaa: int) -> None:
        """(Re)allocate the frame buffers when the size or the supersampling changes."""
        if self._frame == (height, width, ssaa):
            return
        self._colour = np.empty((height * ssaa, width * ssaa, 3), np.uint8)
        self._depth = np.empty((height * ssaa, width * ssaa), np.float32)
        self._output = np.empty((height, width, 3), np.uint8) if ssaa > 1 else None
        self._bands.reserve(height, width, ssaa)  # (whose next frame clears every row)
        self._frame = (height, width, ssaa)

    def _reserve_vertices(self, count: int) -> None:
        """(Re)allocate the per-vertex buffers when the vertex count changes."""
        if self._vertex_count == count:
            return
        self._mesh = None
        self._vertices = np.empty((3, count))
        self._normals = np.empty((3, count))
        self._albedo = np.empty((3, count), np.float32)
        # World positions and normals are Phong's first attributes (`raster.phong_vertices`).
        self._phong_attributes = np.empty((9, count))
        self._world = self._phong_attributes[0:3]
        self._world_normals = self._phong_attributes[3:6]
        self._clip = np.empty((4, count))
        self._screen_xy = np.empty((2, count), np.int64)
        self._screen_z = np.empty(count)
        self._screen_q = np.empty(count)
        self._outcodes = np.empty(count, np.uint8)
        self._colours = np.empty((3, count))
        self._no_attributes = np.empty((0, count))
        self._vertex_count = count


def _read_only(array: np.ndarray) -> np.ndarray:
    """A read-only view of ``array``: so the caller cannot write into the renderer's
    buffers, and so the kernels always see one kind of triangle array (numba compiles a
    kernel again for read-only arrays, and meshes hold theirs read-only)."""
    view = array.view()
    view.flags.writeable = False
    return view


def _lighting(light: Light, camera: Camera) -> raster.Lighting:
    """The rasterize kernels' lighting, every field a float (see ``raster.Lighting``)."""
    (light_x, light_y, light_z), (eye_x, eye_y, eye_z) = light.position, camera.eye
    specular, shininess = float(light.specular), max(float(light.shininess), 0.0)
    return raster.Lighting(
        light_x=float(light_x), light_y=float(light_y), light_z=float(light_z),
        eye_x=float(eye_x), eye_y=float(eye_y), eye_z=float(eye_z),
        ambient=float(light.ambient), diffuse=float(light.diffuse), specular=specular,
        shininess=shininess, highlight_threshold=raster.highlight_threshold(specular, shininess),
    )


def _equal(kept, given) -> bool:
    """Whether ``kept == given``, False where the comparison has no single answer (a
    camera given arrays rather than tuples compares them element by element)."""
    try:
        return bool(kept == given)
    except ValueError:
        return False


def _normal_matrix(model: np.ndarray) -> np.ndarray:
    """The normals' matrix (3, 3) for ``model``; zeros if it flattens space (scale 0), which
    leaves the model lit by the ambient term alone."""
    try:
        return normal_matrix(model)
    except np.linalg.LinAlgError:
        return np.zeros((3, 3))


def _check_mesh(vertices, normals, triangles, albedo) -> None:
    """Raise ValueError unless the arrays make a mesh the kernels can index safely (they
    do not check bounds)."""
    count = len(vertices)
    for name, array in (("vertices", vertices), ("normals", normals), ("albedo", albedo)):
        _check_shape(name, array, count)
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError(f"triangles must have shape (m, 3), got {triangles.shape}")
    if triangles.size and (triangles.min() < 0 or triangles.max() >= count):
        raise ValueError(f"triangles index vertices outside 0..{count - 1}")


def _check_shape(name: str, array, count: int) -> None:
    if np.shape(array) != (count, 3):
        raise ValueError(f"{name} must have shape ({count}, 3), got {np.shape(array)}")
