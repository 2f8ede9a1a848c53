"""The main screen: the picture, and beside it the numbers and the node table; below, when
asked for, the plots, and while one is written, a recording's progress.

The side panel folds away by itself in a narrow terminal, so that the picture keeps the
room (as lazygit and btop fold their panels), and a key hides or shows it at any width.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.content import Content
from textual.events import Resize, ScreenResume, ScreenSuspend
from textual.widget import Widget
from textual.widgets import Static

from biceps.engine.arm import Arm
from biceps.engine.hold import Effort
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui.encoder import PictureEncoder
from biceps.tui.pacing import Pacer
from biceps.tui.fields import Check, Field
from biceps.tui.pixels import ImageEncoder
from biceps.tui.screens.prompt import Prompt
from biceps.tui.screens.sized import LatestSize
from biceps.tui.widgets.footer import FittedFooter
from biceps.tui.widgets.forces import Forces
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.plots import Plots
from biceps.tui.widgets.recorder import Recorder
from biceps.tui.widgets.stats import Stats
from biceps.tui.widgets.viewport import Viewport

# Below this the side panel leaves the picture a sliver and the table a few rows.
SMALLEST_USEFUL = (60, 16)

NARROW = 100
"""Columns below which the side panel is hidden unless asked for: its 32 columns would
take a third of the picture's width or more."""

SHORT = 38
"""The side panel's rows below which, with the forces shown, the numbers are brief (a
muscle's name, length, flexion and volume): the forces of six muscles take 10 rows and all
the numbers 20, which at 80x24 (23 rows) left the node table none, and at 150x45 with the
plots (26) too; brief, it keeps 7 and 10."""


class SidePanel(Vertical):
    """The side panel, which tells its screen when its height changes (a resize, the plots
    shown or hidden), for the numbers to be brief or whole (`SHORT`)."""

    def on_resize(self) -> None:
        self.screen.show_numbers_again()


FOOTER_KEPT_LONGEST = (
    "help", "quit", "edit_node", "insert_node", "delete_node", "subdivide", "turn_in_view",
    "turn", "change_length", "save", "export", "toggle_plots", "record",
)
"""The footer's keys, the first dropped last where they do not all fit (tui/widgets/footer.py):
help and quitting always, the node table's while it has the focus."""


