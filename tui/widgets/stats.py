"""The numbers that matter as the muscle changes: length, elbow and lever, volume,
thickness."""

from __future__ import annotations

from rich.table import Table
from textual.widgets import Static

from biceps.engine.arm import Arm


class Stats(Static):
    _shown = False

    def show(self, arm: Arm) -> None:
        muscle = arm.muscle
        shortest, longest = arm.length_range()
        table = Table.grid(padding=(0, 1))
        table.add_column(style="dim", no_wrap=True)
        table.add_column(no_wrap=True)
        table.add_row("length", f"{_number(muscle.length, 2)} cm")
        table.add_row("  range", f"{_number(shortest, 2)} to {_number(longest, 2)}")
        table.add_row("flexion", f"{arm.flexion:.1f}°")
        table.add_row("moment arm", f"{_number(arm.moment_arm, 2)} cm")
        table.add_row("volume", f"{_number(muscle.volume, 3)} cm³")
        table.add_row("  with", "both end caps" if muscle.volume_mode == "closed"
                      else "no end caps")
        table.add_row("  kept to", _kept(muscle.volume_error))
        table.add_row("max radius", f"{_number(muscle.max_radius, 3)} cm")
        table.add_row("girth", f"{_number(muscle.girth, 2)} cm")
        # Always the same rows in a panel of fixed width: once laid out, a new muscle
        # needs a repaint, not a layout of the whole screen (at every step of a held key).
        self.update(table, layout=not self._shown)
        self._shown = True


def _number(value: float, decimals: int) -> str:
    """``value`` with ``decimals`` decimals where that reads well, else in four significant
    digits, so that no number the model allows (radii of 1e-6 to 1e4 cm, volumes of their
    cubes) runs past the panel's width: ``33.00``, ``1.037e+10``, ``4.189e-18``."""
    if value == 0 or 10.0 ** -decimals <= abs(value) < 1e5:
        return f"{value:.{decimals}f}"
    return f"{value:.4g}"


def _kept(error: float) -> str:
    """How closely the volume is kept, the relative error in words: ``1 part in 5e15``."""
    if error == 0:
        return "exactly"
    return f"1 part in {1 / error:.0e}".replace("e+", "e")
