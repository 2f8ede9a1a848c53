"""Saving, opening, exporting and quitting: no edit is ever lost, every failure is said."""

import difflib
import math
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from textual.widgets import Input

from biceps.engine.config import load_config
from biceps.tui.screens.choice import Choice
from biceps.tui.screens.prompt import Prompt
from biceps.tui.widgets.node_table import NodeTable
from biceps.engine.config import BUNDLED
from waiting import until

BROKEN = Path(__file__).resolve().parents[1] / "invalid_configs" / "broken_toml.toml"


async def _answer(session, *values: str) -> None:
    """Fill the open dialog's inputs with ``values`` and press enter."""
    assert isinstance(session.app.screen, Prompt)
    for box, value in zip(session.app.screen.query(Input), values):
        box.value = value
    await session.pilot.press("enter")
    await session.settle()


async def test_saved_edits_come_back_when_the_file_is_read_again(biceps, config_path):
    async with biceps() as session:
        session.app.screen.query_one(NodeTable).move_cursor(row=3)
        await session.pilot.press("C", "tab", "n", "right", "l", "g", "ctrl+s")
        await session.settle()
        assert not session.app.unsaved
        scene = session.app.scene
    saved = load_config(config_path)
    assert saved.arm.length == scene.arm.length
    assert np.array_equal(saved.arm.muscle.radii, scene.arm.muscle.radii)
    assert np.array_equal(saved.arm.muscle.growth, scene.arm.muscle.growth)
    assert (saved.view, saved.light, saved.render) == (scene.view, scene.light, scene.render)
    assert saved.source.startswith("# A human biceps brachii")  # the comments survive


async def test_save_as_writes_another_file_and_works_on_it_from_then_on(biceps, config_path,
                                                                        tmp_path):
    original = config_path.read_text()
    async with biceps() as session:
        await session.pilot.press("c", "ctrl+d")
        await _answer(session, str(tmp_path / "copy.toml"))
        assert session.app.config.path == tmp_path / "copy.toml"
        assert not session.app.unsaved
        assert "copy.toml" in session.app.sub_title
    assert load_config(tmp_path / "copy.toml").arm.length == 32.9
    assert config_path.read_text() == original


async def test_saving_the_bundled_model_asks_for_a_file_of_ones_own(biceps, tmp_path,
                                                                     monkeypatch):
    bundled = BUNDLED / "biceps.toml"
    original = bundled.read_bytes()
    monkeypatch.chdir(tmp_path)
    async with biceps(on=load_config(bundled)) as session:
        await session.pilot.press("c", "ctrl+s")
        assert session.app.screen.query_one(Input).value == str(tmp_path / "biceps.toml")
        await _answer(session, str(tmp_path / "mine.toml"))
        assert session.app.config.path == tmp_path / "mine.toml"
        assert not session.app.unsaved
    assert bundled.read_bytes() == original
    assert load_config(tmp_path / "mine.toml").arm.length == 32.9


async def test_save_as_into_a_missing_directory_says_so_and_keeps_the_dialog(biceps, config_path):
    async with biceps() as session:
        await session.pilot.press("c", "ctrl+d")
        await _answer(session, "/nonexistent/dir/x.toml")
        assert isinstance(session.app.screen, Prompt)  # as the export dialog does
        assert "there is no directory /nonexistent/dir" in session.app.screen.error
        assert session.app.screen.query_one(Input).value == "/nonexistent/dir/x.toml"
        await session.pilot.press("escape")
        assert session.app.unsaved
        assert session.app.config.path == config_path
        assert session.app.scene.arm.length == 32.9


async def test_save_as_over_another_file_asks_first(biceps, tmp_path):
    other = tmp_path / "other.toml"
    other.write_text("keep me")
    async with biceps() as session:
        await session.pilot.press("c", "ctrl+d")
        await _answer(session, str(other))
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("escape")
        assert other.read_text() == "keep me"
        # Back in the dialog, with the name as typed, to choose another or to insist.
        assert session.app.screen.query_one(Input).value == str(other)
        await _answer(session, str(other))
        await session.pilot.press("y")
        await session.settle()
        assert load_config(other).arm.length == 32.9


async def test_a_directory_is_not_a_file_name(biceps, tmp_path):
    async with biceps() as session:
        await session.pilot.press("ctrl+d")
        await _answer(session, str(tmp_path))
        assert isinstance(session.app.screen, Prompt)
        assert "is a directory" in session.app.screen.error


