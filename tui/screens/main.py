"""The main screen: the picture, and beside it the numbers and the node table."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.containers import Horizontal, Vertical
from textual.events import Resize
from textual.screen import Screen
from textual.widgets import Footer, Static

from engine.scene import Scene
from tui.widgets.node_table import NodeTable
from tui.widgets.stats import Stats
from tui.widgets.viewport import Viewport

# Below this the side panel leaves the picture a sliver and the table a few rows.
SMALLEST_USEFUL = (60, 16)


class MainScreen(Screen[None]):
    AUTO_FOCUS = "#viewport"

    def compose(self) -> ComposeResult:
        with Horizontal(id="workspace"):
            yield Viewport(id="viewport")
            with Vertical(id="side"):
                yield Stats(id="stats")
                yield NodeTable(id="nodes")
        width, height = SMALLEST_USEFUL
        yield Static(
            f"This terminal is too small for biceps.\n"
            f"Please make it at least {width} columns by {height} rows.",
            id="too-small",
        )
        yield Footer()

    def on_mount(self) -> None:
        self.watch(self.app, "scene", self._show_scene)
        self.watch(self.app, "unsaved", self._show_file)
        self.watch(self.app, "sub_title", self._show_file)

    def on_resize(self, event: Resize) -> None:
        width, height = event.size
        self.set_class(width < SMALLEST_USEFUL[0] or height < SMALLEST_USEFUL[1], "-too-small")

    def _show_scene(self, scene: Scene) -> None:
        viewport = self.query_one(Viewport)
        viewport.show(scene)
        viewport.border_title, viewport.border_subtitle = _view_captions(scene)
        self.query_one(Stats).show(scene.arm)
        self.query_one(NodeTable).show(scene.arm.muscle)

    def _show_file(self) -> None:
        self.query_one(Stats).border_title = self.app.sub_title + (
            " ● unsaved" if self.app.unsaved else ""
        )


def _view_captions(scene: Scene) -> tuple[str, str]:
    """How the model is turned and scaled; how it is shaded and lit."""
    view, render = scene.view, scene.render
    x, y, z = scene.light.position
    antialiasing = f"AA {render.ssaa}x{render.ssaa}" if render.ssaa > 1 else "AA off"
    return (
        f"yaw {_degrees(view.yaw)} pitch {_degrees(view.pitch)} roll {_degrees(view.roll)}"
        f" ×{view.scale:.2f}",
        f"{render.shading} · {antialiasing} · light {x:g}, {y:g}, {z:g}",
    )


def _degrees(angle: float) -> str:
    return f"{round(angle, 1):g}°"
