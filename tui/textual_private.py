"""Every use of Textual's private parts, behind the few calls the app and the viewport make.

Textual draws the whole screen on its UI thread, and at 200x60 the picture alone would keep
it busy most of each frame. The app takes shorter ways through Textual's internals: the viewport
writes a frame's new lines to the terminal itself when nothing covers it, reads the lines
Textual has styled from its cache, and hands Textual lines that carry their terminal text
(:class:`PrerenderedStrip`); the pacer asks the terminal where its cursor is; the app learns
what Textual wrote (to paint a picture's image again over it) and which error ended it;
the terminal's input is read leniently, a paste kept whole and ended if its end never
comes; the palette is guarded against faults of its own, as it searches and as it closes;
and a cache of Textual's that kept the lines of widgets gone is made to let them go.
None of that is Textual's public API, so it is used only here, and only on a Textual known
to have it: 8.2.7 (the first with ``XTermParser._parse_extended_key``) up to 9, with every
attribute touched present.

Otherwise, or with ``BICEPS_TEXTUAL_PRIVATE=0``, the app takes the public path: Textual
draws every line of the picture (the Line API), frames are paced by the frame-rate cap
alone, pictures are half-blocks (real pixels need the terminal written to directly), the
colours are Textual's own choice, input and the palette are Textual's as they come, and
an error that ends the app is Textual's to print (no crash report).
It works, more slowly; ``biceps doctor`` says which path it is on (:func:`describe`).
"""

from __future__ import annotations

import os
from contextlib import contextmanager
from functools import lru_cache
from importlib.metadata import version as installed_version
from types import FrameType
from typing import Any, Callable, Iterator, Sequence

from rich.console import Console
from rich.segment import Segment
from textual.app import App
from textual.geometry import Region
from textual.screen import Screen
from textual.strip import Strip
from textual.widget import Widget

from biceps.tui.prerendered import console_system

try:  # imported once: they are looked at on every frame Textual writes
    from textual._compositor import ChopsUpdate, CompositorUpdate, LayoutUpdate
except ImportError:  # a Textual without them takes the public path (see _missing)
    ChopsUpdate = CompositorUpdate = LayoutUpdate = None  # type: ignore[assignment,misc]

SWITCH = "BICEPS_TEXTUAL_PRIVATE"
OLDEST, BEYOND = (8, 2, 7), (9,)  # the Textual versions whose internals are known


def _version(text: str) -> tuple[int, ...]:
    numbers = []
    for part in text.split("."):
        digits = "".join(c for c in part if c.isdigit()) if part[:1].isdigit() else ""
        if not digits:
            break
        numbers.append(int(digits))
    return tuple(numbers)


def _assigned(cls: type, name: str) -> bool:
    """Whether ``cls.__init__`` sets an attribute called ``name``."""
    code = getattr(cls.__init__, "__code__", None)
    return code is not None and name in code.co_names


def _missing() -> list[str]:
    """The private parts this module uses that the running Textual lacks."""
    from textual import constants
    from textual.command import CommandPalette

    missing = []
    try:
        from textual._compositor import Compositor, CompositorUpdate  # noqa: F401
        from textual._compositor import ChopsUpdate, LayoutUpdate  # noqa: F401
        from textual._styles_cache import StylesCache
        from textual._xterm_parser import XTermParser
    except ImportError as error:
        return [str(error)]
    needed: list[tuple[Any, str, Callable[[Any, str], bool]]] = [
        (App, "_display", hasattr), (App, "_handle_exception", hasattr),
        (App, "_driver", _assigned), (App, "_batch_count", _assigned),
        (App, "_sync_available", _assigned), (Screen, "_compositor", _assigned),
        (Compositor, "visible_widgets", hasattr), (Widget, "_repaint_regions", _assigned),
        (Widget, "_styles_cache", _assigned), (StylesCache, "_cache", _assigned),
        (StylesCache, "_width", _assigned), (StylesCache, "is_dirty", hasattr),
        (StylesCache, "set_dirty", hasattr), (XTermParser, "_parse_extended_key", hasattr),
        (CommandPalette, "_GATHER_COMMANDS_GROUP", hasattr),
        (constants, "COLOR_SYSTEM", hasattr),
    ]
    missing += [f"{getattr(owner, '__name__', owner)}.{name}" for owner, name, has in needed
                if not has(owner, name)]
    if not hasattr(getattr(CommandPalette, "_gather_commands", None), "__wrapped__"):
        missing.append("CommandPalette._gather_commands")
    if "_cell_length" not in getattr(Strip, "__slots__", ()) or not STRIP_SLOTS:
        missing.append("Strip.__slots__")
    return missing


