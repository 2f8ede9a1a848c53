"""The muscle's nodes, one row each, and the keys that edit them.

Drawn a line at a time (Textual's Line API) straight from the muscle's arrays: a contraction
changes every radius and position, and costs only the rows in view, however many nodes
there are. (A DataTable updated cell by cell took 0.3 s a contraction at 5,000 nodes.)
"""

from __future__ import annotations

import asyncio
from functools import partial
from typing import Callable

from rich.segment import Segment
from textual import events
from textual.binding import Binding
from textual.geometry import Size
from textual.message import Message
from textual.reactive import reactive
from textual.scroll_view import ScrollView
from textual.strip import Strip

from biceps.engine.bounds import GROWTH, NODES, RADIUS, Limits
from biceps.engine.muscle import Muscle
from biceps.tui.changes import with_node
from biceps.tui.parse import parse_number
from biceps.tui.fields import Ask, Field

COLUMNS = ("#", "at cm", "r cm", "growth")
PADDING = 1  # cells each side of a column's text


class NodeTable(ScrollView, can_focus=True):
    """The nodes of a muscle, a row each under a header that stays; the cursor picks one."""

    BINDINGS = [
        Binding("enter", "edit_node", "Edit", tooltip="Edit the node"),
        Binding("n,insert", "insert_node", "Insert", tooltip="Insert a node after this one"),
        Binding("delete,backspace", "delete_node", "Delete", tooltip="Delete the node"),
        Binding("slash", "subdivide", "Subdivide", tooltip="Subdivide every segment"),
        Binding("up", "move(-1)", "Previous node", show=False),
        Binding("down", "move(1)", "Next node", show=False),
        Binding("pageup", "page(-1)", "Page up", show=False),
        Binding("pagedown", "page(1)", "Page down", show=False),
        Binding("home", "move_to(0)", "First node", show=False),
        Binding("end", "move_to(-1)", "Last node", show=False),
    ]

    COMPONENT_CLASSES = {"node-table--header", "node-table--cursor", "node-table--even-row"}

    DEFAULT_CSS = """
    NodeTable {
        background: $surface;
        color: $foreground;
        &:focus {
            background-tint: $foreground 5%;
            & > .node-table--cursor {
                background: $block-cursor-background;
                color: $block-cursor-foreground;
                text-style: $block-cursor-text-style;
            }
            & > .node-table--header {
                background-tint: $foreground 5%;
            }
        }
        &:dark > .node-table--even-row {
            background: $surface-darken-1 40%;
        }
        & > .node-table--header {
            text-style: bold;
            background: $panel;
            color: $foreground;
        }
        & > .node-table--even-row {
            background: $surface-lighten-1 50%;
        }
        & > .node-table--cursor {
            background: $block-cursor-blurred-background;
            color: $block-cursor-blurred-foreground;
            text-style: $block-cursor-blurred-text-style;
        }
    }
    """

    cursor_row: reactive[int] = reactive(0)

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

    class NodePicked(Message):
        """The node the table picks for the picture to ring: ``node`` (0-based), or None
        while the table has not the focus (the picture marks nothing then)."""

        def __init__(self, node: int | None) -> None:
            super().__init__()
            self.node = node

    def __init__(self, ask_values: Ask, *, id: str | None = None) -> None:
        """``ask_values`` opens the dialog that edits a node (a screen's to open), apart
        from the app's ``ask``, which runs it one dialog at a time."""
        super().__init__(id=id)
        self._ask_values = ask_values
        self._muscle: Muscle | None = None
        self._widths = tuple(len(title) for title in COLUMNS)

    @property
    def row_count(self) -> int:
        return 0 if self._muscle is None else self._muscle.node_count

    def show(self, muscle: Muscle) -> None:
        """Show ``muscle``'s nodes; the cursor stays on the same row, or the last."""
        count_changed = muscle.node_count != self.row_count
        self._muscle = muscle
        # Each column as wide as its widest text: the largest number in it (all positive).
        largest = (muscle.node_count, muscle.length, muscle.max_radius, muscle.growth.max())
        widths = tuple(max(len(title), len(text)) for title, text in
                       zip(COLUMNS, _cells(*largest)))
        if widths != self._widths or count_changed:
            self._widths = widths
            self.virtual_size = Size(sum(widths) + 2 * PADDING * len(widths), 1 + self.row_count)
        if count_changed:
            self.border_title = f"nodes ({muscle.node_count:,})"
            self.cursor_row = min(self.cursor_row, muscle.node_count - 1)
        self.refresh()

    def row(self, index: int) -> tuple[str, ...]:
        """The texts of row ``index`` (0-based), as shown."""
        muscle = self._muscle
        at = muscle.length * index / (muscle.node_count - 1)
        return _cells(index + 1, at, muscle.radii[index], muscle.growth[index])

    def move_cursor(self, *, row: int) -> None:
        self.cursor_row = max(0, min(row, self.row_count - 1))

    def validate_cursor_row(self, row: int) -> int:
        return max(0, min(row, self.row_count - 1))

    def watch_cursor_row(self, old: int, new: int) -> None:
        self._scroll_to_cursor()
        self.refresh()
        if self.has_focus:
            self.post_message(self.NodePicked(new))

    def on_focus(self) -> None:
        self.post_message(self.NodePicked(self.cursor_row))

    def on_blur(self) -> None:
        # A dialog over the screen (the node's own, opened with enter) keeps the ring.
        if self.screen is self.app.screen:
            self.post_message(self.NodePicked(None))

    def _scroll_to_cursor(self) -> None:
        rows = max(self.scrollable_content_region.height - 1, 1)  # under the header
        top = round(self.scroll_y)
        if self.cursor_row < top:
            self.scroll_to(y=self.cursor_row, animate=False)
        elif self.cursor_row >= top + rows:
            self.scroll_to(y=self.cursor_row - rows + 1, animate=False)

    def on_resize(self) -> None:
        self._scroll_to_cursor()

    def render_line(self, y: int) -> Strip:
        width = self.scrollable_content_region.width
        if y == 0:
            return self._strip(COLUMNS, "node-table--header", width)
        index = round(self.scroll_y) + y - 1
        if self._muscle is None or index >= self.row_count:
            return Strip.blank(width, self.rich_style)
        if index == self.cursor_row:
            style = "node-table--cursor"
        else:
            style = "" if index % 2 else "node-table--even-row"  # zebra stripes, as DataTable's
        return self._strip(self.row(index), style, width)

    def _strip(self, texts: tuple[str, ...], component: str, width: int) -> Strip:
        style = self.get_component_rich_style(component) if component else self.rich_style
        pad = " " * PADDING
        cells = [Segment(pad + text.rjust(cell_width) + pad, style)
                 for text, cell_width in zip(texts, self._widths)]
        scroll_x = round(self.scroll_x)
        return Strip(cells).crop(scroll_x, scroll_x + width).extend_cell_length(width, style)

    def on_click(self, event: events.Click) -> None:
        if event.y == 0 or self._muscle is None:
            return
        index = round(self.scroll_y) + event.y - 1
        if index >= self.row_count:
            return
        if index == self.cursor_row:
            self.action_edit_node()  # a click on the picked node opens it
        else:
            self.cursor_row = index

    def action_move(self, rows: int) -> None:
        self.cursor_row += rows

    def action_page(self, pages: int) -> None:
        self.cursor_row += pages * max(self.scrollable_content_region.height - 1, 1)

    def action_move_to(self, row: int) -> None:
        self.cursor_row = row % max(self.row_count, 1)

    def action_edit_node(self) -> None:
        # Asked through the app, which opens one dialog at a time (BicepsApp.ask): a burst
        # of enters (or an enter beside e, ctrl+o) stacked a dialog each, each drawing the
        # ones beneath it, until Textual's compositor ran out of Python's stack
        # (RecursionError, in storms).
        self.app.ask(partial(self._edit_node, self.cursor_row))

    async def _edit_node(self, index: int) -> None:
        # The keys typed with enter (t, a held c) may have changed the muscle, but the table
        # shows a burst's numbers only after the burst (MainScreen._show_numbers, put on the
        # app's queue then): the dialog opens behind them, on the muscle as it is now, which
        # is the one OK changes.
        behind = asyncio.Event()
        self.app.call_later(behind.set)
        await behind.wait()
        muscle = self._muscle
        if muscle is None:
            return
        index = min(index, muscle.node_count - 1)

        def check(radius: float, growth: float) -> None:
            with_node(muscle, index, radius, growth)

        fields = [
            _number_field(f"Radius ({_range(RADIUS)})", muscle.radii[index]),
            _number_field(f"Growth ({_range(GROWTH)})", muscle.growth[index]),
        ]
        values = await self._ask_values(f"Node {index + 1}", fields, check)
        if values is not None:
            radius, growth = values
            self._request(lambda current: with_node(current, index, radius, growth),
                          f"node {index + 1} edited")

    def action_insert_node(self) -> None:
        index = self.cursor_row
        self._request(lambda current: current.with_node_inserted(index),
                      f"a node inserted after node {index + 1}")
        # The cursor on the new node at once, so that the keys typed next (delete) act on
        # it: they are handled before the muscle with it comes back to the table. A node
        # goes between two others, so its row is one the table has now.
        if index < self.row_count - 1 and self.row_count < NODES:
            self.cursor_row = index + 1

    def action_delete_node(self) -> None:
        index = self.cursor_row
        self._request(lambda current: current.without_node(index), f"node {index + 1} deleted",
                      undoable_note=True)

    def action_subdivide(self) -> None:
        self._request(Muscle.subdivided, "every segment subdivided")

    def _request(self, change: Callable[[Muscle], Muscle], what: str,
                 undoable_note: bool = False) -> None:
        self.post_message(self.ChangeRequested(change, what, undoable_note))


def _cells(number: int, at: float, radius: float, growth: float) -> tuple[str, ...]:
    return f"{number}", f"{at:.2f}", f"{radius:.3f}", f"{growth:.3f}"


def _range(limits: Limits) -> str:
    return f"{limits.low:g} to {limits.high:g}{limits.unit}"


def _number_field(label: str, value: float) -> Field[float]:
    shown = f"{value:.4f}".rstrip("0").rstrip(".")

    def parse(text: str) -> float:
        # An untouched field keeps the exact value, not its rounded display.
        return float(value) if text.strip() == shown else parse_number(text)

    return Field(label, shown, parse)
