"""Just enough of a terminal to read Textual's output back: cursor moves, SGR, text.

Each cell keeps its character and the graphic state it was drawn with (attributes, then
foreground and background as the codes that set them), so that two outputs can be
compared cell by cell, and half-block pictures decoded back to pixels.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np
from rich._palettes import EIGHT_BIT_PALETTE

TOKEN = re.compile(
    r"\x1b\[(?P<csi>[0-9;?<>=]*)(?P<final>[@-~])"  # CSI
    r"|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)"  # OSC
    r"|\x1b(?P<escape>.)"  # two-character escapes: DECSC, DECRC
    r"|(?P<text>[^\x1b]+)",
    re.DOTALL,
)
OFF = {22: {1, 2}, 23: {3}, 24: {4, 21}, 25: {5, 6}, 27: {7}, 28: {8}, 29: {9}, 54: {51, 52},
       55: {53}}


@dataclass(frozen=True)
class Pen:
    attributes: frozenset[int] = frozenset()
    foreground: tuple[int, ...] = ()  # () for the default, else the codes: (31,), (38, 2, r, g, b)
    background: tuple[int, ...] = ()

    def after(self, codes: list[int]) -> Pen:
        """The pen once an SGR sequence with these codes has been applied."""
        attributes, foreground, background = set(self.attributes), self.foreground, self.background
        index = 0
        while index < len(codes):
            code = codes[index]
            if code == 0:
                attributes, foreground, background = set(), (), ()
            elif code in (38, 48):
                size = 3 if codes[index + 1] == 5 else 5
                colour = tuple(codes[index + 1:index + size])
                foreground, background = ((colour, background) if code == 38
                                          else (foreground, colour))
                index += size - 1
            elif 30 <= code <= 37 or 90 <= code <= 97:
                foreground = (code,)
            elif 40 <= code <= 47 or 100 <= code <= 107:
                background = (code,)
            elif code in (39, 49):
                foreground, background = ((), background) if code == 39 else (foreground, ())
            elif code in OFF:
                attributes -= OFF[code]
            else:
                attributes.add(code)
            index += 1
        return Pen(frozenset(attributes), foreground, background)


@dataclass
class Screen:
    width: int
    height: int
    cells: list[list[tuple[str, Pen]]] = field(init=False)

    def __post_init__(self) -> None:
        self.cells = [[(" ", Pen())] * self.width for _ in range(self.height)]
        self.x = self.y = 0
        self.pen = Pen()
        self.saved = (0, 0, Pen())

    def feed(self, output: str) -> Screen:
        for token in TOKEN.finditer(output):
            final, parameters = token["final"], token["csi"]
            if token["text"] is not None:
                self._draw(token["text"])
            elif final and re.fullmatch(r"[0-9;]*", parameters) is None:
                continue  # private modes, keyboard protocols: nothing drawn
            elif final == "m":
                self.pen = self.pen.after([int(code or 0) for code in parameters.split(";")])
            elif final in ("H", "f"):
                row, _, column = parameters.partition(";")
                self.y, self.x = int(row or 1) - 1, int(column or 1) - 1
            elif token["escape"] == "7":
                self.saved = (self.x, self.y, self.pen)
            elif token["escape"] == "8":
                self.x, self.y, self.pen = self.saved
        return self

    def _draw(self, text: str) -> None:
        for character in text:
            if character == "\n":
                self.y += 1
            elif character == "\r":
                self.x = 0
            elif self.x < self.width and self.y < self.height:
                self.cells[self.y][self.x] = (character, self.pen)
                self.x += 1

    def text(self, y: int) -> str:
        return "".join(character for character, _ in self.cells[y])

    def picture(self) -> np.ndarray:
        """The half-block picture in the first rounded box from the top left (the app's
        viewport): (2 height, width, 3) uint8."""
        right = self.text(0).index("╮")
        bottom = next(y for y in range(self.height) if self.text(y).startswith("╰"))
        return self.pixels(1, 1, right - 1, bottom - 1)

    def pixels(self, left: int, top: int, width: int, height: int) -> np.ndarray:
        """The half-block picture in these cells: (2 height, width, 3) uint8."""
        frame = np.zeros((2 * height, width, 3), np.uint8)
        for y in range(height):
            for x in range(width):
                character, pen = self.cells[top + y][left + x]
                below = _rgb(pen.background)
                above = _rgb(pen.foreground) if character == "▀" else below
                assert character in "▀ ", f"{character!r} at {left + x}, {top + y}"
                frame[2 * y, x], frame[2 * y + 1, x] = above, below
        return frame


def _rgb(colour: tuple[int, ...]) -> tuple[int, int, int]:
    """A colour's codes as RGB: 24-bit, or an entry of xterm's 256 colours above the 16
    system ones (as Rich has the palette)."""
    if colour[:1] == (5,) and colour[1] >= 16:
        return tuple(EIGHT_BIT_PALETTE[colour[1]])
    assert colour[:1] == (2,), f"not a 24-bit colour or a palette entry: {colour}"
    return colour[1:]
