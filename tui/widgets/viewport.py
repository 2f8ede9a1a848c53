"""The picture: the scene rendered off the UI thread and put on the terminal by a
:class:`~tui.encoder.PictureEncoder` (half-block pixels unless told otherwise).

A widget of ``w x h`` cells shows a frame of ``w x h`` times the encoder's pixels per cell
(half-blocks: ``w x 2h``, as cells are about twice as tall as wide, so the pixels are about
square). The frames are drawn, encoded into lines (and an image, for an encoder that sends
one) and paced apart from Textual (``tui/rendering.py``), on a worker thread of the
widget's; a new frame refreshes only the lines that changed (none, if the picture is the
same). The captions on the border say how the picture on screen was made, so they change
with it.

Until the first frame comes on a first run (an empty numba cache, ``tui/ahead.py``), the
picture's place says that the renderer is being prepared, with the parts done and the
seconds so far; the keys work meanwhile.

The viewport writes a frame's new lines to the terminal itself, framed in its border, as
Textual would write them, whenever nothing else is drawn over it (:meth:`Viewport._wrote`);
otherwise (a notification over its corner, say) Textual's compositor does, as it does the
rest of the screen. Either way Textual's own repaints take the same lines from
:meth:`Viewport.render_lines`.

An encoder of real pixels (``tui/pixels.py``) paints its image over the picture's cells, so
the image is written only while the viewport's screen is the one shown (a dialog or the
help screen would be painted over), taken off when another screen comes up or the size
changes, and written again when Textual has repainted cells under it
(:meth:`Viewport.repainted`). Under another screen the picture's cells show the frame in
half-blocks, so that a dialog opens over the arm rather than over a blank.
"""

from __future__ import annotations

from time import monotonic
from typing import Callable, Sequence

import numpy as np
from rich.color import Color
from rich.console import Console
from rich.segment import Segment
from rich.style import Style
from textual import events, work
from textual.filter import ANSIToTruecolor, LineFilter
from textual.geometry import Region, Size
from textual.message import Message
from textual.strip import Strip
from textual.timer import Timer
from textual.widget import Widget

from biceps.engine.config import rgb
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer, supersampling
from biceps.terminal.palette import Palette256, background_colour
from biceps.terminal.palette import colour as palette_colour
from biceps.tui.ahead import Preparation, preparing
from biceps.tui.encoder import Picture, PictureEncoder
from biceps.tui.halfblocks import HalfBlocks, TextCells
from biceps.tui.pacing import Pacer
from biceps.tui.pixels import ImageEncoder
from biceps.tui import textual_private as private
from biceps.tui.prerendered import console_system
from biceps.tui.rendering import BUSY_AFTER, Failed, Frames, Rendered


MESSAGE = Style(color="#b8b8b8")  # the first run's message, on the picture's background
DRAW_TRIES = 8  # refreshes to wait for a frame to be written before pacing on regardless

BUSY_CAPTION = "drawing…"

PREPARING_EVERY = 0.5
"""Seconds between updates of a first run's message (``tui/ahead.py``), until the first
picture comes: the parts of the compilation done, and the seconds it has taken so far."""

