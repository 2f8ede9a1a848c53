"""What one picture shows: the arm, how it is viewed and lit, and how it is rendered.

The camera frames the arm as it is posed and turned: it looks at the middle of the turned
arm's extent, from as close as keeps every vertex within ``FILL`` of the picture's edges
(`fit_points`), so the arm is as large as the picture allows, centred, in every
pose. The view turns the model about the centre of its bounding box, moves it by its offset,
then scales it about the point the camera looks at: zooming grows the picture about its
own centre, wherever the model was moved, and never pushes the middle of the arm out. The
light, which stays put as the model turns, scales with it, so zooming does not relight it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from biceps.engine import coldstart
from biceps.engine.anatomy import arm_parts, node_places, tendon_share
from biceps.engine.arm import Arm
from biceps.engine.bounds import ACTIVATION, MASS
from biceps.engine.config import Config, rgb
from biceps.engine.cost import check_picture
from biceps.engine.errors import RefusedChange
from biceps.engine.jit import exact, ngjit
from biceps.engine.mesh import Mesh
from biceps.engine.render import Renderer
from biceps.engine.settings import SUPERSAMPLING, RenderSettings, View
from biceps.engine.tension import tensed_arm
from biceps.engine.transforms import (Camera, Light, model_matrix, scale_matrix,
                                      transform_points, translation_matrix)

FILL = 0.9
"""The share of the picture's half-width or half-height the arm reaches, whichever is less."""


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


@dataclass(frozen=True)
class Scene:
    """Everything a frame depends on; immutable, so a render thread can hold one safely.

    Each setting checks its rules when it is made, so ``with_view(scale=-3)`` raises
    :class:`~engine.errors.SettingError` rather than making a scene that cannot be drawn
    or saved.
    """

    arm: Arm
    view: View
    light: Light
    render: RenderSettings
    hidden: frozenset[str] = frozenset()  # the names of the muscles not shown
    selected: int = 0  # which of the arm's muscles the node table edits (0: the driver)
    marked: bool = False  # the picture marks the pick (`marked_albedo`), as the app's do
    picked_node: int | None = None  # the selected muscle's node ringed, if marked
    # What the muscles are asked to do: every one at ``activation`` (0 to 1), or, with a
    # ``mass`` (kg) in the hand, hold it with the least effort (engine/hold.py).
    activation: float = 0.0
    mass: float = 0.0
    # Each muscle's activation that follows, 0 to 1, in the order of the arm's names; none:
    # all at rest. An active belly is drawn tensed (engine/tension.py), and coloured by it
    # if asked.
    activations: tuple[float, ...] = ()

    @classmethod
    def of(cls, config: Config) -> Scene:
        return cls(config.arm, config.view, config.light, config.render)

    def with_view(self, **changes) -> Scene:
        return replace(self, view=replace(self.view, **changes))

    def with_light(self, **changes) -> Scene:
        return replace(self, light=replace(self.light, **changes))

    def with_render(self, **changes) -> Scene:
        return replace(self, render=replace(self.render, **changes))

    def with_arm(self, arm: Arm) -> Scene:
        return replace(self, arm=arm)

    def with_selected(self, index: int) -> Scene:
        """The scene with muscle ``index`` of the arm's (counted round) picked for editing."""
        return replace(self, selected=index % len(self.arm.names))

    def with_picked_node(self, node: int | None) -> Scene:
        """The scene with node ``node`` of the selected muscle ringed (None: no node)."""
        return replace(self, picked_node=node)

    def unmarked(self) -> Scene:
        """The scene as a picture of the model alone, without the pick marked (an export)."""
        return replace(self, marked=False)

    def with_hidden(self, name: str, hide: bool) -> Scene:
        """The scene with muscle ``name`` hidden or shown."""
        return replace(self, hidden=self.hidden | {name} if hide else self.hidden - {name})

    def with_effort(self, activation: float | None = None, mass: float | None = None) -> Scene:
        """The scene with the muscles asked for another ``activation`` or to hold another
        ``mass``, each within its bounds (``engine/bounds.py``), or :class:`RefusedChange`."""
        activation = self.activation if activation is None else activation
        mass = self.mass if mass is None else mass
        for value, limits, what in ((activation, ACTIVATION, "an activation"),
                                    (mass, MASS, "a mass in the hand")):
            if not limits.allows(value):
                raise RefusedChange(f"{what} is {limits.of('')}, not {value:g}")
        return replace(self, activation=float(activation), mass=float(mass))

    def with_activations(self, activations: tuple[float, ...]) -> Scene:
        """The scene with each muscle at its activation (in the order of the arm's names)."""
        return replace(self, activations=tuple(float(a) for a in activations))


