"""A visitor under ``biceps serve``: files only in its own folder, every export a download."""

import shutil

import pytest
from PIL import Image
from textual.widgets import Input

from biceps.engine.config import BUNDLED, load_config
from biceps.tui import visitor
from biceps.tui.app import BicepsApp
from biceps.tui.parse import parse_path
from biceps.tui.screens.prompt import Prompt
from biceps.tui.screens.record import RecordPrompt
from biceps.tui.suggest import PathSuggester
from decode import decoded
from waiting import until


@pytest.fixture
def own_folder(tmp_path, monkeypatch):
    """The visitor's folder, holding an upload (mine.toml, the toy model) and a link to a
    configuration outside it (link.toml -> ../secret.toml, the bundled fine model)."""
    monkeypatch.chdir(tmp_path)  # given back after the test
    monkeypatch.setattr(visitor, "_folder", None)
    folder = tmp_path / "visitor"
    folder.mkdir()
    shutil.copy(BUNDLED / "toy.toml", folder / "mine.toml")
    shutil.copy(BUNDLED / "fine.toml", tmp_path / "secret.toml")
    (folder / "link.toml").symlink_to(tmp_path / "secret.toml")
    visitor.confine_to(folder)
    return folder


async def _open(session, name: str) -> None:
    await session.pilot.press("ctrl+o")
    await until(session.pilot, lambda: isinstance(session.app.screen, Prompt))
    (box,) = session.app.screen.query(Input)
    box.value = name
    await session.pilot.press("enter")
    await session.settle()


@pytest.mark.parametrize("name, reason", [
    ("{outside}/secret.toml", "not a path on the server"),
    ("/etc/passwd", "not a path on the server"),
    ("../secret.toml", "'..' leads out of your own folder"),
    ("sub/../../secret.toml", "'..' leads out of your own folder"),
    ("link.toml", "a link that leads out of your own folder"),
    ("~/secret.toml", "not a path on the server"),
])
async def test_the_open_dialog_refuses_every_way_out_of_the_visitors_folder(
        biceps, own_folder, name, reason):
    name = name.format(outside=own_folder.parent)
    async with biceps() as session:
        before = session.app.scene
        await _open(session, name)
        assert isinstance(session.app.screen, Prompt)
        assert reason in session.app.screen.error
        assert session.app.scene is before


@pytest.mark.parametrize("name, nodes", [("mine.toml", 4), ("elbow", None), ("toy", 4)])
async def test_the_visitor_opens_its_uploads_and_the_bundled_models(biceps, own_folder, name,
                                                                     nodes):
    async with biceps() as session:
        await _open(session, name)
        assert not isinstance(session.app.screen, Prompt)
        expected = own_folder / name if name.endswith(".toml") else BUNDLED / f"{name}.toml"
        assert session.app.config.path.resolve() == expected.resolve()
        if nodes is not None:
            assert session.app.scene.arm.muscle.node_count == nodes


async def test_the_open_dialog_lists_the_bundled_models_and_the_visitors_own(biceps,
                                                                             own_folder):
    (own_folder / "second.toml").write_text("# an upload\n")
    (own_folder / "picture.png").write_bytes(b"")
    async with biceps() as session:
        await session.pilot.press("ctrl+o")
        await until(session.pilot, lambda: isinstance(session.app.screen, Prompt))
        (note,) = session.app.screen.query(".dialog-note")
        shown = str(note.render())
    # Not the link leading out of the folder, nor the picture: only models that are there.
    assert ("A bundled model by its name: biceps, elbow, fine, toy; or one of your files: "
            "mine.toml, second.toml. Upload your own with the bar above.") in " ".join(
        shown.split())


async def test_a_bad_upload_is_refused_with_the_file_and_field_and_changes_nothing(
        biceps, own_folder):
    (own_folder / "bad.toml").write_text('[muscle]\nlength = "long"\n'
                                         "nodes = [[1.0, 0.5], [2.0, 1.0]]\n")
    async with biceps() as session:
        before = session.app.scene
        await _open(session, "bad.toml")
        assert isinstance(session.app.screen, Prompt)
        assert ("bad.toml:2: muscle.length: must be a finite number above 0 cm (found 'long')"
                in session.app.screen.error)
        assert session.app.scene is before


async def test_names_are_suggested_only_from_the_visitors_folder(own_folder):
    suggester = PathSuggester((".toml",))
    assert await suggester.get_suggestion("mi") == "mine.toml"
    assert await suggester.get_suggestion(f"{own_folder.parent}/sec") is None
    assert await suggester.get_suggestion("../sec") is None


def test_outside_serve_file_names_are_as_typed(tmp_path, monkeypatch):
    monkeypatch.setattr(visitor, "_folder", None)
    assert parse_path(str(tmp_path / "a.png")) == tmp_path / "a.png"
    assert parse_path("../a.png").parts[0] == ".."


@pytest.fixture
def in_a_browser(monkeypatch):
    """The app as under Textual's web driver, every file it delivers recorded (name, bytes)."""
    delivered: list[tuple[str, bytes]] = []

    def deliver(app, path, **options):
        with open(path, "rb") as file:
            delivered.append((path.name, file.read()))

    monkeypatch.setattr(BicepsApp, "is_web", property(lambda app: True))
    monkeypatch.setattr(BicepsApp, "deliver_binary", deliver)
    return delivered


async def test_an_export_in_the_browser_is_a_download(biceps, own_folder, in_a_browser):
    async with biceps() as session:
        await session.pilot.press("e")
        await until(session.pilot, lambda: isinstance(session.app.screen, Prompt))
        file_box, size_box = session.app.screen.query(Input)
        assert file_box.value == "biceps.png"
        size_box.value = "64x48"
        await session.pilot.press("enter")
        await session.settle()
        await until(session.pilot, lambda: in_a_browser)
    ((name, data),) = in_a_browser
    assert name == "biceps.png"
    picture = Image.open(own_folder / name)
    assert picture.size == (64, 48)
    assert (own_folder / name).read_bytes() == data


async def test_saving_in_the_browser_downloads_the_model(biceps, own_folder, in_a_browser):
    async with biceps(on=load_config(own_folder / "mine.toml")) as session:
        await session.pilot.press("c", "ctrl+s")
        await until(session.pilot, lambda: in_a_browser)
    ((name, data),) = in_a_browser
    assert name == "mine.toml"
    assert b"pose_length" in data and data == (own_folder / "mine.toml").read_bytes()


async def test_a_recording_in_the_browser_is_a_download(biceps, own_folder, in_a_browser):
    async with biceps() as session:
        await session.pilot.press("v")
        await until(session.pilot, lambda: isinstance(session.app.screen, RecordPrompt))
        values = ["cycle.gif", "96x54", "0", "130", "8", "25", "bounce"]
        for box, value in zip(session.app.screen.query(Input), values):
            box.value = value
        await session.pilot.press("enter")

        def recording() -> list:
            return [worker for worker in session.app.workers if worker.group == "record"]

        await until(session.pilot, lambda: recording() or in_a_browser)
        if recording():
            await session.app.workers.wait_for_complete(recording())
        await until(session.pilot, lambda: in_a_browser)
    ((name, data),) = in_a_browser
    assert name == "cycle.gif"
    assert data == (own_folder / name).read_bytes()
    frames = decoded(own_folder / name)
    assert len(frames) == 8 and frames[0].shape == (54, 96, 3)
