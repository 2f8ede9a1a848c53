"""What the plot panel looks like, compared with the accepted SVG snapshot.

Update it with ``pytest tests/tui/test_app_plot_snapshots.py --snapshot-update`` and look at
the result (``tests/tui/__snapshots__``) before accepting it.
"""

from textual.pilot import Pilot

from biceps.tui.app import BicepsApp
from test_app_snapshots import _picture_drawn


def test_the_plot_panel_after_a_contraction(snap_compare, config):
    async def contract_with_plots(pilot: Pilot) -> None:
        await pilot.press("p", "C", "C")
        await _picture_drawn(pilot)

    assert snap_compare(BicepsApp(config), terminal_size=(110, 34), run_before=contract_with_plots)
