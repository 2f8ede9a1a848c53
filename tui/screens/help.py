"""Every key, read from help.md.

Written once into a log of lines (Rich renders the Markdown in about 15 ms): Textual's
Markdown widget builds a widget for every block and table, a quarter of a second before
the help shows, where a key should be answered within a tenth.
"""

from __future__ import annotations

from importlib.resources import files

from rich.markdown import Markdown
from rich.style import Style
from rich.theme import Theme
from textual.app import ComposeResult
from textual.binding import Binding
from textual.color import Color
from textual.widgets import RichLog

from biceps.tui.screens.once import Dialog

HELP = files("biceps.tui").joinpath("help.md").read_text(encoding="utf-8")


class HelpLog(RichLog):
    """help.md, wrapped to the log's room beside its scrollbar: written when the log first
    has a width and again when the width changes (a resized terminal). Not before: under a
    storm of keys the screen may be mounted long before it is laid out, or never be (closed
    at once, or covered by another dialog)."""

    _written_width = 0

    def on_resize(self) -> None:
        # RichLog's own handler, which runs after this one, is where the log learns that it
        # has a size: write once both have run.
        self.call_later(self._write)

    def _write(self) -> None:
        width = self.scrollable_content_region.width
        if not width or width == self._written_width:
            return
        self._written_width = width
        # Headings in the theme's accent, as Textual's own Markdown has them, rather than
        # Rich's magenta: a terminal's magenta may be the muscle's red.
        # Read by Textual: the ANSI theme's colours (ansi_green) are not Rich's names.
        theme = self.app.current_theme
        heading = Style(bold=True, color=Color.parse(theme.accent or theme.primary).rich_color)
        headings = Theme({f"markdown.h{level}": heading for level in (1, 2, 3)})
        self.clear()
        with self.app.console.use_theme(headings):
            # The width given: RichLog would widen the text to its min_width, 78, and cut
            # it off in a terminal of 80 columns.
            self.write(Markdown(HELP), width=width)


class HelpScreen(Dialog[None]):
    BINDINGS = [Binding("escape,q,f1,question_mark", "dismiss", "Close help")]

    def compose(self) -> ComposeResult:
        log = HelpLog(id="help", auto_scroll=False, wrap=True)
        log.border_title = "biceps: keys and mouse"
        log.border_subtitle = "escape to close"
        yield log
