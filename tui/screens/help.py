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


class HelpScreen(Dialog[None]):
    BINDINGS = [Binding("escape,q,f1,question_mark", "dismiss", "Close help")]

    def compose(self) -> ComposeResult:
        log = RichLog(id="help", auto_scroll=False, wrap=True)
        log.border_title = "biceps: keys and mouse"
        log.border_subtitle = "escape to close"
        yield log

    def on_mount(self) -> None:
        self.call_after_refresh(self._write)  # once laid out: as wide as the log

    def _write(self) -> None:
        # Headings in the theme's accent, as Textual's own Markdown has them, rather than
        # Rich's magenta: a terminal's magenta may be the muscle's red.
        # Read by Textual: the ANSI theme's colours (ansi_green) are not Rich's names.
        accent = Color.parse(self.app.current_theme.accent or self.app.current_theme.primary)
        heading = Style(bold=True, color=accent.rich_color)
        headings = Theme({f"markdown.h{level}": heading for level in (1, 2, 3)})
        logs = self.query(RichLog)
        if not logs:
            return  # closed again before it was laid out (? then escape at once)
        log = logs.first()
        if not log.scrollable_content_region.width:  # not laid out yet: a busy app, a storm
            self.call_after_refresh(self._write)
            return
        with self.app.console.use_theme(headings):
            # As wide as the log's room beside its scrollbar, which RichLog would widen to
            # its min_width, 78, and cut off in a terminal of 80 columns.
            log.write(Markdown(HELP), width=log.scrollable_content_region.width)
