"""Editing the muscle node by node in the table: good values take, bad ones change nothing."""

import io
import re
from pathlib import Path

import pytest
from rich.console import Console
from textual.widgets import Input

from biceps.engine.config import load_config
from biceps.tui.screens.prompt import Prompt
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.stats import Stats
from biceps.engine.config import BUNDLED



def _text(renderable) -> str:
    console = Console(width=80, record=True, file=io.StringIO())
    console.print(renderable)
    return console.export_text()


async def _edit(session, node: int, radius: str | None = None, growth: str | None = None):
    """Open node ``node`` (1-based) for editing, fill in what is given and press enter."""
    table = session.app.screen.query_one(NodeTable)
    table.focus()
    table.move_cursor(row=node - 1)
    await session.pilot.press("enter")
    radius_box, growth_box = session.app.screen.query(Input)
    if radius is not None:
        radius_box.value = radius
    if growth is not None:
        growth_box.value = growth
    await session.pilot.press("enter")


async def test_typing_a_radius_changes_that_node_and_the_picture_follows(biceps):
    async with biceps() as session:
        app, pilot = session.app, session.pilot
        await pilot.press("tab", *["down"] * 7, "enter")
        assert isinstance(app.screen, Prompt)
        await pilot.press(*"2.5", "enter")
        assert not isinstance(app.screen, Prompt)
        muscle = app.scene.arm.muscle
        assert muscle.radii[7] == 2.5
        assert muscle.growth[7] == 2.05
        assert app.unsaved
        await session.settle()
        assert app.screen.query_one(NodeTable).row(7)[2] == "2.500"


async def test_growth_is_edited_in_the_same_dialog(biceps):
    async with biceps() as session:
        await _edit(session, 3, growth="0.5")
        muscle = session.app.scene.arm.muscle
        assert (muscle.radii[2], muscle.growth[2]) == (0.6, 0.5)


async def test_confirming_an_untouched_edit_changes_nothing_even_when_contracted(biceps):
    async with biceps() as session:
        await session.pilot.press("c")
        before = session.app.scene.arm.muscle
        await _edit(session, 8)
        assert session.app.scene.arm.muscle is before


BAD_VALUES = [
    ("abc", "2.05", "not a number"),
    ("", "2.05", "Radius (1e-06 to 10000 cm): give a number"),
    ("2.08", " ", "Growth (0 to 10000): give a number"),
    ("nan", "2.05", "not a finite number"),
    ("-1", "2.05", "radius must be a finite number from 1e-06 to 10000 cm, not -1.0"),
    ("0", "2.05", "radius must be a finite number from 1e-06 to 10000 cm, not 0.0"),
    ("1e9", "2.05", "radius must be a finite number from 1e-06 to 10000 cm, not 1000000000.0"),
    ("1e-162", "2.05", "radius must be a finite number from 1e-06 to 10000 cm, not 1e-162"),
    ("2.08", "-0.5", "growth must be a finite number from 0 to 10000, not -0.5"),
    ("2.08", "1e300", "growth must be a finite number from 0 to 10000, not 1e+300"),
]


async def test_bad_values_are_refused_one_by_one_until_a_good_one_is_typed(biceps):
    async with biceps() as session:
        before = session.app.scene
        table = session.app.screen.query_one(NodeTable)
        table.focus()
        table.move_cursor(row=7)
        await session.pilot.press("enter")
        radius_box, growth_box = session.app.screen.query(Input)
        for radius, growth, complaint in BAD_VALUES:
            radius_box.value, growth_box.value = radius, growth
            await session.pilot.press("enter")
            assert isinstance(session.app.screen, Prompt)  # still open, the text there to fix
            assert complaint in session.app.screen.error
            assert session.app.scene.arm is before.arm
        radius_box.value, growth_box.value = "2.5", "2.05"
        await session.pilot.press("enter")
        assert not isinstance(session.app.screen, Prompt)
        assert session.app.scene.arm.muscle.radii[7] == 2.5


async def test_escape_leaves_the_node_as_it_was(biceps):
    async with biceps() as session:
        before = session.app.scene
        await session.pilot.press("tab", "enter", *"9", "escape")
        assert session.app.scene.arm is before.arm


@pytest.mark.parametrize("key", ["n", "insert"])
async def test_a_node_is_inserted_after_the_picked_one(biceps, key):
    async with biceps() as session:
        await session.pilot.press("tab", "down", key)
        muscle = session.app.scene.arm.muscle
        assert muscle.node_count == 16
        assert muscle.radii[2] == pytest.approx((0.40 + 0.60) / 2)


async def test_nothing_is_inserted_after_the_last_node(biceps):
    async with biceps() as session:
        session.app.screen.query_one(NodeTable).move_cursor(row=14)
        await session.pilot.press("tab", "n")
        assert session.app.scene.arm.muscle.node_count == 15
        assert any("between two neighbours" in warning for warning in session.warnings)


@pytest.mark.parametrize("key", ["delete", "backspace"])
async def test_the_picked_node_is_deleted(biceps, key):
    async with biceps() as session:
        table = session.app.screen.query_one(NodeTable)
        table.move_cursor(row=7)
        await session.pilot.press("tab", key)
        muscle = session.app.scene.arm.muscle
        assert muscle.node_count == 14
        assert muscle.radii[7] == 2.02  # the one that followed it
        assert table.cursor_row == 7


async def test_the_last_two_nodes_stay(biceps):
    async with biceps(on=load_config(BUNDLED / "toy.toml")) as session:
        await session.pilot.press("tab", "backspace", "backspace", "backspace")
        assert session.app.scene.arm.muscle.node_count == 2
        assert any("at least 2 nodes" in warning for warning in session.warnings)