def _path() -> tuple[bool, str]:
    """Whether the private path is taken, and why (or why not)."""
    textual = installed_version("textual")
    if os.environ.get(SWITCH, "1").strip() == "0":
        return False, f"the public path ({SWITCH}=0), Textual {textual}"
    if not OLDEST <= _version(textual) < BEYOND:
        return False, (f"the public path: Textual {textual}, whose internals are not known "
                       "(8.2.7 to 8.x are)")
    missing = _missing()
    if missing:
        return False, f"the public path: Textual {textual} lacks {', '.join(missing)}"
    return True, f"the private path (Textual {textual}'s internals, the fastest)"


STRIP_SLOTS = frozenset(getattr(Strip, "__slots__", ())) - {"_cell_length"}
"""The slots a :class:`PrerenderedStrip` fills only when one of Strip's methods wants them."""

ENABLED, _WHY = _path()


def describe() -> str:
    """Which path the app takes through Textual, and why, for ``biceps doctor``."""
    return _WHY


# The terminal, written to directly.


def write(app: App, text: str) -> bool:
    """Write ``text`` to the terminal after what Textual has queued (as ``App.bell`` does);
    False if it cannot be (the public path, no driver)."""
    driver = app._driver if ENABLED else None
    if driver is None:
        return False
    if text:
        driver.write(text)
    return True


def can_write(app: App) -> bool:
    """Whether :func:`write` reaches the terminal now."""
    return ENABLED and app._driver is not None


def synchronized(app: App, text: str) -> str:
    """``text``, to be shown all at once where the terminal can (synchronized output)."""
    if ENABLED and app._sync_available:
        return f"\x1b[?2026h{text}\x1b[?2026l"
    return text


def batching(app: App) -> bool:
    """Whether Textual holds its updates back (``App.batch_update``)."""
    return ENABLED and bool(app._batch_count)


# What Textual has drawn, and will.


def uncovered(widget: Widget) -> bool:
    """Whether all of ``widget`` is on screen with nothing over it (False on the public
    path, where Textual draws everything)."""
    if not ENABLED:
        return False
    region = widget.region
    if not widget.app.size.region.contains_region(region):
        return False  # the terminal shrank, and Textual has yet to lay the screen out
    # Front to back: the widgets after this one (its containers) are behind it.
    for other, (place, clip) in widget.screen._compositor.visible_widgets.items():
        if other is widget:
            return clip.contains_region(region)
        if place.intersection(clip).overlaps(region):
            return False
    return False  # not on screen at all


def repaint_pending(widget: Widget) -> bool:
    """Whether Textual has yet to write regions of ``widget`` it was asked to: it empties
    them in the very call that writes them out (Compositor.update_widgets, then
    App._display)."""
    return ENABLED and bool(widget._repaint_regions)


def styled_lines(widget: Widget, first: int, last: int) -> list[Strip] | None:
    """Rows ``first`` up to ``last`` of ``widget``, whole, as Textual last styled them, if it
    has them all and none has changed; else None."""
    if not ENABLED:
        return None
    cache = widget._styles_cache
    rows = range(first, last)
    if cache._width == widget.outer_size.width and all(
            y in cache._cache and not cache.is_dirty(y) for y in rows):
        return [cache._cache[y] for y in rows]
    return None


def restyle(widget: Widget, region: Region) -> bool:
    """Have Textual style ``region`` of ``widget`` again when next asked, without a
    repaint; False on the public path (then refresh it)."""
    if not ENABLED:
        return False
    widget._styles_cache.set_dirty(region)
    return True


def update_touches(update: object, area: Region) -> bool:
    """Whether ``update``, which Textual has written, wrote over any of ``area`` (the
    private path only: the public one is told of no update)."""
    if isinstance(update, LayoutUpdate):
        return update.region.overlaps(area)
    if isinstance(update, ChopsUpdate):
        return any(area.y <= y < area.bottom and x1 < area.right and x2 >= area.x
                   for y, x1, x2 in update.spans)
    return True


class AppHooks(App):
    """An app told what Textual wrote (:meth:`screen_written`) and what error ends it
    (:meth:`ending_on`), which Textual has no public hooks for; a closing palette's faults
    are let pass (:func:`a_closing_palette_s_fault`), and a palette clicked on a result it
    no longer has is closed (:func:`list_clicked_on_a_result_gone`)."""

    def screen_written(self, screen: Any, update: object) -> None:
        """Textual has written ``update`` of ``screen`` to the terminal (the private path)."""

    def ending_on(self, error: BaseException) -> None:
        """``error``, which nothing caught, ends the app (the private path; on the public
        one, :attr:`App.return_code` is 1 after)."""

    def _display(self, screen: Any, renderable: Any) -> None:
        super()._display(screen, renderable)
        if ENABLED and isinstance(renderable, CompositorUpdate):
            self.screen_written(screen, renderable)

    def _handle_exception(self, error: Exception) -> None:
        if ENABLED:
            if a_closing_palette_s_fault(error):
                return
            commands = list_clicked_on_a_result_gone(error)
            if commands is not None:
                # Its palette, if still in front: the list takes no more clicks.
                if commands.is_attached and commands.screen is self.screen:
                    self.screen.dismiss()
                return
            self.ending_on(error)
        super()._handle_exception(error)


