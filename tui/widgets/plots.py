"""The plots: how the muscle's shape and its numbers change as the elbow bends.

Four panels side by side, each one quantity on its own axis: the radius along the muscle
now, over its rest shape; and against every flexion the arm allows, with the current pose
marked, the length change and the moment arm, each beside OpenSim's arm26 biceps
(engine/reference.py), and the girth. Once the muscles are asked to work, a fifth: the
strongest torque they can flex the elbow with, the torque the weight in the hand and the
forearm need (where it rises above the strongest, the weight cannot be held), and the
muscles' net torque now (engine/hold.py). The numbers are engine/sweep.py's, the ones
``biceps sweep`` prints; plotext draws them (textual-plotext). The axes stay put while the
muscle changes, so a contraction shows as the profile growing and the mark moving, not as
the scale jumping. Lines are drawn in braille dots, the finest plotext has (2 x 4 a cell):
with quadrant blocks (2 x 2) a curve over a panel's few rows ran in steps a cell wide.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual_plotext import PlotextPlot

from biceps.engine.arm import Arm
from biceps.engine.config import rgb
from biceps.engine.hill import HillParameters
from biceps.engine.hold import Effort, load_at, strongest_torques
from biceps.engine.muscle import Muscle
from biceps.engine.reference import Curve, arm26_biclong
from biceps.engine.skeleton import Skeleton
from biceps.engine.sweep import Row, angles, flexion_range, sweep

CURVE_POINTS = 121
"""About one a degree across the joint's range: more than a panel has columns of braille
dots up to 60 cells wide."""
PROFILE_POINTS = 400
"""The most points a profile is drawn with: more than a plot has columns of dots even
across a wide terminal. A muscle of 16,384 nodes drawn whole took 0.2 s a change."""
MARGIN = 0.08  # of a quantity's span, left above its largest value and below its least
DOTS = "braille"

# The colours of the lines, and of their names in the titles that serve as legends.
NOW, REST = "#e06c5a", "#8c8c8c"
MODEL, REFERENCE = "#e5c07b", "#56b6c2"
GIRTH = "#e06c5a"
MARK = "#5c6370"
STRONGEST, NEEDED = "#e06c5a", "#e5c07b"


@dataclass(frozen=True)
class _Curves:
    """The sweep across the range, for one rest shape on one skeleton."""

    rows: list[Row]

    @classmethod
    def of(cls, arm: Arm) -> _Curves:
        least, most = flexion_range(arm)
        if least == most:  # limits in the config that leave one length: one point
            return cls(sweep(arm, [least]))
        return cls(sweep(arm, angles(least, most, (most - least) / (CURVE_POINTS - 1))))

    def column(self, name: str) -> np.ndarray:
        return np.array([getattr(row, name) for row in self.rows])


@dataclass(frozen=True)
class _Effort:
    """What the muscles of ``arm`` are asked to do and do (``parameters`` in the order of
    its names): the torque panel's data."""

    arm: Arm
    parameters: tuple[HillParameters, ...]
    effort: Effort
    mass: float  # kg in the hand


