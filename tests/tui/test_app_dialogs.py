"""Dialogs as a person meets them: their words wrap at any width, an error is said inside
the dialog, which stays open with the text as typed, names complete, and the names offered
follow the file worked on."""

from pathlib import Path

import pytest
from textual.widgets import Input, Label

from biceps.engine.config import BUNDLED, load_config
from biceps.engine.errors import FileError
from biceps.tui.screens.choice import Choice
from biceps.tui.screens.prompt import Prompt
from biceps.tui.screens.record import RecordPrompt
from biceps.tui.widgets.node_table import NodeTable
from conftest import screen_rows
from waiting import until


def _shown_text(session, widget) -> str:
    """The words of ``widget`` as they are on the screen, lines joined."""
    region = widget.region
    rows = screen_rows(session.app)[region.y:region.bottom]
    return " ".join(" ".join(row[region.x:region.right].split()) for row in rows)


@pytest.mark.parametrize("width", [60, 80, 200])
async def test_the_changed_on_disk_question_is_shown_whole_at_any_width(biceps, config_path,
                                                                          width):
    async with biceps((width, 24)) as session:
        config_path.write_text(config_path.read_text().replace("length = 33.0", "length = 34.0"))
        await session.pilot.press("c", "ctrl+s")
        await session.settle()
        assert isinstance(session.app.screen, Choice)
        question = session.app.screen.query_one(Label)
        words = (f"{config_path} was changed on disk since it was opened here: saving replaces "
                 "those changes with this model.")
        # Every character, in order (a long path is broken where it must be).
        assert "".join(_shown_text(session, question).split()) == "".join(words.split())
        assert question.region.right <= session.app.screen.query_one(".dialog-box").region.right


async def test_the_open_dialog_stays_open_on_a_missing_name_and_keeps_the_keys(biceps, tmp_path,
                                                                             monkeypatch):
    monkeypatch.chdir(tmp_path)
    async with biceps() as session:
        before = session.app.scene
        await session.pilot.press("ctrl+o")
        box = session.app.screen.query_one(Input)
        await session.pilot.press(*"nothere.toml", "enter")  # over the name offered
        await session.settle()
        assert isinstance(session.app.screen, Prompt)
        assert "nothere.toml" in session.app.screen.error
        assert _shown_text(session, session.app.screen.query_one(".dialog-error")) == \
            session.app.screen.error
        await session.pilot.press(*"elb")  # export, the light, the colours, were it closed
        assert isinstance(session.app.screen, Prompt)
        assert box.value == "nothere.tomlelb"
        assert session.app.scene is before
        assert session.notes == []
        assert session.app.screen.error == ""  # typing again clears what was said
        await session.pilot.press("escape")
        assert session.app.scene is before


async def test_the_open_dialog_completes_a_bundled_model_s_name(biceps, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # no file here starts with "el"
    async with biceps() as session:
        await session.pilot.press("ctrl+o")
        box = session.app.screen.query_one(Input)
        assert "elbow" in session.app.screen.query_one(".dialog-note", Label).content.plain
        box.value = "el"
        await until(session.pilot, lambda: box._suggestion)  # found in the background
        await session.pilot.press("end", "enter")
        await session.settle()
        assert session.app.config.path == BUNDLED / "elbow.toml"


async def test_a_file_of_that_name_comes_before_the_bundled_model(biceps, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "elsewhere.toml").write_text("")
    async with biceps() as session:
        await session.pilot.press("ctrl+o")
        box = session.app.screen.query_one(Input)
        box.value = "el"
        await until(session.pilot, lambda: box._suggestion)
        await session.pilot.press("end")
        assert box.value == "elsewhere.toml"


async def test_saving_a_bundled_model_says_why_it_asks_where(biceps, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    async with biceps(on=load_config(BUNDLED / "biceps.toml")) as session:
        await session.pilot.press("c", "ctrl+s")
        await session.settle()
        prompt = session.app.screen
        assert isinstance(prompt, Prompt)
        note = prompt.query_one(".dialog-note", Label)
        assert "biceps.toml is a bundled model" in _shown_text(session, note)
        assert prompt.query_one(".dialog-box").border_title == "Save a copy"


async def test_a_save_the_file_system_refuses_is_said_in_the_dialog(biceps, tmp_path,
                                                                    monkeypatch):
    from biceps.tui import app

    def refuse(*args, **kwargs):
        raise FileError(f"{tmp_path / 'mine.toml'}: no space left on the device")

    monkeypatch.setattr(app, "save_config", refuse)
    async with biceps() as session:
        await session.pilot.press("c", "ctrl+d")
        session.app.screen.query_one(Input).value = str(tmp_path / "mine.toml")
        await session.pilot.press("enter")
        await session.settle()
        assert isinstance(session.app.screen, Prompt)
        assert "no space left" in session.app.screen.error
        assert session.app.screen.query_one(Input).value == str(tmp_path / "mine.toml")
        assert session.app.unsaved


async def test_export_and_record_offer_the_name_of_the_file_saved_as(biceps, tmp_path):
    async with biceps() as session:
        await session.pilot.press("ctrl+d")
        session.app.screen.query_one(Input).value = str(tmp_path / "my.toml")
        await session.pilot.press("enter")
        await session.settle()
        await session.pilot.press("e")
        assert session.app.screen.query_one(Input).value == "my.png"
        await session.pilot.press("escape", "v")
        await session.pilot.pause()
        assert isinstance(session.app.screen, RecordPrompt)
        assert session.app.screen.query_one(Input).value == "my-flex.gif"


async def test_n_then_delete_deletes_the_node_just_inserted(biceps):
    async with biceps() as session:
        radii = session.app.scene.arm.muscle.radii.copy()
        table = session.app.screen.query_one(NodeTable)
        table.move_cursor(row=3)
        await session.pilot.press("tab", "n")
        assert table.cursor_row == 4  # on the new node
        await session.pilot.press("delete")
        await session.settle()
        muscle = session.app.scene.arm.muscle
        assert muscle.node_count == 15
        assert list(muscle.radii) == list(radii)  # the new node gone, the old ones kept