@contextmanager
def colour_system(system: str) -> Iterator[None]:
    """Apps made inside write colours for ``system`` (``truecolor``, ``256``...): Textual
    reads them from a constant as each app is made (from ``TEXTUAL_COLOR_SYSTEM``, once, on
    import). Put back after, for a caller that goes on. The public path leaves Textual's."""
    import textual.constants

    if not ENABLED:
        yield
        return
    previous = textual.constants.COLOR_SYSTEM
    textual.constants.COLOR_SYSTEM = system
    try:
        yield
    finally:
        textual.constants.COLOR_SYSTEM = previous


# A cache of Textual's that keeps what it should let go.

def release_styles_caches() -> bool:
    """Have Textual's ``StylesCache.get_inner_outer`` cache by its two colours alone, for
    the process. Textual caches it for each StylesCache (``lru_cache`` on the method,
    Textual issue 6665), so its 1,024 entries keep that many StylesCaches, and every line
    they hold, after their widgets have gone, and every collection of the oldest generation
    walks them. False on the public path, or where the method is not such a cache (a Textual
    that has mended it)."""
    if not ENABLED:
        return False
    from textual._styles_cache import StylesCache

    cached = StylesCache.__dict__.get("get_inner_outer")
    if getattr(cached, "__module__", None) == __name__:  # released already
        return True
    method = getattr(cached, "__wrapped__", None)
    code = getattr(method, "__code__", None)
    if not hasattr(cached, "cache_info") or code is None or code.co_varnames[:3] != (
            "cls", "base_background", "background"):
        return False

    @lru_cache(maxsize=cached.cache_info().maxsize)
    def by_colours(base_background: Any, background: Any) -> Any:
        return method(StylesCache, base_background, background)  # (cls is not read)

    def get_inner_outer(self: StylesCache, base_background: Any, background: Any) -> Any:
        return by_colours(base_background, background)

    StylesCache.get_inner_outer = get_inner_outer
    return True


# Lines that carry their terminal text.


