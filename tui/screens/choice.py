"""A question with a few answers, each on a button and on a key, and a way out with escape."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

from textual import events, on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Button, Label

from biceps.tui.screens.once import Dialog


@dataclass(frozen=True)
class Answer:
    key: str
    label: str
    value: str
    variant: str = "default"


class ButtonRow(Horizontal):
    """The answers' buttons side by side, the dialog widened for them as far as the screen
    allows; one above another where they still do not fit (an 80-column terminal)."""

    _natural_width: int | None = None  # the buttons' width side by side

    def on_resize(self, event: events.Resize) -> None:
        if self._natural_width is None:
            self._natural_width = event.virtual_size.width
            box = self.parent
            around = box.outer_size.width - event.size.width  # the box's border and padding
            box.styles.width = max(box.outer_size.width, self._natural_width + around)
        self.set_class(self._natural_width > event.size.width, "-stacked")


class Choice(Dialog[str | None]):
    """Dismisses with the chosen answer's value, or ``None`` on escape or Cancel."""

    BINDINGS = [Binding("escape", "dismiss", "Cancel")]

    def __init__(self, title: str, question: str, answers: Sequence[Answer]) -> None:
        super().__init__(classes="dialog")
        self._title = title
        self._question = question
        self._answers = answers

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog-box") as box:
            box.border_title = self._title
            yield Label(self._question, markup=False)
            with ButtonRow(classes="dialog-buttons"):
                for answer in self._answers:
                    yield Button(f"{answer.label} ({answer.key})", variant=answer.variant,
                                 name=answer.value)
                yield Button("Cancel (esc)", id="cancel")

    @on(Button.Pressed)
    def _chosen(self, event: Button.Pressed) -> None:
        self.dismiss(event.button.name)  # None for Cancel, which has no name

    def on_key(self, event: events.Key) -> None:
        for answer in self._answers:
            if event.key == answer.key:
                event.stop()
                self.dismiss(answer.value)
