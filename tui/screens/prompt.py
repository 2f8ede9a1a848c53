"""A small form in a dialog: a few typed values, each read and checked before it is accepted.

A value that cannot be read, or that the model or the file system refuses, is said inside
the dialog, under the fields, and the dialog stays open with the text as typed, so nothing
is lost, nothing changes, and the keys typed next still go to the dialog. The check may do
the work itself (save the file, read the model) and ask questions over the dialog (replace
that file?): the dialog closes only once the work is done.
"""

from __future__ import annotations

import inspect
from typing import Any, Sequence

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.content import Content
from textual.widgets import Button, Input, Label

from biceps.engine.errors import BicepsError
from biceps.tui.fields import Check, Field
from biceps.tui.screens.once import Dialog

# What a field takes: no control characters, which would reach the terminal as they are
# when the field shows them (a paste can hold an escape sequence).
PRINTABLE = r"[^\x00-\x1f\x7f-\x9f]*"

LONGEST = 4096
"""The most characters a field takes, a path's worth: a paste of 100,000 made every key
after it cost time in proportion (Textual checks the whole text at each), 500 keys 5 s.
A paste that would make a field longer is not taken."""


class _Input(Input):
    """An input where ``end``, like ``→`` at the end, accepts the suggested completion, as a
    shell's does."""

    def action_end(self, select: bool = False) -> None:
        super().action_end(select)
        if not select:  # at the end, → takes the suggestion if there is one, else stays
            self.action_cursor_right()


class Prompt(Dialog[tuple[Any, ...] | None]):
    """Dismisses with the parsed values of every field, or ``None`` when cancelled.

    ``check`` (see :data:`Check`), given the parsed values, refuses them while the typed
    text is still there to fix. ``note``: a line under the title saying why it asks.
    """

    BINDINGS = [Binding("escape", "cancel", "Cancel")]

    def __init__(
        self,
        title: str,
        fields: Sequence[Field],
        *,
        check: Check | None = None,
        accept: str = "OK",
        note: str = "",
    ) -> None:
        super().__init__(classes="dialog")
        self._title = title
        self._fields = fields
        self._check = check
        self._accept = accept
        self._note = note
        self._checking = False  # the check is running: the values are not taken twice

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog-box") as box:
            box.border_title = self._title
            if self._note:
                yield Label(Content(self._note), classes="dialog-note")
            yield from self.compose_fields()
            yield Label(classes="dialog-error")
            with Horizontal(classes="dialog-buttons"):
                yield Button(self._accept, variant="primary", id="accept")
                yield Button("Cancel (esc)", id="cancel")

    def compose_fields(self) -> ComposeResult:
        """The labels and inputs of the fields, one under the other."""
        for field in self._fields:
            yield Label(field.label)
            yield _Input(field.text, suggester=field.suggester, restrict=PRINTABLE,
                         max_length=LONGEST)

    @property
    def checking(self) -> bool:
        """Whether the values are being checked (or the work done) with no question up."""
        return self._checking and self.app.screen is self

    @property
    def error(self) -> str:
        """What the dialog says is wrong with the values, if anything."""
        return str(self.query_one(".dialog-error", Label).content)

    def _say(self, error: str) -> None:
        label = self.query_one_optional(".dialog-error", Label)
        if label is None:  # closed while its check ran: nobody to tell
            return
        # Content, not a str: the message may quote a file name such as [b]x.toml.
        label.update(Content(error))
        label.set_class(bool(error), "-shown")

    @on(Input.Changed)
    def _typed(self) -> None:
        self._say("")  # what it said was about the text before

    @on(Input.Submitted)
    @on(Button.Pressed, "#accept")
    def _accept_values(self) -> None:
        if self._checking:
            return
        values = []
        for field, box in zip(self._fields, self.query(Input)):
            try:
                values.append(field.parse(box.value))
            except ValueError as error:
                box.add_class("-invalid")  # the input clears it itself at the next keystroke
                box.focus()
                self._say(f"{field.label}: {error}")
                return
        self._checking = True
        self._run_check(tuple(values))

    @work(group="prompt")
    async def _run_check(self, values: tuple[Any, ...]) -> None:
        # A worker: the check may ask over the dialog (push_screen_wait needs one).
        try:
            if self._check is not None:
                verdict = self._check(*values)
                if inspect.isawaitable(verdict):
                    verdict = await verdict
                if verdict is False:
                    return
        except BicepsError as error:
            self._say(str(error))
            return
        finally:
            self._checking = False
        if self in self.app.screen_stack:  # not closed while its check ran
            self.dismiss(values)

    def action_cancel(self) -> None:
        # Not while the check works: it may be writing the file the dialog names, and
        # the caller would take the file as not written.
        if not self._checking:
            self.dismiss(None)

    @on(Button.Pressed, "#cancel")
    def _cancel(self) -> None:
        self.action_cancel()