COMPANION_DETAIL = 2 / 3
"""The share of the render's segments drawn round each companion (48 -> 32): the pictures'
level of detail, never the exported meshes'. A ring of 32 misses its circle by
r (1 - cos(360 / 64 degrees)), 0.012 cm for the thickest companion (2.6 cm contracted), a
few tenths of a pixel at 1080p with the arm filling the picture; shaded with the circle's
normals, only the outline could show it, and side by side it does not. Volumes are the
nodes' (SPEC 2), whatever the mesh. The six at 1080p: 51,136 triangles, not 64,800."""


def companion_segments(segments: int) -> int:
    """The segments round each companion in a picture drawn with ``segments`` round the
    driver and the bones (`COMPANION_DETAIL`), 3 at least."""
    return max(3, round(segments * COMPANION_DETAIL))


Spans = dict[str, tuple[int, int]]
"""Each part's vertices in a scene's mesh, by its name: the first and one past the last."""


def scene_mesh(arm: Arm, render: RenderSettings, hidden: frozenset[str] = frozenset(),
               activations: tuple[float, ...] = ()) -> tuple[Mesh, np.ndarray, Spans]:
    """The arm as one world-space mesh, its per-vertex albedo (n, 3) float32 in [0, 1] and
    its parts' spans: the bones in the bone colour, each muscle not ``hidden`` with its
    belly in its own colour (or its strain's, see `strain_colour`, or its activation's,
    `activation_colour`) blending into the tendon colour towards its ends; each belly
    tensed by its activation (``activations`` in the order of the arm's names, none for a
    muscle at rest)."""
    strains = [muscle.length / muscle.reference_length - 1.0 for muscle in arm.muscles]
    arm = tensed_arm(arm, activations)
    parts = arm_parts(arm, render.segments, hidden, companion_segments(render.segments))
    ends = np.cumsum([len(mesh.vertices) for mesh in parts.values()])
    spans = dict(zip(parts, zip([0, *ends[:-1]], ends)))
    # Component-major, the renderer's layout (engine/raster/__init__.py), a channel at a time:
    # numpy's loops over rows of three are far slower.
    albedo = np.empty((3, ends[-1]), np.float32)
    albedo[:] = _unit_rgb(render.bone_colour)[:, None]
    tendon_colour = _unit_rgb(render.tendon_colour)
    colours = (render.muscle_colour, *(companion.colour for companion in arm.companions))
    flexion = arm.flexion  # worked out from the length at each read: read once
    for index, (name, muscle, path, colour) in enumerate(
            zip(arm.names, arm.muscles, arm.paths, colours)):
        if name in hidden:
            continue
        if render.colour_by == "strain":
            belly = strain_colour(strains[index])
        elif render.colour_by == "activation":
            belly = activation_colour(activations[index] if activations else 0.0)
        else:
            belly = _unit_rgb(colour)
        tendon = tendon_share(muscle, path, flexion, parts[name])
        not_tendon = 1.0 - tendon
        start, end = spans[name]
        for channel, out in enumerate(albedo[:, start:end]):
            np.multiply(not_tendon, belly[channel], out=out)
            out += tendon * tendon_colour[channel]
    return Mesh.concatenate(list(parts.values())), albedo.T, spans


PICK_LIGHTER = 0.4
"""How far the picked muscle's colour goes towards white, among others: enough to find it
at a glance in 256 colours, not so far that its shading flattens."""
RING_COLOUR = np.array([1.0, 0.82, 0.0], dtype=np.float32)
"""The picked node's ring: a yellow no muscle, tendon or bone is drawn in."""


def marked_albedo(scene: Scene, mesh: Mesh, albedo: np.ndarray, spans: Spans) -> np.ndarray:
    """``albedo`` (n, 3) of ``scene``'s ``mesh`` with its pick marked, a new array: the
    selected muscle lighter when other muscles are shown, and its picked node's ring (the
    vertices within half a node of it, fading out from it) in `RING_COLOUR`."""
    arm = scene.arm
    name = arm.names[scene.selected]
    if name in scene.hidden:
        return albedo
    start, end = spans[name]
    marked = albedo.copy()
    part = marked[start:end]
    if len(arm.names) - len(scene.hidden) > 1:
        part += PICK_LIGHTER * (1.0 - part)
    muscle = arm.muscles[scene.selected]
    node = scene.picked_node
    if node is not None and 0 <= node < muscle.node_count:
        places = node_places(muscle, arm.paths[scene.selected], arm.flexion,
                             mesh.vertices[start:end])
        ring = np.clip(1.0 - 2.0 * np.abs(places - node), 0.0, 1.0).astype(np.float32)
        part += ring[:, None] * (RING_COLOUR - part)
    return marked


