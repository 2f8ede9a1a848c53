"""The biceps app: one scene, the keys that change it, and the files it comes from and goes to.

The app holds the whole state as one immutable :class:`~engine.scene.Scene`; every key,
drag and edit replaces it with a new one, and the main screen watches it. A change the
model refuses leaves the scene as it was and says why in a notification.
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from concurrent.futures import Executor
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from time import monotonic
from typing import Awaitable, Callable, get_args

import textual.constants
from textual import events, on, work
from textual.app import App
from textual.binding import Binding
from textual.command import CommandPalette
from textual.driver import Driver
from textual.message import Message
from textual.notifications import SeverityLevel
from textual.reactive import var
from textual.screen import Screen
from textual.suggester import Suggester
from textual.theme import ThemeProvider

from biceps.configs import FOLDER as BUNDLED_MODELS, bundled_names, file_or_bundled
from biceps.engine.arm import Arm
from biceps.engine.coldstart import Asides
from biceps.engine.config import Config, load_config, save_config
from biceps.engine.cost import check_model, check_picture
from biceps.engine.errors import BicepsError, FileChanged
from biceps.engine.export import check_writable, parse_size, write_png
from biceps.engine.files import same_file
from biceps.engine.hold import Effort, effort
from biceps.engine.names import printable
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer, supersampling
from biceps.engine.settings import ColourBy
from biceps.terminal import detect
from biceps.terminal.choose import TEXT, choose, colours, notice
from biceps.tui.ahead import compile_ahead, lean_once_ready
from biceps.tui.behind import Backlog, outdated
from biceps.tui.flow_control import no_flow_control
from biceps.tui.changes import (
    COARSE_STEP,
    EFFORT_STEP,
    FINE_STEP,
    LIGHT_STEP,
    MASS_STEP,
    MOVE_STEP,
    SLOW_NODES,
    TURN_STEP,
    effort_changed,
    fitted,
    has_unsaved_edits,
    length_changed,
    light_moved,
    moved,
    turned,
    with_antialiasing_switched,
    with_shading_switched,
    zoomed,
)
from biceps.tui.commands import KeyCommands
from biceps.tui.crash_report import text_of, traceback_of, write_crash_report
from biceps.tui.encoder import PictureEncoder
from biceps.tui.history import History, Step
from biceps.tui.pacing import LoopTimer, Pacer, cursor_question
from biceps.tui.rescue import Rescue, rescue_question
from biceps.tui.parse import parse_path
from biceps.tui.pixels import encoder_for
from biceps.tui.screens.choice import Answer, Choice
from biceps.tui.screens.help import HelpScreen
from biceps.tui.screens.main import MainScreen
from biceps.tui.screens.once import Palette
from biceps.tui.screens.prompt import Field, Prompt
from biceps.tui.screens.record import RecordPrompt, as_recording
from biceps.tui.suggest import ModelSuggester, PathSuggester
from biceps.tui.terminal_input import read_terminal_leniently
from biceps.tui import textual_private, visitor
from biceps.tui.textual_private import AppHooks, colour_system, write
from biceps.tui.web_packets import one_packet_at_a_time
from biceps.tui.widgets.node_table import NodeTable
from biceps.tui.widgets.plots import Plots
from biceps.tui.widgets.recorder import Recorder, Recording
from biceps.tui.widgets.viewport import Viewport

# What the terminal sends that tui/behind.py may leave out when the app falls behind.
FROM_THE_TERMINAL = (events.InputEvent, events.Paste, events.AppFocus, events.AppBlur)
# A drag across the picture's full height turns the model half round, or moves it by about
# the height of the arm in view at scale 1.
DRAG_TURN = 180.0  # degrees per picture height
DRAG_MOVE = 70.0  # cm per picture height

TURN = Binding.Group("Turn", compact=True)
FORCES = Binding.Group("Forces", compact=True)
ARROWS = [  # key, yaw, pitch, what it does
    ("left", -TURN_STEP, 0, "Turn left"),
    ("right", TURN_STEP, 0, "Turn right"),
    ("up", 0, -TURN_STEP, "Tip the top away"),
    ("down", 0, TURN_STEP, "Tip the top towards you"),
]


COLOURINGS = get_args(ColourBy)
"""What ``b`` cycles the muscles' colours through."""


class EffortFound(Message):
    """What the muscles do in ``scene``, worked out in a thread."""

    def __init__(self, scene: Scene, effort: Effort) -> None:
        super().__init__()
        self.scene = scene
        self.effort = effort


class QuitAsked(Message):
    """The person asked to quit; delivered behind every key they typed before (see
    :meth:`BicepsApp.action_quit_in_turn`)."""