class Viewport(Widget, can_focus=True):
    """Shows a :class:`Scene`; drags and wheel turns become messages for the app to act on."""

    ALLOW_SELECT = False  # a drag turns the model; it does not select text

    class FrameRendered(Message, bubble=False):
        def __init__(self, frame: Rendered[Picture]) -> None:
            super().__init__()
            self.frame = frame

    class RenderFailed(Message, bubble=False):
        def __init__(self, failure: Failed) -> None:
            super().__init__()
            self.failure = failure

    class Dragged(Message):
        """The mouse moved with a button held; ``pan`` to move the model, else to turn it.

        ``across`` and ``down`` are in picture heights, so a drag of the same length on
        screen means the same whichever way it goes (a cell is taller than it is wide).
        """

        def __init__(self, across: float, down: float, pan: bool) -> None:
            super().__init__()
            self.across = across
            self.down = down
            self.pan = pan

    class Zoomed(Message):
        """The wheel turned by ``steps`` notches (positive: scroll up, towards bigger)."""

        def __init__(self, steps: int) -> None:
            super().__init__()
            self.steps = steps

    def __init__(self, pacer: Pacer, *, id: str | None = None,
                 encoder: PictureEncoder | None = None,
                 renderer: Callable[[], SceneRenderer] | None = None) -> None:
        """``pacer`` says when the next frame may be made; ``encoder`` puts frames on the
        terminal (default: :class:`HalfBlocks`), from the render thread; ``renderer``
        makes that thread's renderer (see :class:`Frames`)."""
        super().__init__(id=id)
        encoder = HalfBlocks() if encoder is None else encoder
        palette: Palette256 | None = None
        if isinstance(encoder, TextCells):
            palette, encoder = self._for_this_terminal(encoder)
        self._palette, self._encoder = palette, encoder
        self._frames: Frames[Picture] = Frames(encoder, pacer, palette, renderer=renderer)
        self._scene: Scene | None = None
        self._strips: list[Strip] = []
        # For each line of the picture, framed in the border's sides: (line, sides, framed).
        self._framed_lines: dict[int, tuple[Strip, tuple[Strip, Strip], Strip]] = {}
        # The first picture line as Textual styles it, and the sides found in it.
        self._found_sides: tuple[Strip, tuple[Strip, Strip] | None] | None = None
        self._image = ""  # the image of the frame on screen, until it is written
        # The newest frame's image and its size in cells, to write again after a repaint.
        self._latest_image, self._latest_size = "", Size(0, 0)
        self._image_on_screen = False  # whether an image was written and not cleared since
        # The newest frame's lines, and the frame at two pixels a cell if the image shows it
        # (Picture.behind), for half-blocks while it is hidden.
        self._picture_lines: list[Strip] = self._strips
        self._behind: np.ndarray | None = None
        self._background = Style()
        self._captions = ("", "")  # on the border now
        self._frame_captions = ("", "")  # those of the frame on screen
        # The border row of the caption being set, and whether it is written with the
        # frame (see refresh).
        self._captioning: tuple[Region, bool] | None = None
        self._progress_timer: Timer | None = None
        self._preparing_timer: Timer | None = None

    def _for_this_terminal(self, encoder: TextCells) -> tuple[Palette256 | None, TextCells]:
        """``encoder`` writing this terminal's colours, and the palette its frames are to be
        mapped onto first, if any."""
        # Text in a 256-colour terminal: every frame mapped onto its palette as a whole
        # (terminal/palette.py), where Textual would map each colour on its own. The lines
        # carry their text for this terminal's colours.
        system = console_system(self.app.console)
        if system == "256":
            return Palette256(), encoder.recoloured(palette_colour, system)
        if system != "truecolor":
            return None, encoder.recoloured(color_system=system)
        return None, encoder

    @property
    def up_to_date(self) -> bool:
        """Whether the frame on screen is that of the latest scene and size."""
        return self._frames.up_to_date

    def show(self, scene: Scene) -> None:
        self._scene = scene
        background = rgb(scene.render.background)
        self._background = Style(bgcolor=Color.from_rgb(*background) if self._palette is None
                                 else background_colour(background))
        if isinstance(self._encoder, ImageEncoder):
            self._encoder.background = self._background
        self._request_frame()

    def on_mount(self) -> None:
        self._render_frames()
        if preparing() is not None:
            self._preparing_timer = self.set_interval(PREPARING_EVERY, self._prepared_yet)

    def _prepared_yet(self) -> None:
        if self._strips and self._preparing_timer is not None:
            self._preparing_timer.stop()
            self._preparing_timer = None
        self.refresh()  # the message's progress, or the picture that replaced it

    def on_unmount(self) -> None:
        self._frames.close()
        self._write(self._encoder.clear())

    def on_resize(self) -> None:
        self._framed_lines.clear()
        # An image of the old size would stay over whatever now takes its place.
        self._latest_image = ""
        self.hide_image()
        self._request_frame()

    def hide_image(self) -> None:
        """Take the image off the screen (another screen is coming up over it); its cells
        show the picture in half-blocks meanwhile, as that screen's backdrop."""
        if self._image_on_screen:
            self._image_on_screen = False
            self._write(self._encoder.clear())
        self._show_lines()

    def show_image(self) -> None:
        """The image's own lines again (the screen over it has gone): once Textual has
        written them, the image goes over them (:meth:`repainted`)."""
        self._show_lines()

    def _show_lines(self) -> None:
        """The newest frame's lines, or half-blocks of it where its image is hidden."""
        strips = self._picture_lines
        if self._behind is not None and not self._on_top and self._scene is not None:
            palette, encoder = self._for_this_terminal(HalfBlocks())
            behind = self._behind
            if palette is not None:
                behind = palette.mapped(behind, rgb(self._scene.render.background))
            strips = encoder.encode(behind).strips
        if strips is not self._strips:
            self._strips = strips
            self.refresh()

    def repainted(self, update: object) -> None:
        """Textual has written ``update`` to the terminal: if it wrote over the picture's
        cells, the image painted there is gone, and is written again."""
        if (not self._latest_image or self._image or not self._on_top
                or self._latest_size != self.size):
            return  # (a frame's image is written once its lines are; one of another size not)
        if private.update_touches(update, self.content_region):
            self._write_image(self._latest_image)

    def _request_frame(self) -> None:
        width, height = self.size
        if self._scene is None or not width or not height:
            return
        cell = self._encoder.cell
        self._frames.request(self._scene, width * cell.width, height * cell.height,
                             self._encoder.aspect)
        self._watch_progress()

    def _watch_progress(self) -> None:
        if self._progress_timer is None:
            self._progress_timer = self.set_timer(BUSY_AFTER, self._check_progress)

    def _check_progress(self) -> None:
        self._progress_timer = None
        if self.up_to_date:
            return
        if self._frames.busy():
            self._caption(self._frame_captions[0], BUSY_CAPTION)  # until the next frame
        self._watch_progress()

    @work(thread=True, exclusive=True, group="render")
    def _render_frames(self) -> None:
        self._frames.serve(self._deliver)

    def _deliver(self, result: Rendered[Picture] | Failed) -> None:
        # On the render thread: to the UI's, as a message.
        self.post_message(self.FrameRendered(result) if isinstance(result, Rendered)
                          else self.RenderFailed(result))

    def on_viewport_frame_rendered(self, message: FrameRendered) -> None:
        frame = message.frame
        picture = frame.picture
        self._frames.arrived(frame)
        self._picture_lines, self._behind = picture.strips, picture.behind
        if picture.behind is not None and not self._on_top:
            self._show_lines()  # made while another screen is over the picture
        else:
            self._strips = picture.strips
        self._image = picture.image
        self._latest_image = picture.image
        self._latest_size = Size(picture.strips[0].cell_length if picture.strips else 0,
                                 len(picture.strips))
        self._frame_captions = _view_captions(frame.scene, frame.height)
        if self._wrote(picture.changed):
            self._frames.written()
            return
        if picture.changed:  # (no regions would mean all of them)
            self.refresh(*(self._rows(y, rows) for y, rows in picture.changed))
        self._caption(*self._frame_captions)
        self.call_after_refresh(self._when_drawn, DRAW_TRIES)

    def _wrote(self, changed: Sequence[tuple[int, int]]) -> bool:
        """Write the ``changed`` lines of the picture, and any border row whose caption
        changed, straight to the terminal, each as Textual would write it, in one update;
        or, if anything else is drawn over the widget (or it is not lines of cells at its
        size, framed in the border's sides alone), leave them to Textual. Whether it
        wrote them."""
        # Textual would find what a frame changed by styling every widget on the screen,
        # when the encoder has said which lines changed and the viewport has framed them
        # already. Only on the private path (tui/textual_private.py).
        app = self.app
        if (self._image or private.batching(app) or app.is_inline or not private.can_write(app)
                or not self._on_top or self._latest_size != self.size
                or not private.uncovered(self)):
            return False
        sides = self._sides()
        if sides is None:
            return False
        console, (width, _), top = app.console, self.size, self.styles.gutter.top
        # A strip's text is its segments' texts one after the other: a line framed is the
        # sides' texts around the line's.
        left, right = (side.render(console) for side in sides)
        lines = [(top + y, f"{left}{self._line(y, width).render(console)}{right}")
                 for first, rows in changed for y in range(first, first + rows)]
        lines += [(top + y, self._styled(top + y, top + y + 1)[0].render(console))
                  for y in self._caption(*self._frame_captions, written=True)]
        if lines:
            x, y = self.region.offset
            # Where Textual leaves the cursor after each update.
            cursor = self.screen.outer_size.clamp_offset(app.cursor_position)
            self._write_synchronized("".join([
                *[f"\x1b[{y + row + 1};{x + 1}H{text}" for row, text in lines],
                f"\x1b[{cursor.y + 1};{cursor.x + 1}H",
            ]))
        return True

    def _when_drawn(self, tries: int) -> None:
        # Once Textual has written this frame, the pacer says when the next may be made.
        # "After refresh" callbacks can run before the refresh that draws the new lines
        # (the screen runs them without painting during a batch update, for one); asking
        # the terminal then would time the wrong write: while Textual has regions of the
        # widget to repaint, the frame is not out yet. A hidden viewport is never drawn,
        # hence the limit.
        pending = private.repaint_pending(self)
        if pending and tries > 1:
            self.call_after_refresh(self._when_drawn, tries - 1)
            return
        if self._image and not pending:
            # Over its lines once they are out (never over another screen), and before the
            # pacer's question, so that the answer waits for the image too.
            if self._on_top and self._latest_size == self.size:
                self._write_image(self._image)
        self._image = ""
        self._frames.written()

    @property
    def _on_top(self) -> bool:
        # Not Screen.is_current, which is also true of a screen shown behind a dialog.
        return self.app.screen is self.screen

    def _write_image(self, image: str) -> None:
        x, y = self.content_region.offset
        # (never half an image on screen)
        self._write_synchronized(f"\x1b7\x1b[{y + 1};{x + 1}H{image}\x1b8")
        self._image_on_screen = True

    def _write_synchronized(self, text: str) -> None:
        """Write ``text`` to be shown all at once, where the terminal can."""
        self._write(private.synchronized(self.app, text))

    def _write(self, text: str) -> None:
        # Straight to the terminal, after the lines already queued there.
        private.write(self.app, text)

    def on_viewport_render_failed(self, message: RenderFailed) -> None:
        self._frames.arrived(message.failure)
        self._caption(*self._frame_captions)
        self.notify(f"The picture cannot be drawn: {message.failure.reason}",
                    severity="error", markup=False)

    def _caption(self, title: str, subtitle: str, written: bool = False) -> list[int]:
        """Set the captions on the border; the rows that changed (``-1`` the top border,
        the picture's height the bottom one). Textual repaints them, unless they are to be
        ``written`` with the frame."""
        # Each caption is set only if it changed: setting one repaints its row, and a
        # turn changes the title alone.
        top, bottom = self.styles.gutter.top, self.styles.gutter.bottom
        changed = []
        for row, caption, shown, attribute in (
                (-top, title, self._captions[0], "border_title"),
                (self.size.height + bottom - 1, subtitle, self._captions[1], "border_subtitle")):
            if caption != shown:
                self._captioning = self._rows(row, 1), written
                try:
                    setattr(self, attribute, caption)
                finally:
                    self._captioning = None
                changed.append(row)
        self._captions = title, subtitle
        return changed

    def refresh(self, *regions: Region, **options) -> Viewport:
        if self._captioning is not None and not regions:
            # Setting a border title repaints the whole widget, picture and all, though
            # only its own row changes.
            row, written = self._captioning
            # Written with the frame: the row need only be styled again.
            if written and private.restyle(self, row.translate(self.content_offset)):
                return self
            regions = (row,)
        return super().refresh(*regions, **options)

    def _rows(self, y: int, rows: int) -> Region:
        """Whole rows of the widget, borders included, from row ``y`` of the picture."""
        # Textual writes a line from the widget's left edge even when only part of it is
        # dirty, and crops it to do so: asking for the whole line costs less.
        return Region(-self.styles.gutter.left, y, self.outer_size.width, rows)

    def get_line_filters(self) -> Sequence[LineFilter]:
        # The picture is all RGB: a filter turning ANSI colours into RGB would only copy
        # every segment of every line. The others (NO_COLOR's, say) still apply.
        return [line_filter for line_filter in super().get_line_filters()
                if not isinstance(line_filter, ANSIToTruecolor)]

    def render_lines(self, crop: Region) -> list[Strip]:
        # Textual styles every line of the picture again at each frame (Widget.render_lines,
        # through its StylesCache): border, padding, tint, opacity, filters, a new strip of
        # the same segments. Where that styling comes down to the border's sides, as it
        # does unless a filter or an effect applies, each line is framed in them here, once
        # per new line, and keeps its terminal text (tui/prerendered.py). The border's rows
        # and any other styling are Textual's own.
        top, (width, height) = self.styles.gutter.top, self.size
        first, last = max(crop.y, top), min(crop.bottom, top + height)
        sides = self._sides() if first < last and private.ENABLED else None
        if sides is None:
            return super().render_lines(crop)
        console = self.app.console
        lines = [
            *self._styled(crop.y, first),
            *[self._framed(y - top, width, sides, console) for y in range(first, last)],
            *self._styled(last, crop.bottom),
        ]
        if crop.column_span != (0, self.outer_size.width):
            lines = [line.crop(*crop.column_span) for line in lines]
        return lines

    def _styled(self, first: int, last: int) -> list[Strip]:
        """Rows ``first`` up to ``last`` of the widget, whole, as Textual styles them."""
        # The compositor asks for every row of the widget at each frame, and Textual
        # answers each call with work of its own (the background's colours, the captions'
        # styles) before it finds a row in its cache: a row it would take from its cache
        # is taken from there here, on the private path.
        if first >= last:
            return []
        cached = private.styled_lines(self, first, last)
        if cached is not None:
            return cached
        return super().render_lines(Region(0, first, self.outer_size.width, last - first))

    def _sides(self) -> tuple[Strip, Strip] | None:
        """What Textual draws left and right of a line of the picture, if the rest of its
        styling leaves the line as it is; None if not (then Textual styles every line)."""
        if self.get_line_filters():
            return None
        gutter, width = self.styles.gutter, self.outer_size.width
        (styled,) = self._styled(gutter.top, gutter.top + 1)
        # Found again only when Textual styles the line again (a new style, a new size).
        if self._found_sides is not None and self._found_sides[0] is styled:
            return self._found_sides[1]
        sides = None
        if styled.crop(gutter.left, width - gutter.right) == self.render_line(0):
            sides = styled.crop(0, gutter.left), styled.crop(width - gutter.right, width)
        self._found_sides = styled, sides
        return sides

    def _framed(self, y: int, width: int, sides: tuple[Strip, Strip],
                console: Console) -> Strip:
        """Line ``y`` of the picture, ``width`` cells, between ``sides``, made again only if
        either changed."""
        line = self._line(y, width)
        cached = self._framed_lines.get(y)
        if cached is not None and cached[0] is line and cached[1] == sides:
            return cached[2]
        framed = private.framed(line, *sides, console)
        self._framed_lines[y] = (line, sides, framed)
        return framed

    def render_line(self, y: int) -> Strip:
        return self._line(y, self.size.width)

    def _line(self, y: int, width: int) -> Strip:
        if not self._strips and (preparation := preparing()) is not None:
            return self._preparing_line(preparation, y, width)
        if y >= len(self._strips):
            return Strip.blank(width, self._background)
        strip = self._strips[y]
        if strip.cell_length == width:
            return strip
        # A frame of the old size, until the one for the new size arrives.
        return strip.crop_extend(0, width, self._background)

    def _preparing_line(self, preparation: Preparation, y: int, width: int) -> Strip:
        """Line ``y`` of a first run's message, in the middle of the picture's place."""
        done, parts = preparation.parts()
        compiling = " and ".join(preparation.compiling())
        lines = ["Preparing the renderer: first run only",
                 f"{done} of {parts} parts done · {monotonic() - preparation.started:.0f} s",
                 f"compiling {compiling}" if compiling else "drawing the first picture",
                 "the keys work meanwhile"]
        index = y - (self.size.height - len(lines)) // 2
        if not 0 <= index < len(lines):
            return Strip.blank(width, self._background)
        text = lines[index][:width].center(width)
        return Strip([Segment(text, self._background + MESSAGE)], width)

    def on_mouse_down(self, event: events.MouseDown) -> None:
        self.capture_mouse()

    def on_mouse_up(self, event: events.MouseUp) -> None:
        self.release_mouse()

    def on_mouse_move(self, event: events.MouseMove) -> None:
        rows = self.size.height
        if not event.button or not (event.delta_x or event.delta_y) or not rows:
            return
        # Shift-drag is often taken by the terminal for selecting text, so every modifier
        # and the other buttons pan too.
        pan = event.button != 1 or event.ctrl or event.shift or event.meta
        # A cell is cell.width pixels across; the picture is rows * cell.height pixels tall.
        cell = self._encoder.cell
        across = event.delta_x * cell.width * self._encoder.aspect / (rows * cell.height)
        self.post_message(self.Dragged(across, event.delta_y / rows, pan))

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        event.stop()
        self.post_message(self.Zoomed(1))

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        event.stop()
        self.post_message(self.Zoomed(-1))


def _view_captions(scene: Scene, height: int) -> tuple[str, str]:
    """How the model is turned and scaled; how a picture ``height`` pixels tall is shaded
    and lit."""
    view, render = scene.view, scene.render
    x, y, z = scene.light.position
    samples = supersampling(render, height)
    antialiasing = f"AA {samples}x{samples}" if samples > 1 else "AA off"
    if samples > render.ssaa:
        antialiasing += " (small)"  # see SMALL_PICTURE
    return (
        f"yaw {_degrees(view.yaw)} pitch {_degrees(view.pitch)} roll {_degrees(view.roll)}"
        f" ×{view.scale:.2f}",
        f"{render.shading} · {antialiasing} · light {x:g}, {y:g}, {z:g}",
    )


def _degrees(angle: float) -> str:
    return f"{round(angle, 1):g}°"