STRAIN_SPAN = 0.2
"""The strain (length over rest length, less 1) at which the strain colour is at its
warmest (shortened by this much) or coolest (lengthened by this much)."""
_NEUTRAL = np.array([0.78, 0.72, 0.70], dtype=np.float32)
_WARM = np.array([0.93, 0.33, 0.12], dtype=np.float32)  # shortened: orange-red
_COOL = np.array([0.20, 0.45, 0.90], dtype=np.float32)  # lengthened: blue


def strain_colour(strain: float) -> np.ndarray:
    """(3,) float32 in [0, 1]: a muscle's colour ``strain`` from its rest length: neutral at
    rest, warmer as it shortens, cooler as it lengthens (a diverging scale)."""
    amount = min(abs(strain) / STRAIN_SPAN, 1.0)
    end = _WARM if strain < 0 else _COOL
    return (1.0 - amount) * _NEUTRAL + amount * end


_AMBER = np.array([0.98, 0.70, 0.15], dtype=np.float32)
_RED = np.array([0.85, 0.08, 0.10], dtype=np.float32)


def activation_colour(activation: float) -> np.ndarray:
    """(3,) float32 in [0, 1]: a muscle's colour at ``activation`` (0 to 1): neutral at rest,
    amber at half, red at full (a sequential scale, as a heat map)."""
    amount = min(max(activation, 0.0), 1.0)
    if amount <= 0.5:
        return (1.0 - 2.0 * amount) * _NEUTRAL + 2.0 * amount * _AMBER
    return (2.0 - 2.0 * amount) * _AMBER + (2.0 * amount - 1.0) * _RED


def _unit_rgb(colour: str) -> np.ndarray:
    return np.array(rgb(colour), dtype=np.float32) / 255.0


def outline(vertices: np.ndarray, directions: int = 256, stride: int = 4) -> np.ndarray:
    """The vertices (k, 3), k <= ``directions``, farthest out along directions spread evenly
    over the sphere (a Fibonacci lattice), among every ``stride``-th of ``vertices`` (n, 3):
    all that framing needs of them.

    Neighbouring directions are at most about 13 degrees apart, so no vertex stands out of
    the outline's hull by more than 1 - cos(6.5 degrees), 0.7 %, of the arm's reach; and
    every 4th vertex of a ring of 48 misses the ring's outermost point by at most
    1 - cos(15 degrees) of the ring's radius, a few tenths of a millimetre: both far inside
    the margin `FILL` leaves. Framing a few hundred points instead of every vertex takes a
    fraction of a millisecond instead of several, and the outline itself 2 ms.
    """
    index = np.arange(directions) + 0.5
    height = 1.0 - 2.0 * index / directions
    turn = np.pi * (1.0 + 5.0**0.5) * index
    ring = np.sqrt(1.0 - height**2)
    lattice = np.array([ring * np.cos(turn), height, ring * np.sin(turn)])  # (3, k)
    some = vertices[::stride]
    # Reduced along rows of one coordinate each: numpy reduces the columns of rows of three
    # far more slowly (the same extremes: min and max do not round).
    coordinates = some.T.copy()
    centre = (coordinates.min(axis=1) + coordinates.max(axis=1)) / 2.0
    farthest, best = np.empty(directions, np.int64), np.empty(directions)
    _farthest_along(lattice, np.ascontiguousarray(some - centre), farthest, best)
    return some[np.unique(farthest)]


@ngjit
def _farthest_along(directions, points, farthest, best):
    """For each of ``directions`` (3, k), by component, the index into ``points`` (m, 3) of
    the first one farthest along it, into ``farthest`` (k,) int64; ``best`` (k,) float64 is
    working space. A kernel, not numpy: einsum holds the GIL for all its run, 45 ms at 5,000
    nodes, and the app's keys wait that long; BLAS's threads took tens of milliseconds to
    start on a busy machine. The directions are the inner loop, each component a contiguous
    row, so that LLVM runs it on several directions at once (SIMD): 2.1 -> 0.36 ms for the
    six muscles' 8,100 points, the same indices."""
    best[:] = -np.inf
    farthest[:] = 0
    for i in range(points.shape[0]):
        x, y, z = points[i, 0], points[i, 1], points[i, 2]
        for k in range(directions.shape[1]):
            reach = directions[0, k] * x + directions[1, k] * y + directions[2, k] * z
            if reach > best[k]:
                best[k], farthest[k] = reach, i