class PrerenderedStrip(Strip):
    """A strip with the text it is written as on a terminal of ``color_system``, whose
    segments, made by ``segments``, are made when first wanted (see ``tui/prerendered.py``).

    Strip.__init__ waits for the segments (see __getattr__): Textual 8.x's Strip keeps its
    segments and caches in slots."""

    __slots__ = ["_text", "_color_system", "_make_segments"]

    def __init__(self, segments: Callable[[], list[Segment]], cell_length: int, text: str,
                 color_system: str) -> None:
        self._make_segments = segments
        self._cell_length = cell_length
        self._text = text
        self._color_system = color_system

    def __getattr__(self, name: str):
        # Only an attribute that was never set comes here: one of Strip's, read by a
        # method of Strip, for the first time.
        if name in STRIP_SLOTS:
            Strip.__init__(self, self._make_segments(), self._cell_length)
            return getattr(self, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def render(self, console: Console) -> str:
        if console_system(console) == self._color_system:
            return self._text
        return super().render(console)

    def divide(self, cuts: Sequence[int]) -> Sequence[Strip]:
        # The compositor divides every line at the edges of the widgets beside it: at its
        # own width, that is the line itself, as Strip.divide finds after its cache.
        if [cut for cut in cuts if cut <= self._cell_length] == [self._cell_length]:
            return [self]
        return super().divide(cuts)


def text_strip(segments: Callable[[], list[Segment]], cell_length: int, text: str,
               color_system: str) -> Strip:
    """A line of ``cell_length`` cells, made of ``segments()``, written as ``text`` on a
    terminal of ``color_system``: a :class:`PrerenderedStrip` on the private path, a
    plain strip of its segments on the public one."""
    if ENABLED:
        return PrerenderedStrip(segments, cell_length, text, color_system)
    return Strip(segments(), cell_length)


def framed(line: Strip, left: Strip, right: Strip, console: Console) -> Strip:
    """``line`` between the one-cell strips ``left`` and ``right`` (a border's sides), as one
    strip, which keeps the line's terminal text if it has it."""
    width = left.cell_length + line.cell_length + right.cell_length
    if not isinstance(line, PrerenderedStrip) or console_system(console) != line._color_system:
        return Strip([*left, *line, *right], width)
    # (the sides are the same strips for every line: Textual renders each once)
    text = f"{left.render(console)}{line._text}{right.render(console)}"
    return PrerenderedStrip(lambda: [*left, *line, *right], width, text, line._color_system)


# Input read leniently (tui/terminal_input.py).


def read_input_with(decoder: Callable[[str], Callable[[], Any]], parser: type) -> bool:
    """Make Textual's Linux driver decode what the terminal sends with ``decoder(encoding)()``
    (an incremental decoder, made as by ``codecs.getincrementaldecoder``) and parse it with
    ``parser`` (:func:`lenient_parser`'s). False on the public path, or with no
    such driver (Windows)."""
    if not ENABLED:
        return False
    try:
        from textual.drivers import linux_driver
    except ImportError:  # no termios: Windows, whose driver reads keys, not bytes
        return False
    # The driver makes both with the names it imported: give those names these.
    linux_driver.getincrementaldecoder = decoder
    linux_driver.XTermParser = parser
    return True


def lenient_parser() -> type:
    """Textual's parser of what the terminal sends, which drops a Kitty key sequence it
    cannot make sense of (rather than typing its characters as keys): it overrides the
    parser's ``_parse_extended_key``, which exists from Textual 8.2.7."""
    from textual import events
    from textual._xterm_parser import XTermParser
    from textual.keys import Keys

    class LenientParser(XTermParser):
        def _parse_extended_key(self, sequence: str) -> list[events.Key] | None:
            try:
                return super()._parse_extended_key(sequence)
            except ValueError:  # a field int() cannot read, such as "97:65"
                return [events.Key(Keys.Ignore, sequence)]  # what the parser drops

    return LenientParser


# Textual's palette, guarded (the one faults as it closes, in :class:`AppHooks`).


def guarded_palette() -> type:
    """Textual's command palette, guarded against a fault of Textual's: a search that
    finishes after the palette has gone (NoMatches). Textual's own on the public path."""
    from textual.command import CommandList, CommandPalette

    if not ENABLED:
        return CommandPalette
    from textual import work
    from textual.css.query import NoMatches

    class GuardedPalette(CommandPalette):
        @work(exclusive=True, group=CommandPalette._GATHER_COMMANDS_GROUP)
        async def _gather_commands(self, search_value: str) -> None:
            # Textual's search, started as the palette mounts and at each change of its
            # input, runs when the app gets to it: in a burst of keys (ctrl+p escape), or
            # as the app closes, the palette's list may be gone by then, NoMatches.
            try:
                await CommandPalette._gather_commands.__wrapped__(self, search_value)
            except NoMatches:
                if self.query(CommandList):  # the list is there: a fault of another kind
                    raise

    return GuardedPalette


def _frames(error: BaseException) -> list[FrameType]:
    """The frames ``error`` was raised through, the one that raised it last."""
    frames, entry = [], error.__traceback__
    while entry is not None:
        frames.append(entry.tb_frame)
        entry = entry.tb_next
    return frames


def a_closing_palette_s_fault(error: BaseException) -> bool:
    """Whether ``error`` is Textual's command palette looking for a widget of its own
    (NoMatches) once its widgets have gone, as it closes: a timer or a watcher of its
    search that fired late (showing it busy, "No matches found"). Nothing is lost by letting
    it pass: the palette is going. Found by the palette in the error's traceback, which is
    Textual's own code, as it stands."""
    from textual.command import CommandList, CommandPalette
    from textual.css.query import NoMatches

    if not isinstance(error, NoMatches):
        return False
    for frame in _frames(error):
        palette = frame.f_locals.get("self")
        if isinstance(palette, CommandPalette):
            return not palette.query(CommandList)
    return False


def list_clicked_on_a_result_gone(error: BaseException) -> Widget | None:
    """The palette's list, if ``error`` is Textual's list handling a click on a result it
    no longer has (IndexError in ``OptionList._on_click``): the click was on the list as
    drawn before its search changed it, and reached it after (seen in a storm of input).
    Nothing is lost by letting it pass, no result was there to choose; but the list's
    messages end with the error, so its palette is closed (ctrl+p opens a new one)."""
    from textual.command import CommandList

    frames = _frames(error) if isinstance(error, IndexError) else []
    if not frames or frames[-1].f_code.co_name != "_on_click":
        return None
    commands, clicked = frames[-1].f_locals.get("self"), frames[-1].f_locals.get(
        "clicked_option")
    if (isinstance(commands, CommandList) and isinstance(clicked, int)
            and clicked >= commands.option_count):
        return commands
    return None