class MainScreen(LatestSize[None]):
    AUTO_FOCUS = "#viewport"
    BINDINGS = [Binding("h", "toggle_panel", "Hide or show the side panel", show=False)]

    def __init__(self, pacer: Pacer, encoder: PictureEncoder | None = None,
                 renderer: Callable[[], SceneRenderer] | None = None) -> None:
        """``encoder``: how the picture reaches the terminal (default: half-blocks);
        ``renderer`` makes the render thread's renderer (see ``tui/rendering.py``)."""
        super().__init__()
        self._pacer = pacer
        self._encoder = encoder
        self._renderer = renderer
        self._arm: tuple[Arm, int] | None = None  # the arm and the muscle shown
        # Real pixels are painted over the cells: notifications keep to the side panel.
        self.set_class(isinstance(encoder, ImageEncoder), "-pixels")
        self._panel_wanted: bool | None = None  # None: as the width has it
        self._focused_before: Widget | None = None
        self._numbers_due = False  # the numbers of a newer arm are to be shown
        self._brief = False  # the numbers shown briefly (see SHORT)

    async def _ask_values(self, title: str, fields: Sequence[Field],
                          check: Check) -> tuple[Any, ...] | None:
        return await self.app.push_screen_wait(Prompt(title, fields, check=check))

    def compose(self) -> ComposeResult:
        with Horizontal(id="workspace"):
            yield Viewport(self._pacer, id="viewport", encoder=self._encoder,
                           renderer=self._renderer)
            with SidePanel(id="side"):
                # The forces first: shown only once asked for, and then the numbers
                # brief in a short panel (SHORT).
                yield Forces(id="forces")
                yield Stats(id="stats")
                yield NodeTable(self._ask_values, id="nodes")
        yield Plots(id="plots")
        yield Recorder(id="recorder")
        width, height = SMALLEST_USEFUL
        yield Static(
            f"This terminal is too small for biceps.\n"
            f"Please make it at least {width} columns by {height} rows.",
            id="too-small",
        )
        yield FittedFooter(FOOTER_KEPT_LONGEST)

    def on_mount(self) -> None:
        self.watch(self.app, "scene", self._show_scene)
        self.watch(self.app, "unsaved", self._show_file)
        self.watch(self.app, "sub_title", self._show_file)
        self.watch(self.app, "effort", self._show_effort)

    def on_screen_suspend(self, event: ScreenSuspend) -> None:
        self.query_one(Viewport).hide_image()

    def on_screen_resume(self, event: ScreenResume) -> None:
        self.query_one(Viewport).show_image()

    def on_resize(self, event: Resize) -> None:
        width, height = event.size
        too_small = width < SMALLEST_USEFUL[0] or height < SMALLEST_USEFUL[1]
        if too_small and not self.too_small:
            # Hidden, the focused widget loses the focus: give it back when it shows again.
            self._focused_before = self.focused
            # Notes about what was on screen would cover the message that says to grow it.
            self.app.clear_notifications()
        elif self.too_small and not too_small:
            self.call_after_refresh(self._refocus)
        self.set_class(too_small, "-too-small")
        self._place_panel()

    @property
    def too_small(self) -> bool:
        """Whether the terminal is too small to show the picture: then no key should
        change what cannot be seen."""
        return self.has_class("-too-small")

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        return not self.too_small

    def _refocus(self) -> None:
        widget = self._focused_before
        if widget not in self.focus_chain:  # the side panel, say, has been hidden since
            widget = self.query_one(Viewport)
        widget.focus()

    @property
    def panel_shown(self) -> bool:
        return not self.has_class("-panel-hidden")

    def action_toggle_panel(self) -> None:
        self._panel_wanted = not self.panel_shown
        self._place_panel()

    def _place_panel(self) -> None:
        wanted = self._panel_wanted
        # With real pixels the notifications keep to the panel's room (an image painted
        # over the picture would hide them), so it does not fold away by itself.
        shown = self.size.width >= NARROW or self.has_class("-pixels") if wanted is None \
            else wanted
        if not shown and self.focused is not None and self.query_one("#side") in (
            self.focused.ancestors
        ):
            self.query_one(Viewport).focus()  # the keys keep working on what is seen
        self.set_class(not shown, "-panel-hidden")

    def _show_scene(self, scene: Scene) -> None:
        self.query_one(Viewport).show(scene)
        # Turning, moving and lighting leave the numbers be. A burst of edits (a held key,
        # keys queued while the app was busy) shows its numbers once, after the burst: the
        # screen refreshes only once the keys waiting have been handled.
        if (scene.arm, scene.selected) != self._arm and not self._numbers_due:
            self._numbers_due = True
            self.app.call_later(self._show_numbers)

    def show_numbers_again(self) -> None:
        """The numbers' panel again, for the arm it shows, if it is to be brief now and was
        not, or the other way (`SHORT`)."""
        if self._arm is not None and self._brief_wanted() != self._brief:
            self._brief = not self._brief
            self.query_one(Stats).show(*self._arm, self._brief)

    def _brief_wanted(self) -> bool:
        return self.app.effort is not None and self.query_one(SidePanel).size.height < SHORT

    def _show_numbers(self) -> None:
        self._numbers_due = False
        arm, selected = self.app.scene.arm, self.app.scene.selected
        if (arm, selected) != self._arm:
            self._arm = (arm, selected)
            self._brief = self._brief_wanted()
            self.query_one(Stats).show(arm, selected, self._brief)
            self.query_one(NodeTable).show(arm.muscles[selected])
            self.query_one(Plots).show(arm)

    def _show_effort(self, effort: Effort | None) -> None:
        scene = self.app.scene
        self.query_one(Forces).show(effort, scene.activation, scene.mass)
        self.show_numbers_again()
        parameters = self.app.config.force_parameters() if effort is not None else ()
        self.query_one(Plots).show_effort(scene.arm, parameters, effort, scene.mass)

    def _show_file(self) -> None:
        # Content, not a str: a str is read as markup, and a file may be named [b]x.toml,
        # or [@click=app.quit]q.toml.
        self.query_one(Stats).border_title = Content(
            self.app.sub_title + (" ● unsaved" if self.app.unsaved else "")
        )

