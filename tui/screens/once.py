"""Dialogs that close once, and a command palette that does too.

Keys come in bursts (a person pressing enter twice, a paste, a terminal catching up), and
Textual hands each key to the widget focused when it arrives, then runs its binding on the
screen in front when the widget gets to it. So the second enter of a quick double enter
reaches a dialog that the first has already closed, and it closes it again: Textual's
``Screen.dismiss`` pops whatever screen is in front, the main screen beneath if nothing
else is left, which raises ScreenStackError and ends the app (Textual 8.2: the same in its
own command palette, ctrl+p enter enter). A dialog here is dismissed once; the keys after
that are dropped.

The palette has more faults, guarded here too: page down before its list has been laid
out (ctrl+p then page down at once) looks up a line the list has not made yet, KeyError: 0;
and a key typed just before it closed starts a search that ends after it has gone, and
looks for its list there, NoMatches, as do its timers and watchers firing as it closes
(both let pass in ``tui/textual_private.py``); and a click outside it in a window shrunk
since finds nothing there, NoWidget.
"""

from __future__ import annotations

from typing import TypeVar

from textual import on
from textual.await_complete import AwaitComplete
from textual.binding import Binding
from textual.command import CommandList
from textual.errors import NoWidget
from textual.events import Click
from textual.screen import ModalScreen
from textual.widgets import Input, OptionList

from biceps.tui.screens.sized import LatestSize
from biceps.tui.textual_private import guarded_palette


Result = TypeVar("Result")


class DismissedOnce(LatestSize[Result]):
    """A screen whose :meth:`dismiss` acts once, and only while it is in front (and that
    lays itself out only for the terminal's latest size)."""

    _dismissed = False

    def dismiss(self, result: Result | None = None) -> AwaitComplete:
        if self._dismissed or self is not self.app.screen:
            return AwaitComplete.nothing()
        self._dismissed = True
        return super().dismiss(result)


# DismissedOnce goes last among the bases: Textual takes a screen's CSS and component
# classes from its first base and that base's first bases, which must be ModalScreen's and
# CommandPalette's (or the guarded palette's, whose first base is CommandPalette).


class Dialog(ModalScreen[Result], DismissedOnce[Result]):
    """A modal dialog, dismissed once."""


class Palette(guarded_palette(), DismissedOnce[None]):
    """Textual's command palette, which runs one command, once, and pages only a list it has
    laid out."""

    BINDINGS = [
        Binding("pagedown", "page(1)", "Next page", show=False),
        Binding("pageup", "page(-1)", "Previous page", show=False),
    ]

    @on(Input.Changed)
    @on(Input.Submitted)
    @on(OptionList.OptionSelected)
    def _after_closing(self, event: Input.Changed | Input.Submitted |
                       OptionList.OptionSelected) -> None:
        # Keys typed before the palette closed still reach its input. Its own handlers run
        # next, and would run the command again, or start a search that, finishing after
        # the palette has gone, looks for its list (NoMatches).
        if self._dismissed:
            event.prevent_default()
            event.stop()

    def on_click(self, event: Click) -> None:
        # A click outside the palette closes it (Textual's handler, after this one): it
        # looks for what was clicked, and in a window shrunk since (to 1x3, say) there is
        # nothing there, NoWidget. Such a click does nothing.
        try:
            self.get_widget_at(event.screen_x, event.screen_y)
        except NoWidget:
            event.prevent_default()

    def action_page(self, direction: int) -> None:
        lists = self.query(CommandList)  # none yet, or none left as the palette closes
        if not lists or not lists[0].option_count or not lists[0].scrollable_content_region:
            return  # nothing listed, or not laid out yet
        commands = lists[0]
        if direction > 0:
            commands.action_page_down()
        else:
            commands.action_page_up()
