"""The help and the footer fit the terminal, 80 columns too (every key in the help:
test_app_screens.py)."""

import gc
import weakref
from importlib.resources import files

import pytest
from textual.screen import ModalScreen
from textual.widgets import RichLog
from textual.widgets._footer import FooterKey

from biceps.tui.screens.help import HelpLog, HelpScreen
from biceps.tui.widgets.footer import FittedFooter
from biceps.tui.widgets.node_table import NodeTable
from conftest import screen_rows
from waiting import until

HELP = files("biceps.tui").joinpath("help.md").read_text(encoding="utf-8")


@pytest.mark.parametrize("size", [(80, 24), (100, 30), (200, 60)])
async def test_the_help_is_wrapped_beside_its_scrollbar(biceps, size):
    async with biceps(size) as session:
        await session.pilot.press("question_mark")
        await until(session.pilot, lambda: _help_written(session.app))
        log = session.app.screen.query_one(RichLog)
        room = log.scrollable_content_region.width
        assert log.virtual_size.width <= room
        assert not log.show_horizontal_scrollbar
        assert max(line.cell_length for line in log.lines) <= room
        # The first paragraph whole, every word of it, in order.
        shown = " ".join(line.text.strip() for line in log.lines)
        first = " ".join(HELP.split("\n\n")[1].split()).replace("`", "")
        assert first in " ".join(shown.split())


def _shown(log: RichLog) -> str:
    return " ".join(" ".join(line.text.strip() for line in log.lines).split())


FIRST_PARAGRAPH = " ".join(HELP.split("\n\n")[1].split()).replace("`", "")


async def test_a_help_covered_before_it_is_laid_out_waits_and_shows_when_uncovered(
        biceps, monkeypatch):
    # Under a storm of keys a help was covered by the next dialog before it was laid out,
    # and asked to be written again after every refresh, for ever: the app fell behind its
    # input by minutes, and q was answered minutes late.
    writes = []
    write = HelpLog._write
    monkeypatch.setattr(HelpLog, "_write", lambda log: (writes.append(log), write(log))[1])
    async with biceps() as session:
        help = HelpScreen()
        session.app.push_screen(help)
        session.app.push_screen(ModalScreen())
        for _ in range(20):  # refreshes: each one wrote it again
            await session.pilot.pause(0.02)
        assert len(writes) <= 1
        session.app.pop_screen()
        log = help.query_one(HelpLog)
        await until(session.pilot, lambda: log.lines)
        assert FIRST_PARAGRAPH in _shown(log)


async def test_the_help_is_wrapped_again_when_the_terminal_is_resized(biceps):
    async with biceps((120, 40)) as session:
        await session.pilot.press("question_mark")
        log = session.app.screen.query_one(HelpLog)
        await until(session.pilot, lambda: log.lines)
        await session.pilot.resize_terminal(80, 24)
        room = lambda: log.scrollable_content_region.width  # noqa: E731
        await until(session.pilot, lambda: log.lines and
                    max(line.cell_length for line in log.lines) <= room() < 100)
        assert FIRST_PARAGRAPH in _shown(log)


def _help_written(app) -> bool:
    return bool(isinstance(app.screen, HelpScreen) and app.screen.query_one(RichLog).lines)


def _footer_keys(session) -> list[FooterKey]:
    footer = session.app.screen.query_one(FittedFooter)
    return [key for key in footer.query(FooterKey) if key.display and key.parent.display]


async def _footer_settled(session) -> None:
    for _ in range(3):  # laid out, measured, the keys of least worth dropped
        await session.pilot.pause(0.1)


@pytest.mark.parametrize("focus", ["picture", "node table"])
@pytest.mark.parametrize("width", [60, 80, 100])
async def test_the_footer_shows_whole_keys_only(biceps, focus, width):
    async with biceps((width, 24)) as session:
        if focus == "node table":
            session.app.screen.query_one(NodeTable).focus()
        await _footer_settled(session)
        keys = _footer_keys(session)
        palette = next(key for key in keys if key.has_class("-command-palette"))
        for key in keys:
            if key is not palette:
                assert key.region.right <= palette.region.x, key.description
        row = screen_rows(session.app)[-1]
        for key in keys:
            assert f"{key.key_display} {key.description}".strip() in row
        actions = {key.action for key in keys}
        assert {"help", "quit"} <= actions  # always
        if focus == "node table":
            assert {"edit_node", "insert_node", "delete_node"} <= actions


async def test_a_wide_footer_has_the_plots_and_the_recording_too(biceps):
    async with biceps((80, 24)) as session:
        await _footer_settled(session)
        assert "toggle_plots" not in {key.action for key in _footer_keys(session)}
        await session.pilot.resize_terminal(120, 30)
        await _footer_settled(session)
        shown = {key.action for key in _footer_keys(session)}
        assert {"toggle_plots", "record", "export", "save", "help", "quit"} <= shown


async def test_the_help_opens_in_the_ansi_theme(biceps):
    # Its accent is Textual's ansi_green, which Rich does not know by that name.
    async with biceps() as session:
        session.app.theme = "ansi-dark"
        await session.pilot.press("question_mark")
        await until(session.pilot, lambda: _help_written(session.app))
        assert session.app.failure is None


async def test_the_footer_is_built_again_only_when_its_keys_change(biceps, monkeypatch):
    # Textual's footer mounts every key anew whenever its screen's bindings may have
    # changed: four times as the app started, to the same keys.
    built = []
    compose = FittedFooter.compose
    monkeypatch.setattr(FittedFooter, "compose",
                        lambda footer: (built.append(footer.size.width), compose(footer))[1])
    async with biceps() as session:
        await _footer_settled(session)
        assert len([width for width in built if width]) == 1
        built.clear()
        await session.pilot.press("c", "right")  # the same keys apply
        await _footer_settled(session)
        assert built == []
        session.app.screen.query_one(NodeTable).focus()  # its own keys too
        await _footer_settled(session)
        assert len(built) == 1
        assert "edit_node" in {key.action for key in _footer_keys(session)}


async def test_a_second_fit_of_the_same_keys_changes_nothing_and_the_footer_rests(
        biceps, monkeypatch):
    # Two compositions in a row (the width changing twice before a refresh) left two fits
    # pending for the last one's keys. The second took the keys the first had dropped (they
    # have no region) for keys not laid out yet, and waited for them at every refresh: a
    # core kept busy for as long as the keys stayed the same.
    async with biceps((60, 24)) as session:
        await _footer_settled(session)
        footer = session.app.screen.query_one(FittedFooter)
        shown = _footer_keys(session)
        fits = []
        fit = FittedFooter._fit
        monkeypatch.setattr(FittedFooter, "_fit",
                            lambda self, *tries: (fits.append(tries), fit(self, *tries))[1])
        footer._fit()
        await _footer_settled(session)
        assert _footer_keys(session) == shown
        assert fits == [()]  # that one, and none after it


async def test_the_keys_of_a_footer_built_again_are_let_go(biceps):
    # Each key watches the footer's compact (Textual's data_bind), and Textual's footer kept
    # the watchers of the keys it removed: every resize left all its keys alive.
    async with biceps((100, 30)) as session:
        await _footer_settled(session)
        footer = session.app.screen.query_one(FittedFooter)
        removed = [weakref.ref(key) for key in footer.query(FooterKey)]
        for width in (90, 110, 95):
            await session.pilot.resize_terminal(width, 30)
            await _footer_settled(session)
        assert footer.query(FooterKey) and not any(key() in footer.query(FooterKey)
                                                   for key in removed)
        gc.collect()
        assert [key() for key in removed if key() is not None] == []
