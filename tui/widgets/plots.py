"""The plots: how the muscle's shape and its numbers change as the elbow bends.

Left, the radius along the muscle now, over its rest shape; right, the length, girth and
moment arm across every flexion the arm allows, with the current pose marked. The numbers are
engine/sweep.py's, the ones ``biceps sweep`` prints; plotext draws them (textual-plotext).
The axes stay put while the muscle changes, so a contraction shows as the profile growing
and the mark moving, not as the scale jumping. Lines are drawn with quadrant blocks rather
than braille: fonts that lack braille, or space it unevenly, are common, and a terminal that
shows the half-block picture shows these.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual_plotext import PlotextPlot

from biceps.engine.arm import Arm
from biceps.engine.config import rgb
from biceps.engine.muscle import Muscle
from biceps.engine.skeleton import Skeleton
from biceps.engine.sweep import Row, angles, flexion_range, sweep

CURVE_POINTS = 121  # about one a degree across the joint's range
PROFILE_POINTS = 400
"""The most points a profile is drawn with: more than a plot has columns of quadrant pixels
even across a wide terminal. A muscle of 16,384 nodes drawn whole took 0.2 s a change."""
MARGIN = 1.08  # room above the largest value and below the smallest
# The right axis (girth, moment arm) reaches to twice the largest girth, so that the girth's
# nearly level line runs across the middle, where the length falls fastest: the two lines
# cross there, instead of running along each other near the top.
RIGHT_HEADROOM = 2.0

# The colours of the lines, and of their names in the titles that serve as legends.
NOW, REST = "#e06c5a", "#8c8c8c"
LENGTH, GIRTH, MOMENT_ARM = "#e5c07b", "#e06c5a", "#61afef"
MARK = "#5c6370"


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

    def column(self, name: str) -> list[float]:
        return [getattr(row, name) for row in self.rows]


class Plots(Horizontal):
    """Two plots side by side; :meth:`show` redraws them for an arm."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._curves_key: tuple[object, Skeleton, float | None, float | None] | None = None
        self._curves: _Curves | None = None
        self._arm: Arm | None = None  # the arm to draw, once shown

    def compose(self) -> ComposeResult:
        profile = PlotextPlot(id="profile")
        profile.border_title = f"radius, cm: [{NOW}]━ now[/]  [{REST}]━ at rest[/]"
        profile.border_subtitle = "along the muscle, cm"
        curves = PlotextPlot(id="curves")
        curves.border_title = (f"cm: [{LENGTH}]━ length[/]  [{GIRTH}]━ girth[/]  "
                               f"[{MOMENT_ARM}]━ moment arm[/]")
        curves.border_subtitle = "flexion, degrees · length: left axis"
        yield profile
        yield curves

    def show(self, arm: Arm) -> None:
        """Draw the plots of ``arm``: now if they are shown, else once they are. (The sweep
        behind them is 121 length changes, 50 ms of the UI thread at 16,384 nodes.)"""
        self._arm = arm
        if self.has_class("-shown"):
            self._draw(arm)

    def toggle(self) -> None:
        """Show the plots, or hide them."""
        self.toggle_class("-shown")
        if self.has_class("-shown") and self._arm is not None:
            self._draw(self._arm)

    def _draw(self, arm: Arm) -> None:
        curves = self._curves_of(arm)
        self._draw_profile(arm.muscle, curves)
        self._draw_curves(arm, curves)

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
        plt.plot(rest.tolist(), muscle.reference_radii[shown].tolist(), marker="hd",
                 color=rgb(REST))
        plt.plot(muscle.positions[shown].tolist(), muscle.radii[shown].tolist(), marker="hd",
                 color=rgb(NOW))
        longest = max(max(curves.column("length")), muscle.reference_length)
        plt.xlim(0.0, longest)
        plt.ylim(0.0, MARGIN * max(curves.column("max_radius") + [muscle.reference_radii.max()]))
        plot.refresh()

    def _draw_curves(self, arm: Arm, curves: _Curves) -> None:
        plot = self.query_one("#curves", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        flexions = curves.column("flexion")
        plt.vline(arm.flexion, color=rgb(MARK))
        now = {"length": arm.length, "girth": arm.muscle.girth, "moment_arm": arm.moment_arm}
        # The length last, so that where the lines cross it is drawn over the others.
        for name, colour, side in (("girth", GIRTH, "right"), ("moment_arm", MOMENT_ARM, "right"),
                                   ("length", LENGTH, "left")):
            plt.plot(flexions, curves.column(name), marker="hd", color=rgb(colour), yside=side)
            plt.scatter([arm.flexion], [now[name]], marker="●", color=rgb(colour), yside=side)
        if flexions[-1] > flexions[0]:
            plt.xlim(flexions[0], flexions[-1])
        lengths = curves.column("length")
        plt.ylim(min(lengths) / MARGIN, max(lengths) * MARGIN, yside="left")
        plt.ylim(0.0, RIGHT_HEADROOM * max(curves.column("girth")), yside="right")
        plot.refresh()


def _spread(count: int) -> np.ndarray:
    """The indices of at most :data:`PROFILE_POINTS` of ``count`` nodes, evenly spread, the
    first and the last among them."""
    if count <= PROFILE_POINTS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, PROFILE_POINTS).round().astype(int))
