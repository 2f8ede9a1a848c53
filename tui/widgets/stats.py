"""The numbers that matter as the muscle changes: length, elbow and lever, volume,
thickness."""

from __future__ import annotations

from rich.console import Group
from rich.table import Table
from textual.widgets import Static

from biceps.engine.arm import Arm


class Stats(Static):
    _rows = 0  # the rows shown last

    def show(self, arm: Arm, selected: int = 0, brief: bool = False) -> None:
        """The numbers of ``arm``'s muscle ``selected`` (0: the driver), and with several
        muscles a line for each: its length, volume and how closely that is kept;
        ``brief``, only its name, length, flexion and volume (where the rows are few)."""
        muscle = arm.muscles[selected]
        table = Table.grid(padding=(0, 1))
        table.add_column(style="dim", no_wrap=True)
        table.add_column(no_wrap=True)
        if len(arm.names) > 1:
            table.add_row("muscle", arm.names[selected])
        table.add_row("length", f"{_number(muscle.length, 2)} cm")
        self.border_subtitle = "more with more rows" if brief else None
        if brief:
            table.add_row("flexion", f"{arm.flexion:.1f}°")
            table.add_row("volume", f"{_number(muscle.volume, 3)} cm³")
            self.update(table, layout=table.row_count != self._rows)
            self._rows = table.row_count
            return
        shortest, longest = arm.length_range()
        if selected == 0:
            table.add_row("  range", f"{_number(shortest, 2)} to {_number(longest, 2)}")
        table.add_row("flexion", f"{arm.flexion:.1f}°")
        if selected == 0:
            table.add_row("moment arm", f"{_number(arm.moment_arm, 2)} cm")
        table.add_row("volume", f"{_number(muscle.volume, 3)} cm³")
        table.add_row("  with", "both end caps" if muscle.volume_mode == "closed"
                      else "no end caps")
        table.add_row("  kept to", _kept(muscle.volume_error))
        table.add_row("max radius", f"{_number(muscle.max_radius, 3)} cm")
        table.add_row("girth", f"{_number(muscle.girth, 2)} cm")
        if len(arm.names) > 1:
            shown = Group(table, "", _muscles_table(arm, selected))
        else:
            shown = table
        # The same rows in a panel of fixed width: once laid out, a new muscle needs a
        # repaint, not a layout of the whole screen (at every step of a held key); only
        # another muscle picked, with other rows, needs a layout.
        self.update(shown, layout=table.row_count != self._rows)
        self._rows = table.row_count


def _number(value: float, decimals: int) -> str:
    """``value`` with ``decimals`` decimals where that reads well, else in four significant
    digits, so that no number the model allows (radii of 1e-6 to 1e4 cm, volumes of their
    cubes) runs past the panel's width: ``33.00``, ``1.037e+10``, ``4.189e-18``."""
    if value == 0 or 10.0 ** -decimals <= abs(value) < 1e5:
        return f"{value:.{decimals}f}"
    return f"{value:.4g}"


def _muscles_table(arm: Arm, selected: int) -> Table:
    """A row for each muscle, the picked one bold: its length, volume and the volume's
    relative error, in as few columns as a narrow panel holds."""
    table = Table.grid(padding=(0, 1))
    table.add_column(no_wrap=True, overflow="ellipsis", max_width=10)
    for _ in range(3):
        table.add_column(no_wrap=True, justify="right")
    table.add_row("muscle", "cm", "cm³", "error", style="dim")
    for index, (name, muscle) in enumerate(zip(arm.names, arm.muscles)):
        table.add_row(name, _number(muscle.length, 2), _number(muscle.volume, 1),
                      _error(muscle.volume_error), style="bold" if index == selected else "")
    return table


def _error(error: float) -> str:
    """The relative volume error, short: ``0`` or ``2e-16``."""
    return "0" if error == 0 else f"{error:.0e}"


def _kept(error: float) -> str:
    """How closely the volume is kept, the relative error in words: ``1 part in 5e15``."""
    if error == 0:
        return "exactly"
    return f"1 part in {1 / error:.0e}".replace("e+", "e")
