"""Frames as images in the kitty graphics protocol
(https://sw.kovidgoyal.net/kitty/graphics-protocol/), as kitty, WezTerm, Ghostty and Konsole
speak it.

Each frame is sent as raw RGB (``f=24``), deflated (``o=z``: zlib at its fastest level, a
few milliseconds for a 1200x800 frame, against three times that for a PNG, and about as
small), in base64 chunks of 4096 bytes as the protocol asks. (The encoders are in
``tui/pixels.py``; this module, free of Textual, also serves ``biceps snapshot --kitty``.)

Inside tmux an image placed at the cursor would stay on the screen when tmux shows another
window, so there the frame gets a virtual placement (``U=1``) instead, sent through tmux's
passthrough, and the picture's cells hold Unicode placeholders (kitty 0.28 and later): the
character U+10EEEE, its row and column as diacritics, and the image id as its colour, text
that tmux draws, moves and hides like any other. Every frame reuses one image
id and one placement id, so each replaces the last in place, without flicker; ``C=1`` keeps
the cursor still, ``q=2`` keeps the terminal from answering (its answers would reach the
app as keys). ``c`` and ``r`` stretch the frame over the picture's cells, whatever its size
in pixels.
"""

from __future__ import annotations

import base64
import zlib

import numpy as np

CHUNK = 4096  # base64 bytes per escape sequence, as the protocol asks
PLACEMENT = 1
PLACEHOLDER = "\U0010EEEE"
# The diacritics that number placeholder rows and columns, kitty's rowcolumn-diacritics.txt:
# the combining characters of Unicode 6.0 of class 230 (above) that neither decompose nor
# take part in a composition, in code point order (tests/tui/test_pixels.py checks the rule).
DIACRITICS = [chr(int(code, 16)) for code in (
    "305 30d 30e 310 312 33d 33e 33f 346 34a 34b 34c 350 351 352 357 35b 363 364 365 366 "
    "367 368 369 36a 36b 36c 36d 36e 36f 483 484 485 486 487 592 593 594 595 597 598 599 "
    "59c 59d 59e 59f 5a0 5a1 5a8 5a9 5ab 5ac 5af 5c4 610 611 612 613 614 615 616 617 657 "
    "658 659 65a 65b 65d 65e 6d6 6d7 6d8 6d9 6da 6db 6dc 6df 6e0 6e1 6e2 6e4 6e7 6e8 6eb "
    "6ec 730 732 733 735 736 73a 73d 73f 740 741 743 745 747 749 74a 7eb 7ec 7ed 7ee 7ef "
    "7f0 7f1 7f3 816 817 818 819 81b 81c 81d 81e 81f 820 821 822 823 825 826 827 829 82a "
    "82b 82c 82d 951 953 954 f82 f83 f86 f87 135d 135e 135f 17dd 193a 1a17 1a75 1a76 1a77 "
    "1a78 1a79 1a7a 1a7b 1a7c 1b6b 1b6d 1b6e 1b6f 1b70 1b71 1b72 1b73 1cd0 1cd1 1cd2 1cda "
    "1cdb 1ce0 1dc0 1dc1 1dc3 1dc4 1dc5 1dc6 1dc7 1dc8 1dc9 1dcb 1dcc 1dd1 1dd2 1dd3 1dd4 "
    "1dd5 1dd6 1dd7 1dd8 1dd9 1dda 1ddb 1ddc 1ddd 1dde 1ddf 1de0 1de1 1de2 1de3 1de4 1de5 "
    "1de6 1dfe 20d0 20d1 20d4 20d5 20d6 20d7 20db 20dc 20e1 20e7 20e9 20f0 2cef 2cf0 2cf1 "
    "2de0 2de1 2de2 2de3 2de4 2de5 2de6 2de7 2de8 2de9 2dea 2deb 2dec 2ded 2dee 2def 2df0 "
    "2df1 2df2 2df3 2df4 2df5 2df6 2df7 2df8 2df9 2dfa 2dfb 2dfc 2dfd 2dfe 2dff a66f a67c "
    "a67d a6f0 a6f1 a8e0 a8e1 a8e2 a8e3 a8e4 a8e5 a8e6 a8e7 a8e8 a8e9 a8ea a8eb a8ec a8ed "
    "a8ee a8ef a8f0 a8f1 aab0 aab2 aab3 aab7 aab8 aabe aabf aac1 fe20 fe21 fe22 fe23 fe24 "
    "fe25 fe26 10a0f 10a38 1d185 1d186 1d187 1d188 1d189 1d1aa 1d1ab 1d1ac 1d1ad 1d242 "
    "1d243 1d244 "
).split()]


def command(keys: str, payload: bytes = b"") -> str:
    """One graphics command: ``ESC _ G keys ; payload ESC \\``."""
    data = ";" + payload.decode("ascii") if payload else ""
    return f"\x1b_G{keys}{data}\x1b\\"


def transmit(frame: np.ndarray, image_id: int, columns: int, rows: int,
             virtual: bool = False) -> list[str]:
    """The commands sending ``frame`` ((h, w, 3) uint8), replacing the image ``image_id``
    and its placement, if there are any, and placing it over ``columns x rows`` cells: from
    the cursor, or (``virtual``) wherever placeholders for it are written."""
    height, width = frame.shape[:2]
    data = base64.b64encode(zlib.compress(np.ascontiguousarray(frame).data, 1))
    chunks = [data[at:at + CHUNK] for at in range(0, len(data), CHUNK)] or [b""]
    where = "U=1" if virtual else f"p={PLACEMENT},C=1"
    first = f"a=T,f=24,o=z,s={width},v={height},i={image_id},{where},c={columns},r={rows},q=2"
    parts = []
    for index, chunk in enumerate(chunks):
        more = int(index < len(chunks) - 1)
        keys = f"{first},m={more}" if index == 0 else f"m={more},q=2"
        parts.append(command(keys, chunk))
    return parts


def delete(image_id: int) -> str:
    """Take the image ``image_id`` off the screen and out of the terminal's memory."""
    return command(f"a=d,d=I,i={image_id},q=2")


def placeholders(row: int, columns: int) -> str:
    """Row ``row`` of a virtual placement, ``columns`` cells wide, as placeholder text (its
    colour, the image id, is the caller's to give)."""
    mark = DIACRITICS[row]
    return "".join(PLACEHOLDER + mark + DIACRITICS[column] for column in range(columns))


def through_tmux(commands: list[str]) -> str:
    """``commands`` in tmux's passthrough (``allow-passthrough on``), each on its own:
    tmux hands the outer terminal what is between ``ESC P tmux;`` and ``ESC \\``, escapes
    doubled."""
    return "".join(f"\x1bPtmux;{command.replace(chr(27), chr(27) * 2)}\x1b\\"
                   for command in commands)
