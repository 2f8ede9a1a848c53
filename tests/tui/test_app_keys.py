"""Every key of the main screen changes the scene as it says, and the mouse does too."""

import pytest
from textual import events

from biceps.tui.app import BicepsApp
from biceps.tui.changes import TURN_STEP
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.viewport import Viewport

# The bundled model starts at yaw -25, pitch 10, roll 0, scale 1, offset 0, light
# (60, 80, 120), length 33 cm, Gouraud shading without anti-aliasing.
KEY_EFFECTS = {
    "left": (lambda s: s.view.yaw, -30.0),
    "right": (lambda s: s.view.yaw, -20.0),
    "up": (lambda s: s.view.pitch, 5.0),
    "down": (lambda s: s.view.pitch, 15.0),
    "left_square_bracket": (lambda s: s.view.roll, 5.0),
    "right_square_bracket": (lambda s: s.view.roll, -5.0),
    "shift+left": (lambda s: s.view.offset, (-2.0, 0.0, 0.0)),
    "a": (lambda s: s.view.offset, (-2.0, 0.0, 0.0)),
    "shift+right": (lambda s: s.view.offset, (2.0, 0.0, 0.0)),
    "d": (lambda s: s.view.offset, (2.0, 0.0, 0.0)),
    "shift+up": (lambda s: s.view.offset, (0.0, 2.0, 0.0)),
    "w": (lambda s: s.view.offset, (0.0, 2.0, 0.0)),
    "shift+down": (lambda s: s.view.offset, (0.0, -2.0, 0.0)),
    "s": (lambda s: s.view.offset, (0.0, -2.0, 0.0)),
    "plus": (lambda s: s.view.scale, 1.1),
    "equals_sign": (lambda s: s.view.scale, 1.1),
    "minus": (lambda s: s.view.scale, 1 / 1.1),
    "c": (lambda s: s.arm.length, 32.9),
    "C": (lambda s: s.arm.length, 32.0),
    "x": (lambda s: s.arm.length, 33.1),
    "X": (lambda s: s.arm.length, 34.0),
    "j": (lambda s: s.light.position, (50.0, 80.0, 120.0)),
    "l": (lambda s: s.light.position, (70.0, 80.0, 120.0)),
    "i": (lambda s: s.light.position, (60.0, 90.0, 120.0)),
    "k": (lambda s: s.light.position, (60.0, 70.0, 120.0)),
    "u": (lambda s: s.light.position, (60.0, 80.0, 130.0)),
    "o": (lambda s: s.light.position, (60.0, 80.0, 110.0)),
    "g": (lambda s: s.render.shading, "phong"),
    "m": (lambda s: s.render.ssaa, 2),
}


@pytest.mark.parametrize("key", KEY_EFFECTS)
async def test_a_key_changes_the_scene(biceps, key):
    read, expected = KEY_EFFECTS[key]
    async with biceps() as session:
        await session.pilot.press(key)
        assert read(session.app.scene) == pytest.approx(expected)
        assert session.app.unsaved == (key in "cCxX")  # the model's length, not the view
        await session.settle()  # and the picture follows without complaint
        assert session.warnings == []


def test_every_key_of_the_main_screen_is_tested():
    tested = set(KEY_EFFECTS) | {
        "r", "f", "ctrl+s", "ctrl+d", "ctrl+o", "e", "f1", "question_mark", "q", "ctrl+q",
        "ctrl+z", "ctrl+y", "ctrl+r",  # tests/tui/test_app_history.py
    }  # fmt: skip
    tested |= {"p", "v"}  # test_app_plots.py, test_app_record.py
    tested |= {"t", "T", "y", "b"}  # test_app_muscles.py
    tested |= {"greater_than_sign", "less_than_sign", "right_curly_bracket",
               "left_curly_bracket"}  # test_app_forces.py
    bound = {key for binding in BicepsApp.BINDINGS for key in binding.key.split(",")}
    assert bound <= tested


async def test_the_muscle_thickens_as_it_contracts_and_the_elbow_bends(biceps):
    async with biceps() as session:
        before = session.app.scene.arm
        await session.pilot.press("C", "C")
        after = session.app.scene.arm
        assert after.muscle.max_radius > before.muscle.max_radius
        assert after.flexion > before.flexion
        assert after.muscle.volume == pytest.approx(before.muscle.volume, rel=1e-12)


async def test_stretching_past_the_straight_arm_stops_there_and_says_so(biceps):
    async with biceps() as session:
        await session.pilot.press(*["X"] * 4)
        low, high = session.app.scene.arm.length_range()
        assert session.app.scene.arm.length == pytest.approx(high)
        assert any("straight" in warning for warning in session.warnings)