class Plots(Horizontal):
    """Four plots side by side; :meth:`show` redraws them for an arm."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._curves_key: tuple[object, Skeleton, float | None, float | None] | None = None
        self._curves: _Curves | None = None
        self._arm: Arm | None = None  # the arm to draw, once shown
        self._effort: _Effort | None = None  # the torque panel's, once the muscles work
        self._strongest_key: tuple | None = None
        self._strongest: np.ndarray | None = None  # (k,) N m at the curves' flexions

    def compose(self) -> ComposeResult:
        # Short enough for a quarter of 100 columns: arm26's muscle is named in the help.
        legend = f"[{MODEL}]━ model[/] [{REFERENCE}]━ arm26[/]"
        for name, title, subtitle in (
            ("profile", "radius, cm", f"[{NOW}]━ now[/] [{REST}]━ at rest[/]"),
            ("length", "length change, cm", legend),
            ("moment-arm", "moment arm, cm", legend),
            ("girth", f"[{GIRTH}]girth[/], cm", "flexion, degrees"),
            ("torque", "torque, N m", f"[{STRONGEST}]━ most[/] [{NEEDED}]━ load[/]"),
        ):
            plot = PlotextPlot(id=name)
            plot.border_title, plot.border_subtitle = title, subtitle
            yield plot

    def show(self, arm: Arm) -> None:
        """Draw the plots of ``arm``: now if they are shown, else once they are. (The sweep
        behind them is 121 length changes, 50 ms of the UI thread at 16,384 nodes.)"""
        self._arm = arm
        if self.has_class("-shown"):
            self._draw(arm)

    def show_effort(self, arm: Arm, parameters: tuple[HillParameters, ...],
                    effort: Effort | None, mass: float) -> None:
        """Draw the torque panel for what the muscles of ``arm`` do, ``effort``, asked to
        hold ``mass`` kg or not: now if the plots are shown, else once they are; hide the
        panel for no effort."""
        self.query_one("#torque").set_class(effort is not None, "-shown")
        self._effort = None if effort is None else _Effort(arm, parameters, effort, mass)
        if self._effort is not None and self.has_class("-shown") and self._arm is not None:
            self._draw_torque(self._effort, self._curves_of(self._arm))

    def toggle(self) -> None:
        """Show the plots, or hide them."""
        self.toggle_class("-shown")
        if self.has_class("-shown") and self._arm is not None:
            self._draw(self._arm)

    def _draw(self, arm: Arm) -> None:
        curves = self._curves_of(arm)
        self._draw_profile(arm.muscle, curves)
        flexions = curves.column("flexion")
        lengths = curves.column("length")
        reference = arm26_biclong()
        start = flexions[0]  # the length change is from here, the model's and arm26's
        self._draw_against_flexion(
            "length", arm.flexion, flexions, lengths - lengths[0], arm.length - lengths[0],
            reference.length_change(flexions, start), reference)
        self._draw_against_flexion(
            "moment-arm", arm.flexion, flexions, curves.column("moment_arm"), arm.moment_arm,
            np.interp(flexions, reference.flexion, reference.moment_arm), reference)
        self._draw_against_flexion(
            "girth", arm.flexion, flexions, curves.column("girth"), arm.muscle.girth)
        if self._effort is not None:
            self._draw_torque(self._effort, curves)

    def _draw_torque(self, asked: _Effort, curves: _Curves) -> None:
        arm, flexions = asked.arm, curves.column("flexion")
        # The strongest torque depends on the paths and the parameters, not on the pose: a
        # contraction only moves the mark. (The curves by identity: made again, they are new.)
        key = (id(curves), arm.paths, asked.parameters)
        if key != self._strongest_key:
            self._strongest = strongest_torques(arm, asked.parameters, flexions)
            self._strongest_key = key
        needed = np.array([load_at(arm.skeleton.forearm, flexion, asked.mass).torque
                           for flexion in flexions])
        self._draw_lines("torque", arm.flexion, flexions,
                         [(needed, NEEDED), (self._strongest, STRONGEST)],
                         asked.effort.torque, NEEDED if asked.mass > 0.0 else STRONGEST)

    def _curves_of(self, arm: Arm) -> _Curves:
        # The sweep depends on the rest shape, not on the current length: a contraction only
        # moves the mark, and only an edit (a new rest) sweeps again.
        key = (arm.muscle.rest, arm.skeleton, arm.min_length, arm.max_length)
        if key != self._curves_key:
            self._curves, self._curves_key = _Curves.of(arm), key
        return self._curves

    def _draw_profile(self, muscle: Muscle, curves: _Curves) -> None:
        plot = self.query_one("#profile", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        shown = _spread(muscle.node_count)
        rest = np.linspace(0.0, muscle.reference_length, muscle.node_count)[shown]
        plt.plot(rest.tolist(), muscle.reference_radii[shown].tolist(), marker=DOTS,
                 color=rgb(REST))
        plt.plot(muscle.positions[shown].tolist(), muscle.radii[shown].tolist(), marker=DOTS,
                 color=rgb(NOW))
        longest = max(curves.column("length").max(), muscle.reference_length)
        plt.xlim(0.0, longest)
        highest = max(curves.column("max_radius").max(), muscle.reference_radii.max())
        plt.ylim(0.0, (1 + MARGIN) * highest)
        plot.refresh()

    def _draw_against_flexion(self, name: str, flexion: float, flexions: np.ndarray,
                              values: np.ndarray, now: float,
                              reference: np.ndarray | None = None,
                              curve: Curve | None = None) -> None:
        """One quantity's ``values`` (k,) at ``flexions`` (k,), ``now`` at ``flexion``
        marked, and ``reference`` (k,), the same quantity of ``curve``, behind it."""
        colour = GIRTH if reference is None else MODEL
        lines = [] if reference is None else [(reference, REFERENCE)]
        self._draw_lines(name, flexion, flexions, [*lines, (values, colour)], now, colour)

    def _draw_lines(self, name: str, flexion: float, flexions: np.ndarray,
                    lines: list[tuple[np.ndarray, str]], now: float, colour: str) -> None:
        """Panel ``name``: each of ``lines``, values (k,) at ``flexions`` (k,) in a colour,
        the last drawn over the others, and ``now`` at ``flexion`` marked in ``colour``."""
        plot = self.query_one(f"#{name}", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        plt.vline(flexion, color=rgb(MARK))
        for values, line_colour in lines:
            plt.plot(flexions.tolist(), values.tolist(), marker=DOTS, color=rgb(line_colour))
        plt.scatter([flexion], [now], marker="●", color=rgb(colour))
        if flexions[-1] > flexions[0]:
            plt.xlim(flexions[0], flexions[-1])
        shown = np.concatenate([values for values, _ in lines] + [[now]])
        low, high = shown.min(), shown.max()
        room = MARGIN * (high - low) or MARGIN * max(abs(high), 1.0)  # one point: a span
        plt.ylim(low - room, high + room)
        plot.refresh()


def _spread(count: int) -> np.ndarray:
    """The indices of at most :data:`PROFILE_POINTS` of ``count`` nodes, evenly spread, the
    first and the last among them."""
    if count <= PROFILE_POINTS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, PROFILE_POINTS).round().astype(int))
