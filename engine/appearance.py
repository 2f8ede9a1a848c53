"""How the arm looks: the scene's mesh with each vertex's colour (albedo), the colour
scales of strain and activation, and the pick marked on it.
"""

from __future__ import annotations

import numpy as np

from biceps.engine.anatomy import arm_parts, node_places, tendon_share
from biceps.engine.arm import Arm
from biceps.engine.config import rgb
from biceps.engine.mesh import Mesh
from biceps.engine.scene import Scene
from biceps.engine.settings import RenderSettings
from biceps.engine.tension import tensed_arm


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