class BicepsApp(AppHooks):
    CSS_PATH = "app.tcss"
    TITLE = "biceps"
    COMMANDS = App.COMMANDS | {KeyCommands}
    BINDINGS = [
        *[Binding(key, f"turn({yaw}, {pitch}, 0)", does, group=TURN)
          for key, yaw, pitch, does in ARROWS],
        # The same again, as priority bindings that act only while the picture has the
        # focus (see action_turn_in_view), shown in the footer as those are.
        *[Binding(key, f"turn_in_view({yaw}, {pitch})", does, group=TURN, priority=True)
          for key, yaw, pitch, does in ARROWS],
        Binding("left_square_bracket", f"turn(0, 0, {TURN_STEP})", "Roll anticlockwise",
                show=False),
        Binding("right_square_bracket", f"turn(0, 0, {-TURN_STEP})", "Roll clockwise",
                show=False),
        Binding("shift+left,a", f"move({-MOVE_STEP}, 0)", "Move left", show=False),
        Binding("shift+right,d", f"move({MOVE_STEP}, 0)", "Move right", show=False),
        Binding("shift+up,w", f"move(0, {MOVE_STEP})", "Move up", show=False),
        Binding("shift+down,s", f"move(0, {-MOVE_STEP})", "Move down", show=False),
        Binding("plus,equals_sign", "zoom(1)", "Scale up", show=False),
        Binding("minus", "zoom(-1)", "Scale down", show=False),
        Binding("f", "fit", "Fit the arm to the view", show=False),
        Binding("c", f"change_length({-FINE_STEP})", "Contract"),
        Binding("C", f"change_length({-COARSE_STEP})", f"Contract {COARSE_STEP:g} cm", show=False),
        Binding("x", f"change_length({FINE_STEP})", "Stretch"),
        Binding("X", f"change_length({COARSE_STEP})", f"Stretch {COARSE_STEP:g} cm", show=False),
        Binding("j", f"move_light({-LIGHT_STEP}, 0, 0)", "Light to the left", show=False),
        Binding("l", f"move_light({LIGHT_STEP}, 0, 0)", "Light to the right", show=False),
        Binding("i", f"move_light(0, {LIGHT_STEP}, 0)", "Light up", show=False),
        Binding("k", f"move_light(0, {-LIGHT_STEP}, 0)", "Light down", show=False),
        Binding("u", f"move_light(0, 0, {LIGHT_STEP})", "Light towards you", show=False),
        Binding("o", f"move_light(0, 0, {-LIGHT_STEP})", "Light away from you", show=False),
        Binding("t", "next_muscle(1)", "Next muscle", show=False),
        Binding("T", "next_muscle(-1)", "Previous muscle", show=False),
        Binding("y", "hide_muscle", "Hide or show the muscle", show=False),
        Binding("b", "switch_colours", "Colours: each muscle's own, its strain or its activation",
                show=False),
        # One footer entry for both, as the arrows': the footer is full at 80 columns.
        Binding("greater_than_sign", f"effort({EFFORT_STEP}, 0)", "Activate", group=FORCES),
        Binding("less_than_sign", f"effort({-EFFORT_STEP}, 0)", "Relax", show=False),
        Binding("right_curly_bracket", f"effort(0, {MASS_STEP})", "Weight", group=FORCES),
        Binding("left_curly_bracket", f"effort(0, {-MASS_STEP})", "Lighter weight", show=False),
        Binding("r", "reset_view", "Reset the view", show=False),
        Binding("g", "switch_shading", "Shading: Gouraud or Phong", show=False),
        Binding("m", "switch_antialiasing", "Anti-aliasing on or off", show=False),
        Binding("ctrl+z", "undo", "Undo", show=False),
        Binding("ctrl+y", "redo", "Redo", show=False),
        Binding("ctrl+r", "revert", "Revert to the saved file", show=False),
        # Shown in the footer in a word, and by their tooltips in the palette (commands.py).
        Binding("ctrl+s", "save", "Save"),
        Binding("e", "export", "Export", tooltip="Export a PNG"),
        Binding("p", "toggle_plots", "Plots", tooltip="Plots on or off"),
        Binding("v", "record", "Record", tooltip="Record the flex cycle"),
        Binding("ctrl+d", "save_as", "Save as", show=False),
        Binding("ctrl+o", "open", "Open", show=False),
        Binding("question_mark,f1", "help", "Help", tooltip="Help: every key"),
        Binding("q", "quit", "Quit"),
        # Quits from anywhere, a dialog too: a priority binding (see action_quit_in_turn).
        Binding("ctrl+q", "quit_in_turn", show=False, priority=True),
    ]

    scene: var[Scene] = var(None)
    unsaved: var[bool] = var(False)
    effort: var[Effort | None] = var(None)  # what the muscles do, once asked to work

    def __init__(self, config: Config, fps: float | None = None,
                 encoder: PictureEncoder | None = None, notice: str | None = None,
                 rescue: Rescue | None = None,
                 renderer: Callable[[], SceneRenderer] | None = None,
                 when_up: Callable[[], object] | None = None) -> None:
        """``fps``: the most frames a second the picture is redrawn at, up to Textual's
        limit (``TEXTUAL_FPS``, 60 unless set), the cap if None; ``encoder``: how the
        picture reaches the terminal (default: half-blocks); ``notice``: said once the app
        is up (what the terminal could show, see terminal/choose.py). ``rescue``: start on the
        model an app left when it ended on an error, and offer to save it. ``renderer``:
        makes the renderer of each thread that draws (the pictures, an export), each closed
        once done (None: a SceneRenderer of its own each). ``when_up``: called once the app
        is up (the command freezes the heap there, ``biceps/cli.py``)."""
        super().__init__()
        # Textual paints no more often than its limit, but the viewport writes most frames
        # itself (tui/widgets/viewport.py): the pacer keeps them to the limit too.
        limit = textual.constants.MAX_FPS
        self.pacer = Pacer(self._ask_cursor_position, LoopTimer,
                           limit if fps is None else min(fps, limit))
        self._encoder = encoder
        self._notice = notice
        self._renderer, self._when_up = renderer, when_up
        self._history = History()
        self._backlog = Backlog()
        self._backlog_report_due = False
        self.failure: str | None = None  # the error this app ended on, if it did
        self.failure_details = ""  # its traceback
        self._rescue = rescue
        self.config: Config | None = None
        self._last_recording: Recording | None = None
        if rescue is None:
            self._adopt(config, Scene.of(config))
            scene = self._saved
        else:
            self._adopt(rescue.config, rescue.saved)
            scene = replace(rescue.scene, marked=True)
        self.set_reactive(BicepsApp.scene, scene)
        self.set_reactive(BicepsApp.unsaved, has_unsaved_edits(scene, self._saved))
        self._export_size = "1920x1080"
        self._notified_until: dict[str, float] = {}
        self._saving = asyncio.Lock()
        self._asking = False  # a dialog is open, or about to open (see _ask)
        self._effort_for: tuple | None = None  # the arm and what was asked of its muscles
        self._effort_busy = False  # an answer is being worked out

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        # On the 'too small' screen nothing is seen to change, so nothing changes: only
        # help and quitting work there.
        screen = self.screen
        if isinstance(screen, MainScreen) and screen.too_small:
            return action in ("help", "quit")
        if action == "turn_in_view":
            return isinstance(self.focused, Viewport)
        return True

    def get_default_screen(self) -> Screen:
        return MainScreen(self.pacer, self._encoder, self._renderer)

    def get_driver_class(self) -> type[Driver]:
        # Textual's own driver, reading stray bytes as U+FFFD (tui/terminal_input.py),
        # sending only the colour codes that change (tui/sgr.py) once it can (tui/ahead.py),
        # and under biceps serve, writing one packet at a time (tui/web_packets.py).
        read_terminal_leniently()
        return lean_once_ready(one_packet_at_a_time(super().get_driver_class()))

    def ending_on(self, error: BaseException) -> None:
        # Textual ends the app on an error nothing caught: note it, so that run_app can
        # offer to save the model and exit with an error.
        self._note_failure(f"{type(error).__name__}: {error}", traceback_of(error))

    def panic(self, *renderables) -> None:
        # How Textual ends the app on an error in its input thread.
        self._note_failure("an error reading the terminal", text_of(renderables))
        super().panic(*renderables)

    def _note_failure(self, summary: str, details: str) -> None:
        """Keep the first error the app ends on, in a line and in full for the crash
        report, with the screens open (a fault may lie in what is open, and in what order)."""
        if self.failure is not None:
            return
        names = ", ".join(type(screen).__name__ for screen in self.screen_stack)
        self.failure = summary
        self.failure_details = (f"{details}\nscreens, bottom to top: {names or 'none'}; "
                                f"focused: {type(self.focused).__name__}\n")

    async def on_event(self, event: events.Event) -> None:
        if isinstance(event, FROM_THE_TERMINAL) and not self._answers(event):
            return
        if isinstance(event, events.Resize) and outdated(self, event.size):
            return
        if isinstance(event, events.MouseDown) and self._on_a_widget_gone(event):
            return
        await super().on_event(event)

    def _on_a_widget_gone(self, press: events.MouseDown) -> bool:
        """Whether ``press`` lands on a widget already removed, whose place the screen has
        not laid out again (a note cleared as the terminal shrank): Textual's text selection
        looked up that widget's parent, None, and ended the app with AttributeError."""
        widget, _ = self.screen.get_widget_and_offset_at(press.x, press.y)
        return widget is not None and not widget.is_attached

    def _answers(self, event: events.Event) -> bool:
        """Whether to answer this input from the terminal, or leave it out."""
        # Keys and the mouse still queued as the app closes: Textual closes the screens (and
        # their widgets, children first) while the app still handles its queue, and a key
        # then reached a widget whose children had gone (NoMatches) or no screen at all
        # (ScreenStackError).
        if not self.is_running or not self.screen_stack:
            return False
        if self.is_headless:  # keys from a script, which waits for each to be answered
            return True
        # A button let go is always answered: a drag left out of it would go on.
        focus = (isinstance(event, events.AppFocus)
                 if isinstance(event, (events.AppFocus, events.AppBlur)) else None)
        if isinstance(event, events.MouseUp) or self._backlog.answer(event.time, focus=focus):
            return True
        if not self._backlog_report_due:  # once the flood is over (tui/behind.py)
            self._backlog_report_due = True
            self.set_timer(self._backlog.patience, self._caught_up)
        return False

    def _caught_up(self) -> None:
        self._backlog_report_due = False
        focus, self._backlog.focus = self._backlog.focus, None
        if focus is not None and focus != self.app_focus:
            self.post_message(events.AppFocus() if focus else events.AppBlur())
        if report := self._backlog.report():
            self.notify(report, severity="warning", timeout=8, markup=False)

    def action_command_palette(self) -> None:
        # Textual's palettes, guarded against its faults (tui/screens/once.py). With no id
        # (Textual's own is "--command-palette"; is_open goes by the palette's class): a
        # palette closed is removed only once the app has handled the keys queued behind
        # it, and a ctrl+p among them would open one with the id of one still there,
        # DuplicateIds.
        if self.use_command_palette and not CommandPalette.is_open(self):
            self.push_screen(Palette())

    def search_themes(self) -> None:
        self.push_screen(Palette(providers=[ThemeProvider], placeholder="Search for themes…"))

    def on_ready(self) -> None:
        if not self.is_headless and not self.is_web:
            # Textual's driver stops the app on SIGTSTP, and leaves that in place after it
            # gives the terminal back: a ctrl+z typed as the app closed (or failed, before
            # its rescue) stopped it, with nothing to start it again. ctrl+z is undo here;
            # the signal is ignored, as it is before the app starts (biceps/cli.py).
            signal.signal(signal.SIGTSTP, signal.SIG_IGN)
        if self._when_up is not None:
            self._when_up()
        if self._notice:
            self.notify(self._notice, timeout=12, markup=False)
        if self._rescue is not None:
            self.ask(self._offer_rescue)

    def screen_written(self, screen: Screen, update: object) -> None:
        # Real pixels are painted over cells that Textual may write again without a new
        # frame (a dialog closing): the viewport is told what was written.
        if isinstance(screen, MainScreen):
            screen.query_one(Viewport).repainted(update)

    def _ask_cursor_position(self, column: int) -> bool:
        # Written straight to the driver, after the frame already queued there (as
        # App.bell does): the terminal answers once it has read the frame.
        return not self.is_headless and write(self, cursor_question(column))

    def on_cursor_position(self, event: events.CursorPosition) -> None:
        self.pacer.answered(event.x, event.y)

    def watch_scene(self, old: Scene, scene: Scene) -> None:
        # A turn, a move, the light leave the model as it was, saved or not: no comparing it
        # with the saved one at each step of a held key (which walks every muscle's nodes).
        if scene.arm is not old.arm:
            self.unsaved = has_unsaved_edits(scene, self._saved)
        self._follow_effort(scene)

    def _follow_effort(self, scene: Scene) -> None:
        """Work out, in a thread, what the muscles do in ``scene``'s pose when asked to work;
        forget it when they are not. One at a time: what is asked meanwhile (a held key's
        poses) is asked again, for the newest pose, when the answer comes."""
        asked = (scene.activation, scene.mass)
        if self._effort_for is not None and scene.arm is self._effort_for[0] \
                and asked == self._effort_for[1]:
            return
        self._effort_for = (scene.arm, asked)
        if self._effort_busy:
            return
        parameters = None
        if asked != (0.0, 0.0):
            try:
                parameters = self.config.force_parameters()
            except BicepsError as error:
                self._refuse(str(error))
        if parameters is None:
            self.effort = None
            if scene.activations:
                self.scene = scene.with_activations(())
            return
        self._effort_busy = True
        self._find_effort(scene, parameters)

    @work(thread=True, group="effort")
    def _find_effort(self, scene: Scene, parameters: tuple) -> None:
        self.post_message(EffortFound(scene, effort(scene.arm, parameters, scene.activation,
                                                    scene.mass)))

    @on(EffortFound)
    def _found_effort(self, message: EffortFound) -> None:
        scene, found = message.scene, message.effort
        self._effort_busy = False
        now = self.scene
        if now.arm is not scene.arm or (now.activation, now.mass) != (scene.activation,
                                                                      scene.mass):
            self._effort_for = None  # asked again since: for the newest pose
            self._follow_effort(now)
            return
        self.effort = found
        self.scene = now.with_activations(found.activations)
        if found.refusal is not None:
            self._refuse(found.refusal)

    def notify(
        self,
        message: str,
        *,
        title: str = "",
        severity: SeverityLevel = "information",
        timeout: float | None = None,
        markup: bool = True,
    ) -> None:
        # A key held at a limit repeats the same refusal many times a second: say it once
        # and not again until it has had time to be read.
        now = monotonic()
        if self._notified_until.get(message, 0.0) > now:
            return
        timeout = self.NOTIFICATION_TIMEOUT if timeout is None else timeout
        self._notified_until = {
            text: until for text, until in self._notified_until.items() if until > now
        }
        self._notified_until[message] = now + timeout
        if not markup:  # text from outside (a file name, an error): nothing in it may act
            message = "\n".join(printable(line) for line in message.split("\n"))
        super().notify(message, title=title, severity=severity, timeout=timeout, markup=markup)

    def _refuse(self, reason: str) -> None:
        self.notify(reason, severity="warning", markup=False)

    def _change(self, change: Callable[[Scene], Scene]) -> None:
        try:
            self.scene = change(self.scene)
        except BicepsError as error:
            self._refuse(str(error))

    def _edit(self, arm: Arm, what: str, *, run: bool = False) -> None:
        """Put ``arm`` in the scene as an edit that undo can take back; ``run`` for a length
        change, which joins the length changes just before it (see tui/history.py)."""
        before = self.scene.arm
        if arm == before:  # (a muscle compares by identity: the very same shape and length)
            return
        self._history.record(before, what, run=run, at=monotonic())
        self.scene = self.scene.with_arm(arm)

    def action_turn(self, yaw: float, pitch: float, roll: float) -> None:
        self._change(partial(turned, yaw=yaw, pitch=pitch, roll=roll))

    def action_turn_in_view(self, yaw: float, pitch: float) -> None:
        # A key that no priority binding takes goes from the app to the focused widget, up
        # through its parents and back to the app before the app's binding runs: Textual's
        # work for each of the dozens of keys a second a held arrow sends, a good part of
        # the UI thread's frame. While the picture has the focus nothing on
        # that way takes the arrows, so they are taken at once; anywhere else (the node
        # table, a dialog's input) check_action turns this binding off and they go their
        # way as before.
        self.action_turn(yaw, pitch, 0.0)

    def action_move(self, right: float, up: float) -> None:
        self._change(partial(moved, right=right, up=up))

    def action_zoom(self, steps: float) -> None:
        self._change(partial(zoomed, steps=steps))

    def action_fit(self) -> None:
        self._change(fitted)

    def action_change_length(self, change: float) -> None:
        try:
            arm, limit = length_changed(self.scene.arm, change)
        except BicepsError as error:
            self._refuse(str(error))
            return
        self._edit(arm, "the length change", run=True)
        if limit is not None:
            self._refuse(limit)

    def action_undo(self) -> None:
        self._go_through_history(self._history.undo, "undo", "Undone")

    def action_redo(self) -> None:
        self._go_through_history(self._history.redo, "redo", "Redone")

    def _go_through_history(self, move: Callable[[Arm], Step | None], verb: str,
                            done: str) -> None:
        step = move(self.scene.arm)
        if step is None:
            self.notify(f"Nothing to {verb}", markup=False)
            return
        self.scene = self.scene.with_arm(step.arm)
        self.notify(f"{done}: {step.what}", markup=False)

    def action_revert(self) -> None:
        name = printable(self.config.path.name)
        if not self.unsaved:
            self.notify(f"Nothing to revert: the model is as {name} has it", markup=False)
            return
        self._edit(self._saved.arm, f"the revert to {name}")
        self.notify(f"Back to {name} as saved; ctrl+z brings the edits back", markup=False)

    def action_move_light(self, x: float, y: float, z: float) -> None:
        self._change(partial(light_moved, x=x, y=y, z=z))

    def action_reset_view(self) -> None:
        self._change(lambda scene: replace(scene, view=self.config.view))

    def action_switch_shading(self) -> None:
        self._change(with_shading_switched)

    def action_next_muscle(self, step: int) -> None:
        self.action_select_muscle(self.scene.selected + step)

    def action_select_muscle(self, index: int) -> None:
        self._change(lambda scene: scene.with_selected(index))
        names = self.scene.arm.names
        if len(names) > 1:
            self.notify(f"Editing {names[self.scene.selected]} "
                        f"({self.scene.selected + 1} of {len(names)})", markup=False)
        else:
            self.notify(f"{names[0]} is the only muscle", markup=False)

    def action_hide_muscle(self) -> None:
        scene = self.scene
        name = scene.arm.names[scene.selected]
        hide = name not in scene.hidden
        self._change(lambda scene: scene.with_hidden(name, hide))
        self.notify(f"{name} hidden; y shows it again" if hide else f"{name} shown",
                    markup=False)

    def action_switch_colours(self) -> None:
        following = COLOURINGS[(COLOURINGS.index(self.scene.render.colour_by) + 1)
                               % len(COLOURINGS)]
        self._change(lambda scene: scene.with_render(colour_by=following))
        self.notify({
            "muscle": "Colours: each muscle's own",
            "strain": "Colours: strain, warm where a muscle is shorter than at rest, cool "
                      "where longer",
            "activation": "Colours: activation, pale at rest, amber to red as a muscle works "
                          "(> and } ask them to)",
        }[following], markup=False)

    def action_effort(self, activation: float, mass: float) -> None:
        """Ask every muscle for ``activation`` more (0 to 1), or the muscles to hold ``mass``
        kg more in the hand (0 to let go), which then takes over from the activation."""
        try:
            self.config.force_parameters()
        except BicepsError as error:
            self._refuse(str(error))
            return
        before = self.scene
        self._change(partial(effort_changed, activation=activation, mass=mass))
        scene = self.scene
        if scene is before:
            return
        if mass:
            self.notify(f"Holding {scene.mass:g} kg in the hand" if scene.mass
                        else "The hand let go", markup=False)
        elif scene.mass:
            self.notify(f"The muscles hold {scene.mass:g} kg, whatever the activation: "
                        "{ lets go of it", markup=False)

    def action_switch_antialiasing(self) -> None:
        self._change(with_antialiasing_switched)

    @on(Viewport.Dragged)
    def _drag(self, message: Viewport.Dragged) -> None:
        if message.pan:
            distance = DRAG_MOVE / self.scene.view.scale
            self.action_move(message.across * distance, -message.down * distance)
        else:
            self.action_turn(message.across * DRAG_TURN, message.down * DRAG_TURN, 0.0)

    @on(Viewport.Zoomed)
    def _zoom(self, message: Viewport.Zoomed) -> None:
        self.action_zoom(message.steps)

    @on(NodeTable.NodePicked)
    def _ring_node(self, message: NodeTable.NodePicked) -> None:
        if message.node != self.scene.picked_node:
            self.scene = self.scene.with_picked_node(message.node)

    @on(NodeTable.ChangeRequested)
    def _edit_muscle(self, message: NodeTable.ChangeRequested) -> None:
        arm, index = self.scene.arm, self.scene.selected
        try:
            edited = arm.with_muscle_at(index, message.change(arm.muscles[index]))
            check_model([muscle.node_count for muscle in edited.muscles],
                        self.scene.render.segments)
        except BicepsError as error:
            self._refuse(str(error))
            return
        self._edit(edited, message.what if index == 0 else f"{message.what} of {arm.names[index]}")
        count = edited.muscles[index].node_count
        if count > SLOW_NODES >= arm.muscles[index].node_count:
            self.notify(
                f"{count:,} nodes: the picture will follow each change slowly, a mesh of "
                f"{count:,} rings; the numbers and the table stay quick. ctrl+z undoes it.",
                severity="warning", markup=False)
        elif message.undoable_note:
            self.notify(f"{message.what.capitalize()}; ctrl+z undoes it", markup=False)

    def action_help(self) -> None:
        if not self._asking and not isinstance(self.screen, HelpScreen):
            self.push_screen(HelpScreen())

    def ask(self, dialogs: Callable[[], Awaitable[object]]) -> None:
        """Run ``dialogs``, a coroutine function that asks in dialogs, unless others are
        already asking. The dialogs that ask for something (files, exports, recordings, a node's
        values) open through here.

        A dialog opens when its worker runs, which is after the keys that came with its
        key: a burst of e, ctrl+d and ctrl+o would open three dialogs on one another, and
        since each modal screen draws the screens beneath it, a stack of them deep enough
        exhausts Python's stack (RecursionError in Textual's compositor).
        """
        if self._asking:
            return
        self._asking = True

        async def asking() -> None:
            try:
                await dialogs()
            finally:
                self._asking = False

        self.run_worker(asking(), group="dialogs")

    def action_save(self) -> None:
        self.ask(self._save_or_ask)

    async def _save_or_ask(self) -> bool:
        """Save to the file the model came from; for the bundled model, which is part of
        the installation (and replaced by the next upgrade), ask where to save a copy."""
        if _bundled(self.config.path):
            return await self._save_as()
        return await self._save()

    async def _save(self) -> bool:
        """Save to the file the model came from; True if saved, else says why not."""
        try:
            return await self._write_config()
        except BicepsError as error:
            self.notify(str(error), title="Not saved", severity="error", markup=False)
            return False

    async def _write_config(self, path: Path | None = None) -> bool:
        """Save the scene to ``path`` (the file it came from if None); True if saved, False
        if the person chose not to replace changes made on disk; raises BicepsError.

        The work runs in a thread, so a save of a large muscle does not stop the app, and
        one save at a time, each from the file the last one left. A file changed on disk
        since it was read is replaced only if the person says so.
        """
        async with self._saving:
            scene, config = self.scene, self.config
            save = partial(save_config, config, scene.arm, scene.view, scene.light, scene.render,
                           path)
            try:
                saved = await asyncio.to_thread(save)
            except FileChanged:
                if not await self._confirm_overwrite(config.path):
                    return False
                saved = await asyncio.to_thread(partial(save, overwrite=True))
            self._adopt(saved, scene)
            self.unsaved = has_unsaved_edits(self.scene, scene)  # edits made meanwhile
            self.notify(f"Saved {self._hand_over(saved.path)}", markup=False)
            return True

    def _adopt(self, config: Config, saved: Scene) -> None:
        """Make ``config`` the file the app edits, ``saved`` the scene it holds; the names
        export and record suggest follow a new file's."""
        if self.config is None or config.path != self.config.path:
            stem = config.path.stem
            self._export_path = f"{stem}.png"
            if self._last_recording is not None:
                suffix = self._last_recording.path.suffix
                self._last_recording = replace(self._last_recording,
                                               path=Path(f"{stem}-flex{suffix}"))
        self.config = config
        self._saved = replace(saved, marked=True)  # the app's pictures mark the pick
        self.sub_title = printable(config.path.name)

    def _config_file_field(self, path: Path, suggester: Suggester | None = None) -> Field:
        """The dialogs' field for a configuration file, ``path`` to start with."""
        return Field("File", printable(path), parse_path,
                     suggester or PathSuggester((".toml",)))

    def action_save_as(self) -> None:
        self.ask(self._save_as)

    async def _save_as(self) -> bool:
        """Ask for a file and save the model there; True if saved."""
        path, title, note = self.config.path, "Save as", ""
        if _bundled(path):
            # A copy of one's own, where one works (under biceps serve, a name in one's folder)
            path = Path(path.name) if visitor.folder() else Path.cwd() / path.name
            title = "Save a copy"
            note = (f"{printable(self.config.path.name)} is a bundled model, part of the "
                    "installation, which an upgrade replaces: save your copy where you work.")

        async def save(path: Path) -> bool:
            check_writable(path, ".toml")
            if (os.path.exists(path) and not same_file(path, self.config.path)
                    and not await self._confirm_replace(path)):
                return False
            return await self._write_config(path)

        answer = await self.push_screen_wait(
            Prompt(title, [self._config_file_field(path)], accept="Save", check=save,
                   note=note))
        return answer is not None

    def action_open(self) -> None:
        self.ask(self._open)

    async def _open(self) -> None:
        # The file open now, to change: a bundled model's own path, for there is nothing
        # else to open where one works; a bundled model may be named (toy, configs/toy.toml).
        opened: list[Config] = []

        async def read(path: Path) -> None:
            opened.append(await asyncio.to_thread(load_config, file_or_bundled(path)))

        shown = Path(self.config.path.name) if visitor.folder() else self.config.path
        field = self._config_file_field(shown, ModelSuggester())
        answer = await self.push_screen_wait(
            Prompt("Open a configuration", [field], accept="Open", check=read,
                   note=_open_note()))
        if answer is None:
            return
        (config,) = opened
        if self.unsaved and not await self._unsaved_edits_settled("open"):
            return
        self._adopt(config, Scene.of(config))
        self._history.clear()
        self.scene = self._saved

    def action_export(self) -> None:
        self.ask(self._export)

    async def _export(self) -> None:
        async def check(path: Path, size: tuple[int, int]) -> bool:
            self._check_export(path, *size)
            return not os.path.exists(path) or await self._confirm_replace(path)

        fields = [
            Field("File", printable(self._export_path), parse_path, PathSuggester((".png",))),
            Field("Size in pixels", self._export_size, parse_size),
        ]
        answer = await self.push_screen_wait(
            Prompt("Export a PNG", fields, accept="Export", check=check))
        if answer is None:
            return
        path, (width, height) = answer
        self._export_path, self._export_size = str(path), f"{width}x{height}"
        self._write_picture(self.scene.unmarked(), path, width, height)

    def _check_export(self, path: Path, width: int, height: int) -> None:
        check_writable(path, ".png", read=self.config.path)
        check_picture(width, height, supersampling(self.scene.render, height))

    @work(thread=True, group="export")
    def _write_picture(self, scene: Scene, path: Path, width: int, height: int) -> None:
        try:
            with (self._renderer or SceneRenderer)() as renderer:
                write_png(path, renderer.render(scene, width, height))
        except BicepsError as error:
            reason = str(error)
        except MemoryError:
            reason = f"not enough memory for a {width}x{height} picture"
        except Exception as error:
            # Whatever breaks in an export, the app and the edits in it must survive.
            reason = f"{type(error).__name__}: {error}"
        else:
            shown = self.call_from_thread(self._hand_over, path)
            self.call_from_thread(self.notify, f"Exported {shown} ({width}x{height})",
                                  markup=False)
            return
        self.call_from_thread(self.notify, reason, title="Not exported", severity="error",
                              markup=False)

    def _hand_over(self, path: Path) -> str:
        """Under ``biceps serve``, send ``path``, just written in the visitor's folder, to the
        browser as a download; the name to show for it."""
        if not self.is_web:
            return printable(path.resolve())
        self.deliver_binary(path)
        return f"{printable(path.name)}, downloading"

    def action_toggle_plots(self) -> None:
        self.screen_stack[0].query_one(Plots).toggle()

    def action_record(self) -> None:
        self.ask(self._record)

    async def _record(self) -> None:
        recorder = self.screen_stack[0].query_one(Recorder)
        if recorder.busy is not None:
            self._refuse(f"Still recording {printable(recorder.busy.path)}; wait for it to finish")
            return
        default = Path(f"{self.config.path.stem}-flex.gif")
        answer = await self.push_screen_wait(
            RecordPrompt(self.scene, default, self._last_recording,
                         read=self.config.path, replace=self._confirm_replace))
        if answer is None:
            return
        recording = self._last_recording = as_recording(*answer)  # if asked again
        recorder.record(self.scene.unmarked(), recording)

    def action_quit(self) -> None:
        self._quit()

    def action_quit_in_turn(self) -> None:
        # A priority binding runs as soon as its key arrives, while keys typed before it
        # may still be on their way through the focused widget to their bindings ("c"
        # then ctrl+q at once). Send the request the same way, behind them, so that it
        # finds their edits made.
        (self.focused or self.screen).post_message(QuitAsked())

    @on(QuitAsked)
    def _quit_asked(self) -> None:
        self._quit()

    @work
    async def _quit(self) -> None:
        if isinstance(self.screen, Choice):
            return  # ctrl+q again while the question is up: it is still waiting for an answer
        if self.unsaved and not await self._unsaved_edits_settled("quit"):
            return
        self.exit()

    async def _offer_rescue(self) -> None:
        """Say what error ended the app before, and offer to save the model it left."""
        while True:
            answer = await self.push_screen_wait(rescue_question(self._rescue))
            if answer is None:
                return
            if answer == "quit" or await (self._save_or_ask() if answer == "save"
                                          else self._save_as()):
                self.exit()
                return

    async def _unsaved_edits_settled(self, doing: str) -> bool:
        """Ask what to do with unsaved edits before doing something that drops them.

        True when they are saved or may be dropped; False to stay as we are.
        """
        answers = [
            Answer("s", f"Save, then {doing}", "save", "primary"),
            # Not "d" for discard: d moves the model, and a move key held or typed a moment
            # too long after a slip onto q would answer the question it did not read.
            Answer("n", "Don't save", "discard", "error"),
        ]
        question = f"{printable(self.config.path.name)} has unsaved edits."
        answer = await self.push_screen_wait(Choice("Unsaved edits", question, answers))
        if answer == "save":
            return await self._save_or_ask()
        return answer == "discard"

    async def _confirm_replace(self, path: Path) -> bool:
        """Whether to replace ``path``; no (escape) goes back to the dialog that named it."""
        answers = [Answer("y", "Replace it", "replace", "error")]
        question = f"{printable(path.resolve())} already exists."
        return await self.push_screen_wait(Choice("Replace?", question, answers)) == "replace"

    async def _confirm_overwrite(self, path: Path) -> bool:
        answers = [Answer("o", "Overwrite it", "overwrite", "error")]
        question = (f"{printable(path)} was changed on disk since it was opened here: saving "
                    "replaces those changes with this model.")
        choice = Choice("Changed on disk", question, answers)
        return await self.push_screen_wait(choice) == "overwrite"


