"""The torque plot: across every flexion the arm allows, the strongest torque the muscles can
flex the elbow with (every flexor fully active, every extensor at its least), and the torque
the weight in the hand and the forearm need; the muscles' net torque now, marked. Where the
need rises above the strongest, the weight cannot be held. Shown with the other plots (``p``)
once the muscles are asked to work."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from textual_plotext import PlotextPlot

from biceps.engine.actuation import muscle_forces, musculotendon
from biceps.engine.arm import Arm
from biceps.engine.config import rgb
from biceps.engine.hill import HillParameters
from biceps.engine.hold import Effort, load_at
from biceps.engine.sweep import angles, flexion_range

CURVE_POINTS = 66  # every 2 degrees across the joint's range
STRONGEST, NEEDED, NOW, MARK = "#e06c5a", "#e5c07b", "#61afef", "#5c6370"


@dataclass(frozen=True)
class _Strongest:
    """The strongest flexing torque (N m) at each of ``flexions`` (degrees)."""

    flexions: list[float]
    torques: list[float]

    @classmethod
    def of(cls, arm: Arm, parameters: tuple[HillParameters, ...]) -> _Strongest:
        least, most = flexion_range(arm)
        flexions = angles(least, most, max((most - least) / (CURVE_POINTS - 1), 1e-9))
        geometry = [musculotendon(arm, flexion) for flexion in flexions]
        lengths = np.array([length for length, _ in geometry])
        moment_arms = np.array([arms for _, arms in geometry])
        least_active = np.array([p.minimum_activation for p in parameters])
        strongest = np.where(moment_arms > 0.0, 1.0, least_active)  # (k, n)
        poses = muscle_forces(arm.names, parameters, lengths, moment_arms, strongest)
        return cls(flexions, [sum(muscle.torque for muscle in pose) for pose in poses])


class TorquePlot(PlotextPlot):
    """Torque against flexion; :meth:`show` draws it for an arm and what its muscles do."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._key: tuple | None = None
        self._strongest: _Strongest | None = None
        self._wanted: tuple | None = None  # what to draw once shown

    def on_mount(self) -> None:
        self.border_title = (f"N m: [{STRONGEST}]━ strongest[/]  [{NEEDED}]━ needed[/]  "
                             f"[{NOW}]● now[/]")
        self.border_subtitle = "flexion, degrees"

    def show(self, arm: Arm, parameters: tuple[HillParameters, ...], effort: Effort | None,
             mass: float) -> None:
        """Draw the curves for ``arm`` (``parameters`` in the order of its names), the need
        of ``mass`` kg, and ``effort``'s torque; hidden for no effort."""
        self.set_class(effort is not None, "-shown")
        self._wanted = (arm, parameters, effort, mass)
        if effort is not None and self.parent is not None and self.parent.has_class("-shown"):
            self._draw()

    def on_show(self) -> None:
        if self._wanted is not None and self._wanted[2] is not None:
            self._draw()

    def _draw(self) -> None:
        arm, parameters, effort, mass = self._wanted
        # The curve depends on the paths and parameters, not on the pose: a contraction
        # only moves the mark.
        key = (arm.paths, arm.skeleton, arm.min_length, arm.max_length, parameters)
        if key != self._key:
            self._strongest, self._key = _Strongest.of(arm, parameters), key
        strongest = self._strongest
        plt = self.plt
        plt.clear_data()
        plt.vline(arm.flexion, color=rgb(MARK))
        plt.plot(strongest.flexions, strongest.torques, marker="hd", color=rgb(STRONGEST))
        needed = [load_at(arm.skeleton.forearm, flexion, mass).torque
                  for flexion in strongest.flexions]
        plt.plot(strongest.flexions, needed, marker="hd", color=rgb(NEEDED))
        plt.scatter([arm.flexion], [effort.torque], marker="●", color=rgb(NOW))
        if strongest.flexions[-1] > strongest.flexions[0]:
            plt.xlim(strongest.flexions[0], strongest.flexions[-1])
        plt.ylim(min(0.0, *strongest.torques), 1.1 * max(*strongest.torques, *needed))
        self.refresh()