async def test_opening_another_configuration_shows_it(biceps):
    async with biceps() as session:
        await session.pilot.press("ctrl+o")
        await _answer(session, str(BUNDLED / "toy.toml"))
        assert session.app.scene.arm.muscle.node_count == 4
        assert session.app.sub_title == "toy.toml"
        assert not session.app.unsaved
        assert session.app.screen.query_one(NodeTable).row_count == 4


@pytest.mark.parametrize("name", ["toy", "configs/toy.toml"])
async def test_a_bundled_model_is_opened_by_its_name_from_any_folder(biceps, name, tmp_path,
                                                                      monkeypatch):
    monkeypatch.chdir(tmp_path)
    async with biceps() as session:
        await session.pilot.press("ctrl+o")
        await _answer(session, name)
        assert session.app.scene.arm.muscle.node_count == 4
        assert session.app.config.path == BUNDLED / "toy.toml"


async def test_the_open_dialog_offers_the_file_open_now(biceps, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # not where the bundled model is: no copy of it here
    async with biceps(on=load_config(BUNDLED / "elbow.toml")) as session:
        await session.pilot.press("ctrl+o")
        (box,) = session.app.screen.query(Input)
        assert box.value == str(session.app.config.path)
        await session.pilot.press("enter")
        assert not session.warnings


async def test_a_broken_file_is_not_opened_and_the_model_stays(biceps):
    async with biceps() as session:
        before = session.app.scene
        await session.pilot.press("ctrl+o")
        await _answer(session, str(BROKEN))
        assert isinstance(session.app.screen, Prompt)
        assert "not valid TOML" in session.app.screen.error
        assert session.app.scene is before


async def test_opening_over_unsaved_edits_asks_first(biceps):
    async with biceps() as session:
        await session.pilot.press("c", "ctrl+o")
        await _answer(session, str(BUNDLED / "toy.toml"))
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("escape")
        assert session.app.scene.arm.length == 32.9
        await session.pilot.press("ctrl+o")
        await _answer(session, str(BUNDLED / "toy.toml"))
        await session.pilot.press("n")
        assert session.app.scene.arm.muscle.node_count == 4


async def test_export_writes_a_png_of_the_asked_size_and_says_where(biceps, tmp_path,
                                                                      monkeypatch):
    monkeypatch.chdir(tmp_path)
    async with biceps() as session:
        await session.pilot.press("e")
        await _answer(session, "arm.png", "320x200")
        with Image.open(tmp_path / "arm.png") as picture:
            assert picture.size == (320, 200)
        assert session.notes[-1].message == f"Exported {tmp_path / 'arm.png'} (320x200)"


async def test_export_over_an_existing_png_asks_every_time_and_escape_goes_back(biceps,
                                                                                  tmp_path):
    path = tmp_path / "arm.png"
    async with biceps() as session:
        await session.pilot.press("e")
        await _answer(session, str(path), "64x48")
        written = path.read_bytes()
        await session.pilot.press("right", "e", "enter")  # the same file again
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("escape")
        assert isinstance(session.app.screen, Prompt)
        assert [box.value for box in session.app.screen.query(Input)] == [str(path), "64x48"]
        await session.pilot.press("enter", "y")
        await session.settle()
    assert path.read_bytes() != written


async def test_end_accepts_the_suggested_file_name(biceps, tmp_path):
    (tmp_path / "arm-flexed.png").write_bytes(b"")
    async with biceps() as session:
        await session.pilot.press("e")
        box = session.app.screen.query_one(Input)
        box.value = str(tmp_path / "arm-f")
        await until(session.pilot, lambda: box._suggestion)  # found in the background
        box.action_home()
        await session.pilot.press("end")
        assert box.value == str(tmp_path / "arm-flexed.png")


async def test_export_is_1920_by_1080_unless_asked_otherwise(biceps, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    async with biceps() as session:
        await session.pilot.press("e", "enter")
        await session.settle()
    with Image.open(tmp_path / "biceps.png") as picture:
        assert picture.size == (1920, 1080)


async def test_export_needs_a_png_name_and_a_size(biceps, tmp_path):
    async with biceps() as session:
        await session.pilot.press("e")
        await _answer(session, str(tmp_path / "arm"), "320x200")
        assert "must end in .png" in session.app.screen.error
        await _answer(session, str(tmp_path / "arm.png"), "huge")
        assert isinstance(session.app.screen, Prompt)
        assert "not a size" in session.app.screen.error
    assert not (tmp_path / "arm.png").exists()


async def test_export_into_a_missing_directory_says_so_before_rendering(biceps):
    async with biceps() as session:
        await session.pilot.press("e")
        await _answer(session, "/nonexistent/dir/x.png", "64x64")
        assert isinstance(session.app.screen, Prompt)
        assert "/nonexistent/dir" in session.app.screen.error


async def test_quit_without_edits_quits(biceps):
    async with biceps() as session:
        await session.pilot.press("q")
        assert session.app.return_code == 0


async def test_quit_with_unsaved_edits_asks_and_waits_for_an_answer(biceps, config_path):
    original = config_path.read_text()
    async with biceps() as session:
        await session.pilot.press("c", "q")
        assert isinstance(session.app.screen, Choice)
        assert session.app.return_code is None
        await session.pilot.press("escape")
        assert session.app.return_code is None
        assert session.app.scene.arm.length == 32.9
        await session.pilot.press("ctrl+q", "n")
        assert session.app.return_code == 0
    assert config_path.read_text() == original


async def test_keys_that_move_the_model_do_not_answer_the_quit_question(biceps, config_path):
    # Moving with d (or w, a, s) and slipping onto q: the next d must not drop the edits.
    original = config_path.read_text()
    async with biceps() as session:
        await session.pilot.press("c", "d", "q", "d", "a", "w")
        assert isinstance(session.app.screen, Choice)
        assert session.app.return_code is None
    assert config_path.read_text() == original


async def test_quit_can_save_first(biceps, config_path):
    async with biceps() as session:
        await session.pilot.press("c", "q", "s")
        await until(session.pilot, lambda: session.app.return_code is not None)
        assert session.app.return_code == 0
    assert load_config(config_path).arm.length == 32.9


async def test_ctrl_q_asks_even_from_inside_a_dialog(biceps):
    async with biceps() as session:
        await session.pilot.press("c", "e", "ctrl+q")
        assert isinstance(session.app.screen, Choice)
        await session.pilot.press("ctrl+q")  # asking twice does not stack questions
        await session.pilot.press("escape")
        assert isinstance(session.app.screen, Prompt)


async def test_saving_after_contracting_changes_the_pose_line_alone(biceps, config_path):
    before = config_path.read_text().splitlines()
    async with biceps() as session:
        await session.pilot.press("C", "C", "ctrl+s")
        await session.settle()
        assert not session.app.unsaved
    after = config_path.read_text().splitlines()
    changed = [line for line in difflib.unified_diff(before, after, lineterm="", n=0)
               if line[:1] in "+-" and line[:3] not in ("+++", "---")]
    assert changed == ["-pose_length = 33.0", "+pose_length = 31.0"]
    # The comments beside the nodes still say what the nodes are.
    belly = next(line for line in after if "# the belly" in line)
    radius = float(re.match(r"\s*\[([\d.]+),", belly)[1])
    area = re.search(r"about ([\d.]+) cm\^2", belly)[1]
    assert f"{math.pi * radius**2:.1f}" == area


async def test_turning_and_shading_are_saved_but_quitting_does_not_ask_about_them(
    biceps, config_path
):
    async with biceps() as session:
        await session.pilot.press("right", "g", "l", "plus")
        assert not session.app.unsaved
        await session.pilot.press("ctrl+s")
        await session.settle()
        await session.pilot.press("left", "q")
        assert session.app.return_code == 0  # quit at once, no question
    saved = load_config(config_path)
    assert (saved.view.yaw, saved.render.shading) == (-20.0, "phong")


async def test_a_drag_saves_a_round_angle(biceps, config_path):
    async with biceps() as session:
        session.app.action_turn(13.783785, 0.0, 0.0)
        await session.pilot.press("ctrl+s")
        await session.settle()
    assert "\nyaw = -11.2 " in config_path.read_text()


async def test_turning_keeps_whether_the_model_is_saved_without_comparing_it(biceps,
                                                                             monkeypatch):
    from biceps.tui import app

    compared = []
    has_unsaved_edits = app.has_unsaved_edits
    monkeypatch.setattr(app, "has_unsaved_edits",
                        lambda *scenes: compared.append(scenes) or has_unsaved_edits(*scenes))
    async with biceps() as session:
        compared.clear()  # (once, as the app starts)
        await session.pilot.press("right", "l", "w")
        assert compared == [] and not session.app.unsaved
        await session.pilot.press("c", "right", "l")
        assert len(compared) == 1 and session.app.unsaved
