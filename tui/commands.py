"""The command palette offers every key's action, found by its description, and with
several muscles each muscle to pick for the node table.

The commands are read from the bindings themselves, so a new key is in the palette the
moment it is bound, with the key shown beside it.
"""

from __future__ import annotations

from functools import partial
from typing import Iterator

from textual.binding import Binding
from textual.command import DiscoveryHit, Hit, Hits, Provider
from textual.dom import DOMNode

from biceps.tui.widgets.node_table import NodeTable


class KeyCommands(Provider):
    def _commands(self) -> Iterator[tuple[str, str, partial]]:
        app = self.app
        owners: list[DOMNode] = [app, self.screen, *self.screen.query(NodeTable)]
        for owner in owners:
            keys: dict[str, list[str]] = {}
            descriptions: dict[str, str] = {}
            for binding in Binding.make_bindings(type(owner).BINDINGS):
                # (a priority binding of the app's repeats one of its others: the arrows')
                if binding.description and not binding.priority:
                    keys.setdefault(binding.action, []).append(app.get_key_display(binding))
                    # The footer's word, or the whole sentence where it has one.
                    descriptions[binding.action] = binding.tooltip or binding.description
            for action, shown in keys.items():
                run = partial(app.run_action, action, owner)
                yield descriptions[action], ", ".join(shown), run

    def _muscles(self) -> Iterator[tuple[str, str, partial]]:
        names = self.app.scene.arm.names
        if len(names) > 1:
            for index, name in enumerate(names):
                yield (f"Edit muscle {name}", "the driver" if index == 0 else "t cycles",
                       partial(self.app.run_action, f"select_muscle({index})"))

    async def discover(self) -> Hits:
        for name, keys, run in (*self._commands(), *self._muscles()):
            yield DiscoveryHit(name, run, help=keys)

    async def search(self, query: str) -> Hits:
        matcher = self.matcher(query)
        for name, keys, run in (*self._commands(), *self._muscles()):
            score = matcher.match(name)
            if score > 0:
                yield Hit(score, matcher.highlight(name), run, help=keys)