async def test_subdividing_doubles_the_segments_and_keeps_the_volume(biceps):
    async with biceps() as session:
        before = session.app.scene.arm.muscle
        await session.pilot.press("tab", "slash")
        after = session.app.scene.arm.muscle
        assert after.node_count == 29
        assert after.volume == pytest.approx(before.volume, rel=1e-12)
        assert session.app.screen.query_one(NodeTable).row_count == 29


async def test_clicking_a_picked_node_opens_it(biceps):
    async with biceps() as session:
        table = session.app.screen.query_one(NodeTable)
        await session.pilot.click(table, offset=(3, 3))  # under the header and the border
        await session.pilot.click(table, offset=(3, 3))
        assert isinstance(session.app.screen, Prompt)


async def test_the_range_shown_and_a_held_stretch_stop_where_a_node_thins_to_nothing(biceps):
    async with biceps(on=load_config(BUNDLED / "toy.toml")) as session:
        await _edit(session, 1, radius="0.2", growth="5")
        await session.settle()
        assert "6.16 to 10.63" in _text(session.app.screen.query_one(Stats).content)
        await session.pilot.press("X", "X", "X")
        arm = session.app.scene.arm
        assert f"{arm.length:.2f}" == "10.63"
        assert session.warnings == [
            "the muscle is at its longest, 10.63 cm: stretched further, node 1's radius "
            "would fall to zero"]


async def test_the_numbers_say_what_the_volume_is_and_how_closely_it_is_kept(biceps):
    async with biceps() as session:
        stats = session.app.screen.query_one(Stats)
        lines = [line.split() for line in _text(stats.content).splitlines()]
        volume = lines.index(["volume", "198.879", "cm³"])
        assert lines[volume + 1] == ["with", "both", "end", "caps"]
        assert lines[volume + 2] == ["kept", "to", "exactly"]
        await session.pilot.press("c")
        kept = " ".join(_text(stats.content).splitlines()[volume + 2].split())
        assert re.fullmatch(r"kept to 1 part in \de1[2-9]", kept), kept


@pytest.mark.parametrize(("radius", "growth", "complaint"), [
    # The bounds a file's nodes have too (engine/bounds.py), in the same words.
    ("1e9", "2.05", "node 8: radius must be a finite number from 1e-06 to 10000 cm, "
                    "not 1000000000.0"),
    ("1e-9", "2.05", "node 8: radius must be a finite number from 1e-06 to 10000 cm, not 1e-09"),
    ("2.08", "1e5", "node 8: growth must be a finite number from 0 to 10000, not 100000.0"),
])
async def test_a_value_the_model_cannot_draw_is_refused_saying_what_it_takes(
    biceps, radius, growth, complaint
):
    async with biceps() as session:
        before = session.app.scene
        await _edit(session, 8, radius=radius, growth=growth)
        assert isinstance(session.app.screen, Prompt)
        assert complaint in session.app.screen.error
        assert session.app.scene.arm is before.arm


async def test_subdividing_says_when_the_picture_will_be_slow_and_stops_at_the_most_nodes(
    biceps, monkeypatch
):
    monkeypatch.setattr("biceps.engine.muscle.NODES", 200)
    async with biceps() as session:
        monkeypatch.setattr("biceps.tui.app.SLOW_NODES", 50)
        await session.pilot.press("tab", "slash", "slash")
        assert session.app.scene.arm.muscle.node_count == 57
        assert "57 nodes: the picture will follow each change slowly" in session.warnings[-1]
        await session.pilot.press("slash", "slash")
        assert session.app.scene.arm.muscle.node_count == 113
        assert session.warnings[-1] == ("subdividing would make 225 nodes; a muscle has at most "
                                        "200, more than a picture can show apart, each a ring "
                                        "of its mesh")


@pytest.mark.parametrize("radius", ["10000", "0.000001"])
async def test_the_numbers_fit_their_panel_at_either_end_of_the_radii(biceps, radius):
    async with biceps() as session:
        await _edit(session, 8, radius=radius)
        await session.pilot.pause()
        stats = session.app.screen.query_one(Stats)
        assert session.app.scene.arm.muscle.radii[7] == float(radius)
        lines = _text(stats.content).splitlines()
        assert max(len(line.rstrip()) for line in lines) <= stats.content_size.width


@pytest.mark.parametrize("keys, row", [(["end"], 14), (["end", "home"], 0), (["pagedown"], 9),
                                       (["end", "pageup"], 5), (["up"], 0), (["end", "down"], 14)])
async def test_the_cursor_pages_and_jumps_and_stops_at_the_ends(biceps, keys, row):
    async with biceps(size=(100, 24)) as session:  # 9 rows of nodes in view
        table = session.app.screen.query_one(NodeTable)
        await session.pilot.press("tab", *keys)
        assert table.cursor_row == row


async def test_thousands_of_nodes_show_the_rows_in_view_as_they_change(biceps, tmp_path):
    path = tmp_path / "fine.toml"
    radius = ", ".join(["2.0"] * 5000)
    path.write_text(f"[muscle]\nlength = 33.0\nradius = [{radius}]\ngrowth = [{radius}]\n")
    async with biceps(on=load_config(path)) as session:
        table = session.app.screen.query_one(NodeTable)
        await session.pilot.press("tab", "end", "c")
        muscle = session.app.scene.arm.muscle
        assert table.border_title == "nodes (5,000)"
        assert table.row(4999) == ("5000", "32.90", f"{muscle.radii[4999]:.3f}", "2.000")
        assert table.scroll_y == table.max_scroll_y  # the last row is in view
