"""What the screens look like, compared with the accepted SVG snapshots.

Update them with ``pytest tests/tui/test_app_snapshots.py --snapshot-update`` and look at the
result (``tests/tui/__snapshots__``) before accepting it.
"""

from textual.pilot import Pilot
from textual.widgets import Input

from biceps.configs import FOLDER
from biceps.engine.config import load_config
from biceps.tui.app import BicepsApp
from biceps.tui.widgets.viewport import Viewport
from waiting import until


async def _picture_drawn(pilot: Pilot) -> None:
    await pilot.pause()  # the main screen may not be composed yet
    viewport = pilot.app.screen_stack[0].query_one(Viewport)
    await until(pilot, lambda: viewport.up_to_date, "the picture caught up with the scene")


def test_main_screen(snap_compare, config):
    async def contract_and_turn(pilot: Pilot) -> None:
        await pilot.press("C", "C", "right", "right")
        await _picture_drawn(pilot)

    assert snap_compare(BicepsApp(config), terminal_size=(100, 30), run_before=contract_and_turn)


def test_main_screen_at_80_by_24(snap_compare, config):
    assert snap_compare(BicepsApp(config), terminal_size=(80, 24), run_before=_picture_drawn)


def test_help_screen(snap_compare, config):
    async def open_help(pilot: Pilot) -> None:
        await _picture_drawn(pilot)
        await pilot.press("question_mark")

    assert snap_compare(BicepsApp(config), terminal_size=(100, 30), run_before=open_help)


def test_a_notification_stays_over_the_picture_as_it_turns(snap_compare, config):
    async def notify_then_turn(pilot: Pilot) -> None:
        await _picture_drawn(pilot)
        pilot.app.notify("A note over the picture, which new frames must not paint over.")
        await pilot.pause()
        # Bigger, and down and right: the arm reaches under the note as it changes.
        await pilot.press("plus", "plus", "plus", *"ssssss", *"dddddd")
        await _picture_drawn(pilot)

    assert snap_compare(BicepsApp(config), terminal_size=(100, 30), run_before=notify_then_turn)


def test_a_dialog_stays_over_the_picture_as_it_turns(snap_compare, config):
    async def prompt_then_turn(pilot: Pilot) -> None:
        await _picture_drawn(pilot)
        await pilot.press("e")
        await pilot.pause()
        pilot.app.action_turn(30.0, 10.0, 0.0)  # keys go to the dialog now
        await _picture_drawn(pilot)
        # No blinking cursor: its phase at the snapshot hung on how long the picture took
        # to draw (one run in seven failed on a busy machine).
        for field in pilot.app.screen.query(Input):
            field.cursor_blink = False

    assert snap_compare(BicepsApp(config), terminal_size=(100, 30), run_before=prompt_then_turn)


def test_help_screen_at_80_by_24(snap_compare, config):
    async def open_help(pilot: Pilot) -> None:
        await _picture_drawn(pilot)
        await pilot.press("question_mark")

    assert snap_compare(BicepsApp(config), terminal_size=(80, 24), run_before=open_help)


def test_the_footer_at_80_columns_with_the_node_table_focused(snap_compare, config):
    async def focus_the_table(pilot: Pilot) -> None:
        await pilot.press("h", "tab")
        await _picture_drawn(pilot)
        await pilot.pause(0.3)  # the footer laid out, and fitted

    assert snap_compare(BicepsApp(config), terminal_size=(80, 24), run_before=focus_the_table)


def test_a_picked_muscle_and_node_marked_in_the_picture(snap_compare):
    async def pick(pilot: Pilot) -> None:
        await _picture_drawn(pilot)
        await pilot.press("tab", "down", "down", "down", "down", "down")
        await _picture_drawn(pilot)

    elbow = load_config(FOLDER / "elbow.toml")
    assert snap_compare(BicepsApp(elbow), terminal_size=(100, 30), run_before=pick)
