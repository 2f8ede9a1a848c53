"""What the keys, the mouse and the node editor do to the model, as plain functions.

Each returns a new :class:`~engine.scene.Scene` (or muscle) or raises
:class:`~engine.errors.RefusedChange` with a sentence for the user. None touches the
terminal, so they are tested without one.
"""

from __future__ import annotations

import numpy as np

from biceps.engine.arm import Arm
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.scene import Scene

TURN_STEP = 5.0  # degrees per key press
MOVE_STEP = 2.0  # cm per key press
LIGHT_STEP = 10.0  # cm per key press
ZOOM_FACTOR = 1.1  # per key press or wheel notch
SMALLEST_SCALE, LARGEST_SCALE = 0.1, 20.0
FINE_STEP, COARSE_STEP = 0.1, 1.0  # cm of muscle length per contract or stretch
_ROUNDING = 1e-12


def turned(scene: Scene, yaw: float = 0.0, pitch: float = 0.0, roll: float = 0.0) -> Scene:
    """The model turned by these angles (degrees), each kept within [-180, 180)."""
    view = scene.view
    return scene.with_view(
        yaw=_folded(view.yaw + yaw),
        pitch=_folded(view.pitch + pitch),
        roll=_folded(view.roll + roll),
    )


def _folded(angle: float) -> float:
    return _tidy((angle + 180.0) % 360.0 - 180.0)


def _tidy(value: float) -> float:
    # Rounded far below what can be seen, so that the saved file says 1.21, not
    # 1.2100000000000002, and a step forth and back returns to the same number.
    return round(value, 6)


def moved(scene: Scene, right: float = 0.0, up: float = 0.0) -> Scene:
    """The model moved across the picture by ``right`` and ``up`` cm."""
    x, y, z = scene.view.offset
    return scene.with_view(offset=(_tidy(x + right), _tidy(y + up), z))


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
    as posed, to the picture (``engine/scene.py``)."""
    return scene.with_view(scale=1.0, offset=(0.0, 0.0, 0.0))


def light_moved(scene: Scene, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Scene:
    """The light moved by (x, y, z) cm in world space."""
    lx, ly, lz = scene.light.position
    return scene.with_light(position=(_tidy(lx + x), _tidy(ly + y), _tidy(lz + z)))


def with_shading_switched(scene: Scene) -> Scene:
    """Gouraud shading becomes Phong and back."""
    return scene.with_render(shading="phong" if scene.render.shading == "gouraud" else "gouraud")


def with_antialiasing_switched(scene: Scene) -> Scene:
    """Supersampling on (2 x 2) when it is off, off when it is on at any level."""
    return scene.with_render(ssaa=1 if scene.render.ssaa > 1 else 2)


def length_changed(scene: Scene, change: float) -> tuple[Scene, str | None]:
    """The muscle ``change`` cm longer (shorter if negative), stopping at a limit.

    Returns the new scene and, when a limit stopped it, the sentence saying which.
    """
    arm, note = scene.arm.stepped(change)
    return scene.with_arm(arm), note


def with_node(muscle: Muscle, index: int, radius: float, growth: float) -> Muscle:
    """The muscle with node ``index`` (0-based) at ``radius`` cm and ``growth``.

    A value equal to the current one is left alone, so confirming an untouched edit does
    not redefine the muscle's rest shape.
    """
    if radius != muscle.radii[index]:
        muscle = muscle.with_radius(index, radius)
    if growth != muscle.growth[index]:
        muscle = muscle.with_growth(index, growth)
    return muscle


def differs_from_saved(scene: Scene, saved: Scene) -> bool:
    """Whether saving ``scene`` would change the file last saved (or opened) as ``saved``."""
    settings = (scene.view, scene.light, scene.render)
    saved_settings = (saved.view, saved.light, saved.render)
    return settings != saved_settings or not _same_arm(scene.arm, saved.arm)


def _same_arm(a: Arm, b: Arm) -> bool:
    # By value, to a rounding error: contracting and stretching back makes a new muscle whose
    # radii, solved again from the rest shape, may differ from it in the last bit.
    return (
        (a.skeleton, a.min_length, a.max_length) == (b.skeleton, b.min_length, b.max_length)
        and a.muscle.volume_mode == b.muscle.volume_mode
        and a.muscle.node_count == b.muscle.node_count
        and np.isclose(a.muscle.length, b.muscle.length, rtol=_ROUNDING, atol=0.0)
        and np.allclose(a.muscle.radii, b.muscle.radii, rtol=_ROUNDING, atol=0.0)
        and np.array_equal(a.muscle.growth, b.muscle.growth)
    )
