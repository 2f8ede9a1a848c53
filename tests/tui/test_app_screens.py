"""The layout follows the terminal's size; help and the command palette cover every key."""

from importlib.resources import files

import pytest
from textual.binding import Binding
from textual.widgets import RichLog, Static

from biceps.engine.config import rgb
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.app import BicepsApp
from biceps.tui.commands import KeyCommands
from biceps.tui.screens.help import HelpScreen
from biceps.tui.screens.main import MainScreen
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.viewport import Viewport
from pictures import pieces, shown_pixels


@pytest.fixture
def render_sizes(monkeypatch) -> list[tuple[int, int]]:
    """Every (width, height) in pixels the viewport asks its renderer for."""
    sizes = []

    class RecordingRenderer(SceneRenderer):
        def render(self, scene, width, height, framed=None, pixel_aspect=1.0):
            sizes.append((width, height))
            return super().render(scene, width, height, framed, pixel_aspect)

    monkeypatch.setattr("biceps.tui.rendering.SceneRenderer", RecordingRenderer)
    return sizes


async def test_the_picture_is_rendered_at_two_pixels_per_cell_and_again_on_resize(
    biceps, render_sizes
):
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        width, height = viewport.size
        assert render_sizes[-1] == (width, 2 * height)
        await session.pilot.resize_terminal(160, 50)
        await session.settle()
        assert viewport.size.width > width and viewport.size.height > height
        assert render_sizes[-1] == (viewport.size.width, 2 * viewport.size.height)
        assert viewport.render_line(0).cell_length == viewport.size.width


async def test_a_terminal_too_small_gets_a_message_instead_of_the_layout(biceps, render_sizes):
    async with biceps(size=(50, 12)) as session:
        screen = session.app.screen
        assert screen.has_class("-too-small")
        assert screen.query_one("#too-small", Static).display
        await session.pilot.resize_terminal(100, 30)
        await session.settle()
        assert not screen.has_class("-too-small")
        viewport = screen.query_one(Viewport)
        assert render_sizes[-1] == (viewport.size.width, 2 * viewport.size.height)


async def test_a_terminal_shrunk_too_small_clears_the_notes_over_its_message(biceps):
    async with biceps() as session:
        # The notes the app holds (run_test shows them as no toasts; Textual 8's own list).
        await session.pilot.press("b")  # a note: what the strain colours mean
        await session.settle()
        assert len(session.app._notifications) == 1
        await session.pilot.resize_terminal(30, 8)
        await session.settle()
        assert session.app.screen.has_class("-too-small")
        assert len(session.app._notifications) == 0


@pytest.mark.parametrize("key", ["question_mark", "f1"])
async def test_help_opens_and_closes(biceps, key):
    async with biceps() as session:
        await session.pilot.press(key)
        assert isinstance(session.app.screen, HelpScreen)
        await session.pilot.press("escape")
        assert isinstance(session.app.screen, MainScreen)


@pytest.mark.parametrize("theme", ["ansi-dark", "ansi-light"])
async def test_help_is_written_in_a_theme_of_ansi_colours(biceps, theme):
    # Their accents, "ansi_green" and "ansi_magenta", are no colours to Rich: help with such
    # a theme on (a storm's theme palette chose one) ended the app (StyleSyntaxError).
    async with biceps() as session:
        app = session.app
        app.theme = theme
        await session.pilot.press("question_mark")
        await session.settle()
        assert isinstance(app.screen, HelpScreen)
        assert app.screen.query_one(RichLog).lines  # written
        assert app.failure is None


def _bindings() -> list[Binding]:
    return [*Binding.make_bindings(BicepsApp.BINDINGS), *Binding.make_bindings(MainScreen.BINDINGS),
            *Binding.make_bindings(NodeTable.BINDINGS)]


