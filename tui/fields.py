"""What a dialog asks for: its fields and the check of their values, named apart from the
dialog (``tui/screens/prompt.py``) so that a widget can ask for values without importing a
screen."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Awaitable, Callable, Generic, Sequence, TypeVar

from textual.suggester import Suggester

T = TypeVar("T")

Check = Callable[..., "bool | None | Awaitable[bool | None]"]
"""Given a dialog's parsed values: raises :class:`BicepsError` to keep the dialog open with
the message in it, returns False to keep it open without one (a question asked over it was
declined), or anything else to close it with the values."""


@dataclass(frozen=True)
class Field(Generic[T]):
    label: str
    text: str  # what the input starts with
    parse: Callable[[str], T]  # raises ValueError saying what is wrong
    suggester: Suggester | None = None


Ask = Callable[[str, Sequence[Field], Check], Awaitable["tuple[Any, ...] | None"]]
"""``await ask(title, fields, check)``: the values a dialog titled ``title`` asked for in
``fields``, parsed and passed by ``check``, or None if it was cancelled."""
