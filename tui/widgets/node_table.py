"""The muscle's nodes, one row each, and the keys that edit them."""

from __future__ import annotations

from typing import Callable

from rich.text import Text
from textual.binding import Binding
from textual.coordinate import Coordinate
from textual.message import Message
from textual.widgets import DataTable

from biceps.engine.muscle import Muscle
from biceps.tui.changes import node_bounds, subdivided, with_node, with_node_inserted
from biceps.tui.parse import parse_number
from biceps.tui.screens.prompt import Field, Prompt

COLUMNS = ("#", "at cm", "r cm", "growth")


class NodeTable(DataTable):
    BINDINGS = [
        Binding("enter", "edit_node", "Edit node"),
        Binding("n,insert", "insert_node", "Insert after"),
        Binding("delete,backspace", "delete_node", "Delete"),
        Binding("slash", "subdivide", "Subdivide all"),
        Binding("home", "first_node", "First node", show=False),
        Binding("end", "last_node", "Last node", show=False),
    ]

    class ChangeRequested(Message):
        """The user asked for ``change`` to be made to the muscle; ``what`` says it in words
        (``node 8 deleted``); ``undoable_note``: say that undo takes it back, for an edit
        that removes what a person typed."""

        def __init__(self, change: Callable[[Muscle], Muscle], what: str,
                     undoable_note: bool = False) -> None:
            super().__init__()
            self.change = change
            self.what = what
            self.undoable_note = undoable_note

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, cursor_type="row", zebra_stripes=True)
        self._muscle: Muscle | None = None
        self._rows: list[tuple[str, ...]] = []

    def on_mount(self) -> None:
        self.add_columns(*COLUMNS)

    def show(self, muscle: Muscle) -> None:
        self._muscle = muscle
        rows = [
            (f"{number}", f"{at:.2f}", f"{radius:.3f}", f"{growth:.3f}")
            for number, (at, radius, growth) in enumerate(
                zip(muscle.positions, muscle.radii, muscle.growth), start=1
            )
        ]
        if len(rows) == len(self._rows):
            # Contracting changes every radius many times a second: touch only what changed.
            for y, (row, old) in enumerate(zip(rows, self._rows)):
                for x, (text, old_text) in enumerate(zip(row, old)):
                    if text != old_text:
                        self.update_cell_at(Coordinate(y, x), Text(text, justify="right"),
                                            update_width=len(text) != len(old_text))
        else:
            cursor = self.cursor_row
            self.clear()
            self.add_rows([[Text(text, justify="right") for text in row] for row in rows])
            self.move_cursor(row=min(cursor, len(rows) - 1), animate=False)
            self.border_title = f"nodes ({len(rows)})"
        self._rows = rows

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        # A table of rows has nothing to the sides: left and right fall through and turn
        # the model, so the arrows stay useful while the table has focus.
        return action not in ("cursor_left", "cursor_right")

    def on_data_table_row_selected(self, event: DataTable.RowSelected) -> None:
        event.stop()  # a click on the highlighted row
        self.action_edit_node()

    def action_edit_node(self) -> None:
        muscle, index = self._muscle, self.cursor_row
        if muscle is None:
            return

        def check(radius: float, growth: float) -> None:
            with_node(muscle, index, radius, growth)

        def request(values: tuple[float, float] | None) -> None:
            if values is not None:
                radius, growth = values
                self._request(lambda current: with_node(current, index, radius, growth),
                              f"node {index + 1} edited")

        bounds = node_bounds()
        fields = [
            _number_field(f"Radius ({_range(*bounds['radius'])})", muscle.radii[index]),
            _number_field(f"Growth ({_range(*bounds['growth'])})", muscle.growth[index]),
        ]
        self.app.push_screen(Prompt(f"Node {index + 1}", fields, check=check), request)

    def action_first_node(self) -> None:
        self.move_cursor(row=0)

    def action_last_node(self) -> None:
        self.move_cursor(row=self.row_count - 1)

    def action_insert_node(self) -> None:
        index = self.cursor_row
        self._request(lambda current: with_node_inserted(current, index),
                      f"a node inserted after node {index + 1}")

    def action_delete_node(self) -> None:
        index = self.cursor_row
        self._request(lambda current: current.without_node(index), f"node {index + 1} deleted",
                      undoable_note=True)

    def action_subdivide(self) -> None:
        self._request(subdivided, "every segment subdivided")

    def _request(self, change: Callable[[Muscle], Muscle], what: str,
                 undoable_note: bool = False) -> None:
        self.post_message(self.ChangeRequested(change, what, undoable_note))


def _range(low: float, high: float, unit: str) -> str:
    return f"{low:g} to {high:g}{unit}"


def _number_field(label: str, value: float) -> Field[float]:
    shown = f"{value:.4f}".rstrip("0").rstrip(".")

    def parse(text: str) -> float:
        # An untouched field keeps the exact value, not its rounded display.
        return float(value) if text.strip() == shown else parse_number(text)

    return Field(label, shown, parse)
