"""What the muscles do: each one's activation, tendon force and torque about the elbow, and
the elbow's net torque; with a weight in the hand, the load's torque too, or why the
muscles cannot hold it. Shown once the muscles are asked to work (``>`` or ``}``)."""

from __future__ import annotations

from rich.table import Table
from textual.content import Content
from textual.widgets import Static

from biceps.engine.hold import Effort


class Forces(Static):
    """The side panel's forces: hidden until :meth:`show` has an effort to show."""

    def show(self, effort: Effort | None, activation: float, mass: float) -> None:
        """Show ``effort``, what the muscles do when asked for ``activation`` or to hold
        ``mass`` kg; hide the panel for None."""
        self.set_class(effort is not None, "-shown")
        if effort is None:
            return
        self.border_title = (f"holding {mass:g} kg" if mass > 0.0
                             else f"all at activation {activation:.2f}")
        # The load and a refusal in the border, so that the panel is a row for each muscle
        # and three more (the side panel shares 23 rows at 80x24).
        self.border_subtitle = (
            None if effort.load is None else
            Content.styled("too heavy: " + _heaviest(effort.refusal), "bold $text-error")
            if effort.refusal is not None else f"load {effort.load.torque:.2f} N m")
        table = Table.grid(padding=(0, 1))
        table.add_column(no_wrap=True, overflow="ellipsis", max_width=8)
        for _ in range(3):
            table.add_column(no_wrap=True, justify="right")
        table.add_row("muscle", "act.", "N", "N m", style="dim")
        for muscle in effort.muscles:
            table.add_row(muscle.name, f"{muscle.activation:.2f}", f"{muscle.tendon_force:.0f}",
                          f"{muscle.torque:+.2f}")
        table.add_row("net", "", "", f"{effort.torque:+.2f}", style="bold")
        self.update(table)


def _heaviest(refusal: str) -> str:
    """The refusal's end, what the muscles can do (``max 24.79 kg``), short enough for the
    panel's border (26 cells of its 32); the whole sentence is in the notification."""
    *_, last = refusal.rsplit(": ", 1)
    if "kg" not in last:
        return "the muscles cannot"
    return last.removesuffix(" there").replace("at most", "max")