def _open_note() -> str:
    """What the open dialog may open: under ``biceps serve``, the bundled models and the
    visitor's own files (uploaded or saved), and nothing else."""
    bundled = ", ".join(bundled_names())
    if visitor.folder() is None:
        return f"A file, or a bundled model by its name: {bundled}."
    own = ", ".join(printable(name) for name in visitor.models()) or "none yet"
    return (f"A bundled model by its name: {bundled}; or one of your files: {own}. Upload "
            "your own with the bar above.")


def _bundled(path: Path) -> bool:
    """Whether ``path`` is one of the models installed with biceps."""
    return path.resolve().parent == BUNDLED_MODELS.resolve()


@dataclass(frozen=True)
class AppProcess:
    """What the command sets up for an app in a process of its own (``biceps/cli.py``),
    which the app would not do to a caller's (a test's): by default nothing."""

    asides: Asides | None = None
    """The children the command started compiling the first frame's kernels; given, the
    app gives the rest of them to more (``tui/ahead.py``), and its renderers wait for
    them all before their first frame."""
    pool: Executor | None = None
    """The threads the app's renderers draw on, shared; each its own if None."""
    when_up: Callable[[], object] | None = None
    """Called once the app is up."""

    def renderer(self) -> SceneRenderer:
        """A renderer on the shared pool, once the children are done."""
        return SceneRenderer(self.pool, None if self.asides is None else self.asides.wait)


