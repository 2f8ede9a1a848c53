"""Every key, read from help.md.

Written once into a log of lines (Rich renders the Markdown in about 15 ms): Textual's
Markdown widget builds a widget for every block and table, a quarter of a second before
the help shows, where a key should be answered within a tenth.
"""

from __future__ import annotations

from importlib.resources import files

from rich.markdown import Markdown
from textual.app import ComposeResult
from textual.binding import Binding
from textual.screen import ModalScreen
from textual.widgets import RichLog

HELP = files("biceps.tui").joinpath("help.md").read_text(encoding="utf-8")


class HelpScreen(ModalScreen[None]):
    BINDINGS = [Binding("escape,q,f1,question_mark", "dismiss", "Close help")]

    def compose(self) -> ComposeResult:
        log = RichLog(id="help", auto_scroll=False, wrap=True)
        log.border_title = "biceps: keys and mouse"
        log.border_subtitle = "escape to close"
        yield log

    def on_mount(self) -> None:
        self.query_one(RichLog).write(Markdown(HELP))  # as wide as the log, once laid out
