"""What one picture shows: the arm, how it is viewed and lit, what is picked and how hard
the muscles work, as one immutable value.

How it looks is ``engine/appearance.py``'s, how it is framed ``engine/framing.py``'s, and
how it is drawn ``engine/scene_renderer.py``'s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from biceps.engine.arm import Arm
from biceps.engine.bounds import ACTIVATION, MASS
from biceps.engine.config import Config
from biceps.engine.errors import RefusedChange
from biceps.engine.settings import RenderSettings, View
from biceps.engine.transforms import Light


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

