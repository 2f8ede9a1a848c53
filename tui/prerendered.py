"""Lines that carry the terminal text they are written as, made where it costs least.

Textual writes a line by turning each segment into its colour codes and text
(:meth:`Strip.render`), on the UI thread, at every frame. A picture's line is made once,
on the render thread, from a few hundred cell colours that each know their codes, so it
can carry its text from there; the viewport frames it in its border the same way. What
the terminal is sent is the same, byte for byte: each segment as Textual writes it,
``CSI <codes> m``, the text, ``CSI 0 m`` (``Strip.render_style``), with the codes Textual
makes (``Strip.render_ansi``), for the colour system the text was made for. A console of
another colour system, and any line Textual makes from one (cropped, divided under a
dialog), are written by Textual as usual.

Nor are a picture's segments made unless Textual asks for them: to write a line that it
neither crops nor divides, it needs the line's width and text alone, so a frame's new
lines, some fifty of a dozen segments each, are made without a :class:`Segment` or a
:class:`Strip`'s caches (1.3 ms a frame on the render thread at 200x60). Cropped
under a dialog, exported as SVG or compared, a line makes its segments then, once.
"""

from __future__ import annotations

from typing import Callable, Sequence

from rich.console import COLOR_SYSTEMS, Console
from rich.segment import Segment
from rich.style import Style
from textual.strip import Strip

RESET = "\x1b[0m"


def codes(style: Style, color_system: str) -> str:
    """What Textual writes before a segment of ``style`` (which has colours and no link),
    for a terminal of ``color_system`` (a :class:`~rich.console.Console`'s name for it)."""
    # Of a copy: Textual keeps the codes it makes in the style, for any colour system.
    copy = Style.from_color(style.color, style.bgcolor)
    return f"\x1b[{Strip.render_ansi(copy, COLOR_SYSTEMS[color_system])}m"


def console_system(console: Console) -> str:
    """The colour system Textual renders for on ``console`` (truecolor if it has none)."""
    return console.color_system or "truecolor"


class PrerenderedStrip(Strip):
    """A strip with the text it is written as on a terminal of ``color_system``, whose
    segments, made by ``segments``, are made when first wanted."""

    __slots__ = ["_text", "_color_system", "_make_segments"]

    def __init__(self, segments: Callable[[], list[Segment]], cell_length: int, text: str,
                 color_system: str) -> None:
        # Strip.__init__ waits for the segments (see __getattr__). A private hook:
        # Textual is pinned to 8.x, whose Strip keeps its segments and caches in slots.
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

    def framed(self, left: Strip, right: Strip, console: Console) -> Strip:
        """This line between the one-cell strips ``left`` and ``right`` (a border's
        sides), as one strip."""
        width = left.cell_length + self.cell_length + right.cell_length
        if console_system(console) != self._color_system:
            return Strip([*left, *self, *right], width)
        # (the sides are the same strips for every line: Textual renders each once)
        text = f"{left.render(console)}{self._text}{right.render(console)}"
        return PrerenderedStrip(lambda: [*left, *self, *right], width, text,
                                self._color_system)


STRIP_SLOTS = frozenset(Strip.__slots__) - {"_cell_length"}
