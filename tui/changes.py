"""What the keys, the mouse and the node editor do to the model, as plain functions.

Each returns a new :class:`~engine.scene.Scene` (or arm, or muscle) or raises
:class:`~engine.errors.RefusedChange` with a sentence for the user. None touches the
terminal, so they are tested without one.
"""

from __future__ import annotations

import numpy as np

from biceps.engine.arm import Arm
from biceps.engine.bounds import ACTIVATION, MASS
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.scene import Scene

TURN_STEP = 5.0  # degrees per key press
MOVE_STEP = 2.0  # cm per key press
LIGHT_STEP = 10.0  # cm per key press
ZOOM_FACTOR = 1.1  # per key press or wheel notch
SMALLEST_SCALE, LARGEST_SCALE = 0.1, 20.0
FINE_STEP, COARSE_STEP = 0.1, 1.0  # cm of muscle length per contract or stretch
EFFORT_STEP = 0.1  # activation per key press
MASS_STEP = 1.0  # kg in the hand per key press
_ROUNDING = 1e-12
# What a drag is rounded to: finer than a drag of one cell moves (some degrees, some
# millimetres), coarse enough that a saved file says yaw = 13.8, not 13.783785.
ANGLE_PLACES = 1  # a tenth of a degree
DISTANCE_PLACES = 2  # a tenth of a millimetre


def turned(scene: Scene, yaw: float = 0.0, pitch: float = 0.0, roll: float = 0.0) -> Scene:
    """The model turned by these angles (degrees), each kept within [-180, 180)."""
    view = scene.view
    return scene.with_view(
        yaw=_folded(view.yaw + yaw),
        pitch=_folded(view.pitch + pitch),
        roll=_folded(view.roll + roll),
    )


def _folded(angle: float) -> float:
    return _tidy((angle + 180.0) % 360.0 - 180.0, ANGLE_PLACES)


def _tidy(value: float, places: int = 6) -> float:
    # Rounded far below what can be seen, so that the saved file says 1.21, not
    # 1.2100000000000002, and a step forth and back returns to the same number.
    return round(value, places)


def moved(scene: Scene, right: float = 0.0, up: float = 0.0) -> Scene:
    """The model moved across the picture by ``right`` and ``up`` cm."""
    x, y, z = scene.view.offset
    return scene.with_view(
        offset=(_tidy(x + right, DISTANCE_PLACES), _tidy(y + up, DISTANCE_PLACES), z))


def zoomed(scene: Scene, steps: float) -> Scene:
    """The model scaled up by ``steps`` zoom steps (down if negative), within the limits."""
    scale = scene.view.scale
    wanted = _tidy(float(np.clip(scale * ZOOM_FACTOR**steps, SMALLEST_SCALE, LARGEST_SCALE)))
    if wanted == scale:
        which = "largest" if steps > 0 else "smallest"
        raise RefusedChange(f"the model is at its {which} scale, ×{scale:g}")
    return scene.with_view(scale=wanted)


def fitted(scene: Scene) -> Scene:
    """The view at scale 1 and unmoved, however it is turned: the camera then fits the arm,
    as posed, to the picture (``engine/framing.py``)."""
    return scene.with_view(scale=1.0, offset=(0.0, 0.0, 0.0))


def light_moved(scene: Scene, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Scene:
    """The light moved by (x, y, z) cm in world space."""
    lx, ly, lz = scene.light.position
    return scene.with_light(position=(_tidy(lx + x), _tidy(ly + y), _tidy(lz + z)))


def effort_changed(scene: Scene, activation: float = 0.0, mass: float = 0.0) -> Scene:
    """The muscles asked for ``activation`` more, or to hold ``mass`` kg more in the hand,
    stopping at the bounds (``engine/bounds.py``); :class:`RefusedChange` saying so if
    already there."""
    wanted = (_tidy(min(max(scene.activation + activation, ACTIVATION.low), ACTIVATION.high)),
              _tidy(min(max(scene.mass + mass, MASS.low), MASS.high)))
    if wanted == (scene.activation, scene.mass):
        if activation:
            raise RefusedChange("Every muscle is fully active already: activation 1"
                                if activation > 0 else
                                "Every muscle is at rest already: activation 0")
        raise RefusedChange(f"The hand holds the most it may already, {MASS.high:g} kg"
                            if mass > 0 else "The hand holds nothing already")
    return scene.with_effort(*wanted)


def with_shading_switched(scene: Scene) -> Scene:
    """Gouraud shading becomes Phong and back."""
    return scene.with_render(shading="phong" if scene.render.shading == "gouraud" else "gouraud")


def with_antialiasing_switched(scene: Scene) -> Scene:
    """Supersampling on (2 x 2) when it is off, off when it is on at any level."""
    return scene.with_render(ssaa=1 if scene.render.ssaa > 1 else 2)


def length_changed(arm: Arm, change: float) -> tuple[Arm, str | None]:
    """The muscle ``change`` cm longer (shorter if negative), stopping at a limit.

    Returns the new arm and, when a limit stopped it, the sentence saying which.
    """
    return arm.towards(_tidy(arm.length + change))


SLOW_NODES = 5_000
"""Nodes beyond which the picture follows a change of length slowly: each change rebuilds a
mesh of that many rings, lying on the bones (0.17 s a frame at 3,585 nodes, 0.3 s at 7,169,
0.6 s at 14,337, at 172x68 pixels on two shared cores); the numbers and the table stay
quick."""


def with_node(muscle: Muscle, index: int, radius: float, growth: float) -> Muscle:
    """The muscle with node ``index`` (0-based) at ``radius`` cm and ``growth``.

    A value equal to the current one is left alone, so confirming an untouched edit does
    not redefine the muscle's rest shape; the muscle refuses a value outside the bounds
    (engine/bounds.py), saying what is allowed. The node may be gone by the time the edit
    comes (deleted by a key typed while the dialog was open): that is refused too.
    """
    if not 0 <= index < muscle.node_count:
        raise RefusedChange(f"node {index + 1} is no longer there: the muscle has "
                            f"{muscle.node_count} nodes now")
    if radius != muscle.radii[index]:
        muscle = muscle.with_radius(index, radius)
    if growth != muscle.growth[index]:
        muscle = muscle.with_growth(index, growth)
    return muscle


def has_unsaved_edits(scene: Scene, saved: Scene) -> bool:
    """Whether the model in ``scene`` differs from the one last saved (or opened) as
    ``saved``. The view, the light and the picture's settings are saved with it, but are
    not edits that quitting should ask about."""
    return not _same_arm(scene.arm, saved.arm)


def _same_arm(a: Arm, b: Arm) -> bool:
    return ((a.skeleton, a.min_length, a.max_length, a.names)
            == (b.skeleton, b.min_length, b.max_length, b.names)
            and all(map(_same_muscle, a.muscles, b.muscles)))


def _same_muscle(first: Muscle, second: Muscle) -> bool:
    # By value, to a rounding error: contracting and stretching back makes a new muscle whose
    # radii, solved again from the rest shape, may differ from it in the last bit.
    return (
        first.volume_mode == second.volume_mode
        and first.node_count == second.node_count
        and np.isclose(first.length, second.length, rtol=_ROUNDING, atol=0.0)
        and np.isclose(first.reference_length, second.reference_length, rtol=_ROUNDING,
                       atol=0.0)
        and np.allclose(first.reference_radii, second.reference_radii, rtol=_ROUNDING, atol=0.0)
        and np.array_equal(first.growth, second.growth)
    )
