"""Scenes drawn: the supersampling a picture gets, and a renderer that keeps the last
scene's mesh, colours and outline, so that frames that only turn, move or relight the
model rebuild none of them.
"""

from __future__ import annotations

from concurrent.futures import Executor
from typing import Callable

import numpy as np

from biceps.engine.appearance import Spans, marked_albedo, scene_mesh
from biceps.engine.config import rgb
from biceps.engine.cost import check_picture
from biceps.engine.framing import outline, view_camera, zoomed_light
from biceps.engine.mesh import Mesh
from biceps.engine.render import Renderer
from biceps.engine.scene import Scene
from biceps.engine.settings import SUPERSAMPLING, RenderSettings

SMALL_PICTURE = 120
"""Pixel rows at or below which a picture is drawn with twice the supersampling each way
(2 x 2 without anti-aliasing, 4 x 4 with). In a small picture (80x24, or the arm zoomed
out) the bones are about a pixel thick: sampled once a pixel they fall between pixel
centres and break into pieces, where four samples a pixel keep them whole; and a picture
this small costs little four or sixteen times over. Doubled rather than raised to 2, so
that anti-aliasing on still smooths the edges further (``m`` changes the picture)."""


def supersampling(render: RenderSettings, height: int) -> int:
    """The supersampling a picture ``height`` pixels tall is drawn with."""
    if height <= SMALL_PICTURE:
        return min(2 * render.ssaa, int(SUPERSAMPLING.high))
    return render.ssaa



class SceneRenderer:
    """Turns scenes into pictures, reusing its buffers and the last mesh between frames.

    Not thread-safe: give each thread its own. Draws on a pool of threads of its own, which
    :meth:`close` stops (or leaving a ``with`` block), unless given one to share.
    """

    def __init__(self, pool: Executor | None = None,
                 wait_for_kernels: Callable[[], None] | None = None) -> None:
        """``pool``: threads to share with other renderers (``raster/bands.py``'s
        `band_pool`), shut down by whoever made it. ``wait_for_kernels``: called first,
        returning once kernels being compiled elsewhere are in numba's cache (the children
        an entry point started, ``engine/coldstart.py``), so that this renderer loads them
        rather than compiling them again."""
        if wait_for_kernels is not None:
            wait_for_kernels()
        self._renderer = Renderer(pool=pool)
        self._mesh_key: tuple | None = None
        self._mesh: tuple[Mesh, np.ndarray, Spans] | None = None
        self._outline: np.ndarray | None = None
        self._marked_key: tuple | None = None
        self._marked: np.ndarray | None = None

    def render(self, scene: Scene, width: int, height: int,
               framed: np.ndarray | None = None, pixel_aspect: float = 1.0) -> np.ndarray:
        """The picture of ``scene``: (height, width, 3) uint8, valid until the next call;
        :class:`BicepsError` if its buffers would take more memory than the bound. Its
        pixels are shown ``pixel_aspect`` as wide as they are tall.

        ``framed``: the points (k, 3), world space at rest, the camera fits to the picture
        (and the view turns about the middle of); the scene's own `outline` if None. A
        cycle passes the outlines of all its poses, so that every frame has one camera.
        """
        ssaa = supersampling(scene.render, height)
        check_picture(width, height, ssaa)
        mesh, albedo = self._mesh_of(scene)
        framed = self._outline if framed is None else framed
        camera, model = view_camera(scene.view, framed, width * pixel_aspect / height)
        light = zoomed_light(scene.light, scene.view.scale, camera)
        return self._renderer.render(
            mesh.vertices, mesh.normals, mesh.triangles, albedo, model, camera,
            light, width, height, shading=scene.render.shading,
            ssaa=ssaa, background=rgb(scene.render.background), pixel_aspect=pixel_aspect,
        )  # fmt: skip

    def close(self) -> None:
        """Stop the threads of the renderer's own pool, if it started one."""
        self._renderer.close()

    def __enter__(self) -> SceneRenderer:
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def outline(self, scene: Scene) -> np.ndarray:
        """The `outline` (k, 3) of ``scene``'s mesh, world space at rest."""
        self._unmarked_mesh_of(scene)
        return self._outline

    def _mesh_of(self, scene: Scene) -> tuple[Mesh, np.ndarray]:
        """The mesh of ``scene`` and its albedo, marked if the scene is."""
        mesh, albedo, spans = self._unmarked_mesh_of(scene)
        if not scene.marked:
            return mesh, albedo
        # Moving the node table's cursor colours a few vertices: the mesh is kept.
        key = (self._mesh_key, scene.selected, scene.picked_node)
        if key != self._marked_key:
            self._marked = marked_albedo(scene, mesh, albedo, spans)
            self._marked_key = key
        return mesh, self._marked

    def _unmarked_mesh_of(self, scene: Scene) -> tuple[Mesh, np.ndarray, Spans]:
        # Turning, moving and lighting leave the mesh as it was: rebuild it only when the
        # arm or its look changes.
        render = scene.render
        # The arm compares its muscle by identity (a new muscle is a new object), and the
        # key holds the arm, so the identity cannot be reused by another.
        key = (scene.arm, render.segments, render.muscle_colour, render.tendon_colour,
               render.bone_colour, render.colour_by, scene.hidden, scene.activations)
        if key != self._mesh_key:
            self._mesh = scene_mesh(scene.arm, render, scene.hidden, scene.activations)
            self._outline = outline(self._mesh[0].vertices)
            self._mesh_key = key
        return self._mesh
