"""Several muscles in the app: picking one for the node table, hiding one, colouring by
strain, and edits of any of them undone and saved."""

import re
import shutil

import numpy as np
import pytest
from PIL import Image
from textual.widgets import Input

from biceps.configs import FOLDER
from biceps.engine.config import load_config
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.commands import KeyCommands
from biceps.tui.screens.prompt import Prompt
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.stats import Stats
from biceps.tui.widgets.viewport import Viewport

from test_app_nodes import _edit, _text


@pytest.fixture
def elbow(tmp_path):
    path = tmp_path / "elbow.toml"
    shutil.copy(FOLDER / "elbow.toml", path)
    return load_config(path)


async def test_t_picks_each_muscle_in_turn_for_the_node_table_and_T_goes_back(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        names = app.scene.arm.names
        await pilot.press("t", "t")
        await session.settle()
        assert app.scene.selected == 2
        table = app.screen.query_one(NodeTable)
        assert table.row_count == app.scene.arm.muscles[2].node_count
        assert re.search(rf"muscle +{names[2]}", _text(app.screen.query_one(Stats).content))
        await pilot.press(*"t" * (len(names) - 2))
        assert app.scene.selected == 0
        await pilot.press("T")
        assert app.scene.selected == len(names) - 1
        assert not app.unsaved  # picking a muscle is no edit


async def test_one_muscle_is_the_only_one_to_pick(biceps):
    async with biceps() as session:
        await session.pilot.press("t")
        assert session.app.scene.selected == 0
        assert any("only muscle" in note.message for note in session.notes)


async def test_a_node_edit_changes_the_picked_muscle_alone_and_undo_takes_it_back(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        before = app.scene.arm
        await pilot.press("t")  # the BRA
        await _edit(session, 5, radius="2.6")
        after = app.scene.arm
        assert after.muscles[1].radii[4] == 2.6
        assert after.muscles[1].volume_error == 0.0
        for index in (0, 2, 3, 4, 5):
            assert after.muscles[index] is before.muscles[index]
        assert app.unsaved
        await pilot.press("ctrl+z")
        assert app.scene.arm.muscles[1].radii[4] == before.muscles[1].radii[4]
        assert not app.unsaved
        await pilot.press("ctrl+y")
        assert app.scene.arm.muscles[1].radii[4] == 2.6


async def test_an_edited_companion_is_saved_and_loads_again(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press("t", "C", "C")  # the BRA; then the elbow bends
        await _edit(session, 5, radius="2.6")
        edited = app.scene.arm
        await pilot.press("ctrl+s")
        await session.settle()
        again = load_config(elbow.path).arm
        assert np.allclose(again.muscles[1].radii, edited.muscles[1].radii, rtol=1e-12)
        assert again.muscles[1].reference_volume == pytest.approx(
            edited.muscles[1].reference_volume, rel=1e-12)


async def test_contracting_the_biceps_lengthens_the_triceps_each_at_its_own_volume(biceps,
                                                                                    elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        before = session.app.scene.arm
        await session.pilot.press("C", "C", "C")
        after = session.app.scene.arm
        assert after.flexion > before.flexion
        for name, old, new in zip(after.names, before.muscles, after.muscles):
            assert (new.length > old.length) == name.startswith("TRI")
            assert new.volume_error < 1e-12


async def test_y_hides_the_picked_muscle_and_shows_it_again(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        await pilot.press("t", "y")
        assert app.scene.hidden == {"BRA"}
        await session.settle()
        await pilot.press("y")
        assert app.scene.hidden == frozenset()
        await session.settle()
        assert session.warnings == []


async def test_b_colours_the_muscles_by_strain(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        await session.pilot.press("b")
        assert session.app.scene.render.colour_by == "strain"
        await session.settle()
        await session.pilot.press("b")  # by activation: tests/tui/test_app_forces.py
        assert session.app.scene.render.colour_by == "activation"
        await session.pilot.press("b")
        assert session.app.scene.render.colour_by == "muscle"


async def test_the_palette_lists_every_muscle_and_picks_one(biceps, elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        provider = KeyCommands(session.app.screen)
        offered = {hit.text async for hit in provider.discover()}
        names = session.app.scene.arm.names
        assert {f"Edit muscle {name}" for name in names} <= offered
        await session.run_command("edit muscle TRIlat")
        assert session.app.scene.selected == names.index("TRIlat")


async def test_the_palette_lists_no_muscles_for_one(biceps):
    async with biceps() as session:
        offered = {hit.text async for hit in KeyCommands(session.app.screen).discover()}
        assert not any(text.startswith("Edit muscle") for text in offered)


@pytest.mark.parametrize("first", ["t", "C"], ids=["t, a muscle picked", "C, contracted"])
async def test_a_node_opened_in_the_same_burst_as_a_change_shows_and_keeps_what_it_has_now(
        biceps, elbow, first):
    # "t" then enter, typed quickly, opened the node of the muscle picked before, and OK put
    # that muscle's radius and growth into the new one's (the BRA's node 3, 2.68 cm with
    # growth 1.93, became 0.3 cm with growth 0): the table shows a burst's numbers only after
    # the burst, and the dialog took them from the table.
    from textual import events
    from textual.widgets import Input

    async with biceps(size=(120, 40), on=elbow) as session:
        app = session.app
        app.screen.query_one(NodeTable).focus()
        await session.pilot.press(*["down"] * 7)  # node 8, which grows as it shortens
        for key in (first, "enter"):
            app.post_message(events.Key(key, None))
        await session.settle()
        picked = app.scene.arm.muscles[app.scene.selected]
        radius, growth = (box.value for box in app.screen.query(Input))
        assert (radius, growth) == (f"{picked.radii[7]:.4f}".rstrip("0").rstrip("."),
                                    f"{picked.growth[7]:.4f}".rstrip("0").rstrip("."))
        await session.pilot.press("enter")  # OK with nothing typed: the node stays as it was
        kept = app.scene.arm.muscles[app.scene.selected]
        assert (kept.radii[7], kept.growth[7]) == (picked.radii[7], picked.growth[7])


async def test_an_edit_past_the_most_nodes_of_all_the_muscles_together_is_refused(
        biceps, elbow, monkeypatch):
    total = sum(muscle.node_count for muscle in elbow.arm.muscles)
    monkeypatch.setattr("biceps.engine.cost.NODES", total + 9)
    async with biceps(size=(120, 40), on=elbow) as session:
        app = session.app
        before = app.scene.arm
        await session.pilot.press("t", "tab", "slash")  # the BRA's 11 nodes would make 21
        await session.settle()
        assert app.scene.arm is before
        assert session.warnings[-1] == (f"{total + 10} nodes; a model has at most {total + 9}, "
                                        "all its muscles together")


async def test_the_picture_marks_the_picked_muscle_and_rings_the_node_the_table_picks(biceps,
                                                                                     elbow):
    async with biceps(size=(120, 40), on=elbow) as session:
        app, pilot = session.app, session.pilot
        assert app.scene.marked and app.scene.picked_node is None
        await pilot.press("t")
        await session.settle()
        assert app.scene.selected == 1
        table = app.screen.query_one(NodeTable)
        table.focus()
        await pilot.press("down", "down")
        await session.settle()
        assert app.scene.picked_node == table.cursor_row == 2
        await pilot.press("end")
        await session.settle()
        assert app.scene.picked_node == app.scene.arm.muscles[1].node_count - 1
        await pilot.press("enter")  # the node's own dialog keeps it ringed
        await session.settle()
        assert isinstance(app.screen, Prompt)
        assert app.scene.picked_node == app.scene.arm.muscles[1].node_count - 1
        await pilot.press("escape")
        await session.settle()
        app.screen.query_one(Viewport).focus()  # back to turning the model
        await session.settle()
        assert app.scene.picked_node is None
        assert not app.unsaved  # marking the pick is no edit


async def test_an_export_is_the_model_alone_without_the_marks(biceps, elbow, tmp_path):
    async with biceps(size=(120, 40), on=elbow) as session:
        app = session.app
        app.screen.query_one(NodeTable).focus()
        await session.settle()
        assert app.scene.picked_node == 0
        out = tmp_path / "marked.png"
        await session.pilot.press("e")
        app.screen.query(Input)[0].value = str(out)
        app.screen.query(Input)[1].value = "160x120"
        await session.pilot.press("enter")
        await session.settle()
        exported = np.asarray(Image.open(out).convert("RGB"))
        plain = SceneRenderer().render(app.scene.unmarked(), 160, 120)
        assert np.array_equal(exported, plain)
        assert not np.array_equal(exported, SceneRenderer().render(app.scene, 160, 120))
