"""The footer: Textual's own, compact, less the keys of least worth that do not fit.

Textual's footer lays every key shown out in one row and, when they are too many for the
width, lets the last ones run under the command palette's key, cut off mid-word ("c
Contrac▏^p palette" at 80 columns with the node table's keys in front). This one drops
whole keys instead, those of least worth first, until the rest fit; every key is still in
the help (``?``) and the command palette.
"""

from __future__ import annotations

from typing import Hashable, Iterable, Sequence

from textual.events import Resize
from textual.screen import Screen
from textual.widget import Widget
from textual.widgets import Footer


FIT_TRIES = 3
"""Refreshes a fit waits for the keys to be laid out before it leaves them as they are."""


class FittedFooter(Footer):
    """A compact footer that drops the keys of least worth until the rest fit its width.

    ``kept_longest``: the actions (their names, without arguments) in the order they are
    dropped last: the first is dropped last of all. An action not named goes before them.
    """

    DEFAULT_CSS = """
    FittedFooter.-compact FooterLabel {
        margin-right: 1;  /* Textual's compact footer runs a group's name into the next key */
    }
    """

    def __init__(self, kept_longest: Sequence[str], *, id: str | None = None) -> None:
        super().__init__(id=id, compact=True)
        self._rank = {action: rank for rank, action in enumerate(kept_longest)}
        self._composed: Hashable = None  # the width and keys they were last laid out for
        self._fitted = False  # the keys composed last have had those of least worth dropped
        self._keys_known = False  # the screen has said which bindings apply

    def on_resize(self, event: Resize) -> None:
        # Wider, a key dropped may fit again: lay them all out anew, then drop. (Textual
        # sends Resize for a new virtual size too, which each drop makes: the width is the
        # same then, and recompose does nothing, or fits the keys if they were not shown.)
        self.call_after_refresh(self.recompose)

    def bindings_changed(self, screen: Screen) -> None:
        # (until then Textual's footer composes no keys)
        self._keys_known = True
        super().bindings_changed(screen)

    async def recompose(self) -> None:
        # Textual's footer recomposes, mounting every key anew, each time the screen says its
        # bindings changed: whenever the focus moves, four times as the app starts, mostly to
        # the same keys. So only when the keys or the width differ from the last time.
        composed_from = self._composed_from()
        if composed_from != self._composed:
            self._composed, self._fitted = composed_from, False
            await super().recompose()
            # Each key watches the footer's compact (Textual's data_bind), and the footer
            # keeps the watchers of the keys just removed, and so the keys, until compact
            # changes, which it never does (Textual issue 6666): a resize left every key
            # alive. Setting it again lets Textual drop the watchers of removed keys.
            self.mutate_reactive(Footer.compact)
        if not self._fitted:
            self.call_after_refresh(self._fit)

    def _composed_from(self) -> Hashable:
        """What Textual's footer composes its keys from (its ``compose``), and the width."""
        if not self._keys_known or not self.is_attached:
            return None
        shown = tuple((binding.key, binding.action, binding.description, binding.group,
                       enabled, tooltip)
                      for _, binding, enabled, tooltip in self.screen.active_bindings.values()
                      if binding.show or binding.key == self.app.COMMAND_PALETTE_BINDING)
        return self.size.width, shown

    def _fit(self, tries: int = FIT_TRIES) -> None:
        """Keep the keys of most worth that fit beside the docked ones (the palette's key),
        each as wide as it was laid out, all of them shown: once for each composition (the
        keys it drops have no region, and a second pass would take them for keys not laid
        out yet)."""
        if self._fitted:
            return
        units = self._units()
        if any(not widget.region for unit in units for widget in unit):
            if tries:  # not laid out yet
                self.call_after_refresh(self._fit, tries - 1)
            return  # not shown (a terminal too small, another screen in front): on a resize
        self._fitted = True
        room = self.size.width - sum(_width(widget) for widget in self._docked())
        for unit in sorted(units, key=self._worth, reverse=True):
            width = sum(_width(widget) for widget in unit)
            if width <= room:
                room -= width
            else:
                room = 0  # none after it either: the keys kept are the most worth
                for widget in unit:
                    widget.display = False

    def _docked(self) -> Iterable[Widget]:
        return (child for child in self.children if child.styles.dock != "none")

    def _units(self) -> list[list[Widget]]:
        """The keys that go or stay together: a group of keys and its label, or the keys of
        one action (c and x, contract and stretch, both change the length)."""
        units: list[list[Widget]] = []
        for child in self.children:
            if child.styles.dock != "none":
                continue
            if units and (_is(child, "FooterLabel")
                          or _action(child) and _action(child) == _action(units[-1][-1])):
                units[-1].append(child)
            else:
                units.append([child])
        return units

    def _worth(self, unit: list[Widget]) -> tuple[int, int]:
        """How long ``unit`` is kept: by the rank of its action, then the earlier first."""
        action = _action(unit[0])
        worth = len(self._rank) - self._rank[action] if action in self._rank else 0
        return worth, -self.children.index(unit[0])


def _width(widget: Widget) -> int:
    """The cells ``widget`` takes in a row, with its margins."""
    return widget.region.width + widget.styles.margin.width


def _action(widget: Widget) -> str:
    """The name of the action of a footer's key, or of a group's first key; else ''."""
    if _is(widget, "KeyGroup"):  # (its keys may not be mounted yet)
        widget = next(iter(widget.query("FooterKey")), None)
    return widget.action.split("(", 1)[0] if _is(widget, "FooterKey") else ""


def _is(widget: Widget | None, name: str) -> bool:
    """Whether ``widget`` is one of Textual's footer's pieces, by its type's name, as a
    stylesheet names it: the classes themselves are not exported (8.x)."""
    return widget is not None and any(cls.__name__ == name for cls in type(widget).__mro__)