def run_app(config: Config, colors: str = "auto", fps: float | None = None,
            graphics: str | None = None, pixel_scale: float = 1.0,
            process: AppProcess = AppProcess()) -> int:
    """Run the app on ``config``; ``colors`` is ``auto`` (the config's, or what the terminal
    answers), ``truecolor`` or ``256``; ``fps`` caps the frame rate. ``graphics``: the
    command line's choice of how the picture reaches the terminal (default: the config's),
    real pixels ``pixel_scale`` of the terminal's each way. ``process``: what the command
    set up for a process of its own (none by default).

    Returns the exit status: 0, or 1 if the app ended on an error, after offering to save
    the model it had (:func:`rescued`)."""
    with no_flow_control():
        return _run(config, colors, fps, graphics, pixel_scale, process)


def _run(config: Config, colors: str, fps: float | None, graphics: str | None,
         pixel_scale: float, process: AppProcess) -> int:
    # Asked before Textual takes the terminal (its input thread would take the answers); not
    # at all when the command line says half-blocks and the colours, so nothing is written
    # but the app.
    asked = graphics or config.render.graphics
    colours_asked = config.render.colors if colors == "auto" else colors
    answers = None if graphics == "halfblocks" and colors != "auto" else detect.ask()
    place = detect.Place.here()
    choice = choose(asked, answers, place)
    if choice.graphics not in TEXT and not textual_private.ENABLED:
        choice = replace(choice, graphics="halfblocks", reason="real pixels are written to "
                         f"the terminal through Textual's internals, and the app is on "
                         f"{textual_private.describe()}")
    system = colours(colours_asked, answers, place).system
    encoder = encoder_for(choice, pixel_scale)
    if process.asides is not None:
        compile_ahead(process.asides, config, encoder,
                      palette=system == "256" and choice.graphics in TEXT)
    with colour_system(system):  # Textual's apps take it as they are made
        app = BicepsApp(config, fps=fps, encoder=encoder, notice=notice(asked, choice),
                        renderer=process.renderer, when_up=process.when_up)
        app.run()
        if app.failure is None and app.return_code == 1:  # the public path says no more
            app.failure = "an error in the app"
        if app.failure is None:
            return 0
        # Written first: the rescue runs in the same terminal, and may fail in turn. On the
        # public path the app is not told the error, and Textual's traceback above is all.
        report = None if not app.failure_details else write_crash_report(
            app.failure_details, config.path, graphics=choice.graphics, colours=system)
        rescue = rescued(app, fps)
        if rescue is not None:
            rescue.run()
    details = ("the details are above" if report is None
               else f"the details are in {printable(report)}")
    print(f"biceps: stopped on an error it did not expect ({printable(app.failure)}); "
          f"{details}. Please report them.", file=sys.stderr)
    return 1


def rescued(app: BicepsApp, fps: float | None = None) -> BicepsApp | None:
    """An app on the model ``app`` ended with, offering to save it; None if nothing is
    unsaved. Whatever broke in ``app`` (its screens, its message queues), this one is new,
    and draws with half-blocks, which any terminal shows."""
    if not has_unsaved_edits(app.scene, app._saved):
        return None
    return BicepsApp(app.config, fps=fps,
                     rescue=Rescue(app.config, app.scene, app._saved, app.failure or "?"),
                     renderer=app._renderer, when_up=app._when_up)
