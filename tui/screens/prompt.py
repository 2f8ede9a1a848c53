"""A small form in a dialog: a few typed values, each read and checked before it is accepted.

A value that cannot be read, or that the model refuses, gets a notification and the dialog
stays open with the text as typed, so nothing is lost and nothing changes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Generic, Sequence, TypeVar

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.suggester import Suggester
from textual.widgets import Button, Input, Label

from biceps.engine.errors import BicepsError
from biceps.tui.screens.once import Dialog

T = TypeVar("T")

# What a field takes: no control characters, which would reach the terminal as they are
# when the field shows them (a paste can hold an escape sequence).
PRINTABLE = r"[^\x00-\x1f\x7f-\x9f]*"

LONGEST = 4096
"""The most characters a field takes, a path's worth: a paste of 100,000 made every key
after it cost time in proportion (Textual checks the whole text at each), 500 keys 5 s.
A paste that would make a field longer is not taken."""


@dataclass(frozen=True)
class Field(Generic[T]):
    label: str
    text: str  # what the input starts with
    parse: Callable[[str], T]  # raises ValueError saying what is wrong
    suggester: Suggester | None = None


class _Input(Input):
    """An input where ``end``, like ``→`` at the end, accepts the suggested completion, as a
    shell's does."""

    def action_end(self, select: bool = False) -> None:
        super().action_end(select)
        if not select and self._suggestion:  # private: Textual is pinned to 8.x
            self.action_cursor_right()


class Prompt(Dialog[tuple[Any, ...] | None]):
    """Dismisses with the parsed values of every field, or ``None`` when cancelled.

    ``check``, given the parsed values, raises :class:`BicepsError` if the model would
    refuse them, so the refusal is said while the typed text is still there to fix.
    """

    BINDINGS = [Binding("escape", "dismiss", "Cancel")]

    def __init__(
        self,
        title: str,
        fields: Sequence[Field],
        *,
        check: Callable[..., object] | None = None,
        accept: str = "OK",
    ) -> None:
        super().__init__(classes="dialog")
        self._title = title
        self._fields = fields
        self._check = check
        self._accept = accept

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog-box") as box:
            box.border_title = self._title
            for field in self._fields:
                yield Label(field.label)
                yield _Input(field.text, suggester=field.suggester, restrict=PRINTABLE,
                             max_length=LONGEST)
            with Horizontal(classes="dialog-buttons"):
                yield Button(self._accept, variant="primary", id="accept")
                yield Button("Cancel (esc)", id="cancel")

    @on(Input.Submitted)
    @on(Button.Pressed, "#accept")
    def _accept_values(self) -> None:
        values = []
        for field, box in zip(self._fields, self.query(Input)):
            try:
                values.append(field.parse(box.value))
            except ValueError as error:
                self._complain(box, f"{field.label}: {error}")
                return
        if self._check is not None:
            try:
                self._check(*values)
            except BicepsError as error:
                self.notify(str(error), severity="warning", markup=False)
                return
        self.dismiss(tuple(values))

    @on(Button.Pressed, "#cancel")
    def _cancel(self) -> None:
        self.dismiss(None)

    def _complain(self, box: Input, message: str) -> None:
        box.add_class("-invalid")  # the input clears it itself at the next keystroke
        box.focus()
        self.notify(message, severity="warning", markup=False)
