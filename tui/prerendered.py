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
:class:`Strip`'s caches. Cropped under a dialog, exported as SVG or compared, a line makes
its segments then, once. Such a line is a Strip made without Strip.__init__, which only
Textual's internals allow: :class:`~tui.textual_private.PrerenderedStrip`. On the public
path a line is a plain strip of its segments, made on the render thread.
"""

from __future__ import annotations

from rich.console import COLOR_SYSTEMS, Console
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