# How help.md writes the keys whose Textual names are words.
WRITTEN = {
    "left": "←", "right": "→", "up": "↑", "down": "↓",
    "shift+left": "shift+←", "shift+right": "shift+→",
    "shift+up": "shift+↑", "shift+down": "shift+↓",
    "left_square_bracket": "[", "right_square_bracket": "]", "plus": "+", "equals_sign": "=",
    "minus": "-", "question_mark": "?", "slash": "/",
    "greater_than_sign": ">", "less_than_sign": "<", "right_curly_bracket": "}",
    "left_curly_bracket": "{",
}  # fmt: skip


def test_the_help_lists_every_key():
    help_text = files("biceps.tui").joinpath("help.md").read_text()
    for binding in _bindings():
        written = WRITTEN.get(binding.key, binding.key)
        assert f"`{written}`" in help_text, f"{binding.key} is not in help.md"


async def test_the_command_palette_offers_every_action(biceps):
    async with biceps() as session:
        provider = KeyCommands(session.app.screen)
        offered = {hit.text async for hit in provider.discover()}
        # (in the palette's words: the whole sentence where the footer has a word)
        described = {binding.tooltip or binding.description for binding in _bindings()
                     if binding.description}
        assert described <= offered


async def test_a_command_from_the_palette_runs(biceps):
    async with biceps() as session:
        await session.run_command("stretch 1 cm")
        assert session.app.scene.arm.length == pytest.approx(34.0)


async def test_the_side_panel_folds_away_in_a_narrow_terminal_and_h_brings_it_back(biceps):
    async with biceps(size=(80, 24)) as session:
        screen = session.app.screen
        side, viewport = screen.query_one("#side"), screen.query_one(Viewport)
        assert not side.display
        assert viewport.outer_size.width == 80  # the picture takes the room
        await session.pilot.press("h")
        assert side.display
        assert viewport.outer_size.width == 80 - side.outer_size.width
        await session.pilot.resize_terminal(60, 20)
        await session.pilot.pause()
        assert side.display  # asked for, so it stays


async def test_a_wide_terminal_shows_the_panel_and_h_hides_it(biceps):
    async with biceps(size=(120, 30)) as session:
        screen = session.app.screen
        side, viewport = screen.query_one("#side"), screen.query_one(Viewport)
        assert side.display and viewport.outer_size.width == 120 - 32
        await session.pilot.press("tab")
        assert session.app.focused.id == "nodes"
        await session.pilot.press("h")
        await session.pilot.pause()
        assert not side.display and viewport.outer_size.width == 120
        assert session.app.focused is viewport
        await session.settle()
        assert viewport.render_line(0).cell_length == viewport.size.width
        await session.pilot.press("h")
        assert side.display


async def test_at_80_by_24_the_bones_are_whole_with_the_side_panel_or_without(biceps, config):
    async with biceps(size=(80, 24)) as session:
        viewport = session.app.screen.query_one(Viewport)
        background = rgb(config.render.background)
        await session.pilot.press(*["minus"] * 4)  # zoomed out: the bones thinner still
        for _ in range(2):
            await session.pilot.press("h")
            await session.settle()
            assert pieces(shown_pixels(viewport), background) == 1


async def test_a_terminal_too_small_changes_nothing_out_of_sight_but_quits(biceps):
    async with biceps(size=(50, 12)) as session:
        before = session.app.scene
        await session.pilot.press("c", "X", "right", "j", "g", "h", "ctrl+z", "tab", "delete")
        assert session.app.scene is before
        assert session.app.screen.has_class("-panel-hidden")  # h did nothing either
        await session.pilot.press("q")
        assert session.app.return_code == 0


async def test_the_focus_comes_back_after_resizing_through_too_small(biceps):
    async with biceps(size=(120, 30)) as session:
        await session.pilot.press("tab")
        table = session.app.screen.query_one(NodeTable)
        assert session.app.focused is table
        await session.pilot.resize_terminal(50, 12)
        await session.pilot.pause()
        await session.pilot.resize_terminal(120, 30)
        await session.pilot.pause()
        assert session.app.focused is table
        await session.pilot.press("down")
        assert table.cursor_row == 1
