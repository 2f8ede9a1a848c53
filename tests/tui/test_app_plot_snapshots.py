"""What the plot panel looks like, compared with the accepted SVG snapshot.

Update it with ``pytest tests/tui/test_app_plot_snapshots.py --snapshot-update`` and look at
the result (``tests/tui/__snapshots__``) before accepting it.
"""

import shutil

from textual.pilot import Pilot

from biceps.configs import FOLDER
from biceps.engine.config import load_config
from biceps.tui.app import BicepsApp
from test_app_snapshots import _picture_drawn
from waiting import until


def test_the_plot_panel_after_a_contraction(snap_compare, config):
    async def contract_with_plots(pilot: Pilot) -> None:
        await pilot.press("p", "C", "C")
        await _picture_drawn(pilot)

    assert snap_compare(BicepsApp(config), terminal_size=(110, 34), run_before=contract_with_plots)


def test_the_torque_panel_beside_the_others_holding_5_kg(snap_compare, tmp_path):
    path = tmp_path / "elbow.toml"
    shutil.copy(FOLDER / "elbow.toml", path)

    async def hold_with_plots(pilot: Pilot) -> None:
        await pilot.press("p", *"}" * 5)
        app = pilot.app
        await until(pilot, lambda: (app.effort is not None and not app._effort_busy
                                    and app.scene.mass == 5.0), "the effort of holding 5 kg")
        app.clear_notifications()  # the five 'Holding N kg', each over the picture
        await _picture_drawn(pilot)

    assert snap_compare(BicepsApp(load_config(path)), terminal_size=(150, 45),
                        run_before=hold_with_plots)