async def test_a_held_key_at_a_limit_says_so_once(biceps):
    async with biceps() as session:
        await session.pilot.press(*["C"] * 8)
        assert len(session.warnings) == 1


async def test_reset_puts_back_the_view_from_the_file(biceps, config):
    async with biceps() as session:
        await session.pilot.press("right", "up", "a", "plus", "left_square_bracket", "r")
        assert session.app.scene.view == config.view


def _drag(viewport: Viewport, dx: int, dy: int, *, button: int = 1, ctrl: bool = False):
    x, y = viewport.size.width // 2, viewport.size.height // 2
    return events.MouseMove(viewport, x, y, dx, dy, button, False, False, ctrl)


async def test_a_drag_turns_the_model(biceps):
    async with biceps() as session:
        viewport = session.app.screen.query_one(Viewport)
        viewport.post_message(_drag(viewport, 4, -2))
        await session.pilot.pause()
        view = session.app.scene.view
        assert view.yaw > -25.0
        assert view.pitch < 10.0


@pytest.mark.parametrize("how", [{"ctrl": True}, {"button": 3}])
async def test_a_modified_or_right_button_drag_moves_the_model(biceps, how):
    async with biceps() as session:
        viewport = session.app.screen.query_one(Viewport)
        viewport.post_message(_drag(viewport, 4, -2, **how))
        await session.pilot.pause()
        x, y, _ = session.app.scene.view.offset
        assert x > 0 and y > 0
        assert session.app.scene.view.yaw == -25.0


async def test_the_wheel_scales_the_model(biceps):
    async with biceps() as session:
        viewport = session.app.screen.query_one(Viewport)
        await session.pilot.hover(viewport)
        viewport.post_message(events.MouseScrollUp(viewport, 1, 1, 0, 0, 0, False, False, False))
        viewport.post_message(events.MouseScrollUp(viewport, 1, 1, 0, 0, 0, False, False, False))
        viewport.post_message(events.MouseScrollDown(viewport, 1, 1, 0, 0, 0, False, False, False))
        await session.pilot.pause()
        assert session.app.scene.view.scale == pytest.approx(1.1)


async def test_left_and_right_still_turn_while_the_node_table_has_focus(biceps):
    async with biceps() as session:
        await session.pilot.press("tab", "right", "down")
        assert session.app.focused.id == "nodes"
        assert session.app.scene.view.yaw == -20.0
        assert session.app.scene.view.pitch == 10.0  # down moved the table's cursor instead


async def test_keys_queued_while_the_app_was_busy_show_their_numbers_once(biceps, monkeypatch):
    shown = []
    show = NodeTable.show

    def counting(table, muscle):
        shown.append(muscle.length)
        return show(table, muscle)

    monkeypatch.setattr(NodeTable, "show", counting)
    async with biceps() as session:
        shown.clear()
        for _ in range(30):  # as a held key's repeats wait while a slow update runs
            session.app.post_message(events.Key("c", "c"))
        await session.pilot.pause()
        assert session.app.scene.arm.length == 30.0
        assert shown[-1] == 30.0  # the latest, and
        assert len(shown) <= 2  # not a queue of 30 updates


async def test_the_arrows_turn_the_picture_at_once_while_it_has_the_focus(biceps, monkeypatch):
    # Priority bindings (BicepsApp.action_turn_in_view): the key is not sent on through
    # the widgets first.
    reached = []
    monkeypatch.setattr(Viewport, "on_key", lambda self, event: reached.append(event.key),
                        raising=False)
    async with biceps() as session:
        app = session.app
        assert isinstance(app.focused, Viewport)
        yaw = app.scene.view.yaw
        await session.pilot.press("right", "right")
        assert app.scene.view.yaw == yaw + 2 * TURN_STEP
        await session.pilot.press("x")
        assert reached == ["x"]  # (a key no priority binding takes does reach it)


async def test_with_the_node_table_focused_up_and_down_move_in_it_and_left_right_turn(biceps):
    async with biceps() as session:
        app = session.app
        table = app.screen.query_one(NodeTable)
        table.focus()
        await session.pilot.pause()
        view, row = app.scene.view, table.cursor_row
        await session.pilot.press("down", "down", "up")
        assert table.cursor_row == row + 1 and app.scene.view == view
        await session.pilot.press("left")
        assert app.scene.view.yaw == view.yaw - TURN_STEP
