"""The numbers that matter as the muscle changes: length, elbow and lever, volume,
thickness."""

from __future__ import annotations

from rich.table import Table
from textual.widgets import Static

from biceps.engine.arm import Arm


class Stats(Static):
    def show(self, arm: Arm) -> None:
        muscle = arm.muscle
        shortest, longest = arm.length_range()
        table = Table.grid(padding=(0, 1))
        table.add_column(style="dim", no_wrap=True)
        table.add_column(no_wrap=True)
        table.add_row("length", f"{muscle.length:.2f} cm")
        table.add_row("  range", f"{shortest:.2f} to {longest:.2f}")
        table.add_row("flexion", f"{arm.flexion:.1f}°")
        table.add_row("moment arm", f"{arm.moment_arm:.2f} cm")
        table.add_row("volume", f"{muscle.volume:.3f} cm³")
        table.add_row("  with", "both end caps" if muscle.volume_mode == "closed"
                      else "no end caps")
        table.add_row("  kept to", _kept(muscle.volume_error))
        table.add_row("max radius", f"{muscle.max_radius:.3f} cm")
        table.add_row("girth", f"{muscle.girth:.2f} cm")
        self.update(table)


def _kept(error: float) -> str:
    """How closely the volume is kept, the relative error in words: ``1 part in 5e15``."""
    if error == 0:
        return "exactly"
    return f"1 part in {1 / error:.0e}".replace("e+", "e")