def fit_points(points, aspect: float, fov_y_deg: float = 35.0, fill: float = 0.9,
               scale: float = 1.0) -> Camera:
    """The tightest centred framing of ``points`` (n, 3) (world space): a camera on their
    ``+z`` side looking down ``-z``, as close as it can be with every point within ``fill``
    of the view's half-width and half-height, aimed so that their picture is centred.

    aspect: width / height of the view. ``scale`` (the model's zoom about the target) only
    pushes the far plane out so a scaled-up model is not cut off.

    From an eye at ``(cx, cy, e)``, a point ``(x, y, z)`` is in view when
    ``|x - cx| <= (e - z) tan_x`` and ``|y - cy| <= (e - z) tan_y``: for a given aim the
    least ``e`` is the largest of ``z + |x - cx| / tan_x`` and ``z + |y - cy| / tan_y`` over
    the points, exact in perspective. Aimed first at the middle of the points' extents, the
    picture of a deep model is off centre (its near end looks larger), so the aim then moves
    by the picture's own offset, a few times over.
    """
    points = np.asarray(points, dtype=np.float64)
    low, high = points.min(axis=0), points.max(axis=0)
    aim = (low + high) / 2.0
    tan_y = math.tan(math.radians(fov_y_deg) / 2.0) * fill
    eye_z = _aim(np.ascontiguousarray(points), tan_y * aspect, tan_y, aim)
    distance = eye_z - aim[2]
    reach = float(np.linalg.norm(high - low)) / 2.0
    return Camera(
        eye=(float(aim[0]), float(aim[1]), eye_z),
        target=tuple(float(c) for c in aim), fov_y_deg=fov_y_deg,
        near=0.05 * distance, far=distance + 8.0 * reach * max(scale, 1.0),
    )


@exact
def _aim(points, tan_x, tan_y, aim):
    """Move ``aim`` (3,) float64, the middle of ``points``' (n, 3) extents, by the picture's
    own offset four times over (see :func:`fit_points`); the least eye ``z`` for that aim.
    A kernel: numpy took 0.1 ms a frame (at 60 a second) on the outline's hundred-odd
    points, in thirty calls on arrays of two columns."""
    for _ in range(4):
        eye_z = _least_eye_z(points, tan_x, tan_y, aim)
        low_x = low_y = np.inf
        high_x = high_y = -np.inf
        for i in range(points.shape[0]):
            depth = eye_z - points[i, 2]
            # each point's place in the picture, in tan
            seen_x, seen_y = (points[i, 0] - aim[0]) / depth, (points[i, 1] - aim[1]) / depth
            # (numpy's minimum and maximum, which keep a NaN, as its reductions do)
            low_x, high_x = np.minimum(low_x, seen_x), np.maximum(high_x, seen_x)
            low_y, high_y = np.minimum(low_y, seen_y), np.maximum(high_y, seen_y)
        aim[0] += (low_x + high_x) / 2.0 * (eye_z - aim[2])
        aim[1] += (low_y + high_y) / 2.0 * (eye_z - aim[2])
    return _least_eye_z(points, tan_x, tan_y, aim)


@exact
def _least_eye_z(points, tan_x, tan_y, aim):
    """The least eye ``z`` from which every one of ``points`` is in view, aimed at ``aim``."""
    eye_z = -np.inf
    for i in range(points.shape[0]):
        reach = np.maximum(abs(points[i, 0] - aim[0]) / tan_x,
                           abs(points[i, 1] - aim[1]) / tan_y)
        eye_z = np.maximum(eye_z, points[i, 2] + reach)
    return eye_z


def view_camera(view: View, vertices: np.ndarray, aspect: float) -> tuple[Camera, np.ndarray]:
    """The camera framing ``vertices`` (n, 3), world space at rest, turned by ``view``, at
    this width / height; and the model matrix (4, 4) that turns, moves and scales them.
    (Pass the `outline` of a mesh's vertices: it frames them as well, and faster.)"""
    pivot = (vertices.min(axis=0) + vertices.max(axis=0)) / 2.0
    turn = model_matrix(np.radians(view.yaw), np.radians(view.pitch), np.radians(view.roll),
                        pivot=pivot)
    camera = fit_points(transform_points(turn, vertices), aspect, view.fov, FILL, view.scale)
    target = np.array(camera.target)
    model = (translation_matrix((1.0 - view.scale) * target) @ scale_matrix(view.scale)
             @ translation_matrix(view.offset) @ turn)
    return camera, model


def zoomed_light(light: Light, scale: float, camera: Camera) -> Light:
    """``light`` scaled with the model about the point the camera looks at, so that zooming
    magnifies the picture without relighting it (a light left where it was would end up
    inside a model zoomed eight times)."""
    target = np.array(camera.target)
    position = target + scale * (np.array(light.position) - target)
    return replace(light, position=tuple(position.tolist()))


class SceneRenderer:
    """Turns scenes into pictures, reusing its buffers and the last mesh between frames.

    Not thread-safe: give each thread its own.
    """

    def __init__(self) -> None:
        coldstart.wait_for_aside()  # load, rather than compile again, what a child compiles
        self._renderer = Renderer()
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
