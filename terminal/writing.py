"""Terminal codes written into byte buffers, by kernels: numbers in decimal, and colours as
SGR parameters. Shared by the output minimizer (``tui/sgr.py``), the text cells
(``terminal/cells.py``) and sixel (``terminal/sixel.py``); free of Textual.
"""

from __future__ import annotations

from biceps.engine.jit import helper

# A colour as one number: its kind above bit 32, its value below. 0 is the default colour.
BASIC, PALETTE, RGB = 1 << 32, 2 << 32, 3 << 32  # 30-37 or 90-97 (40-.. 100-..), 5;n, 2;r;g;b
VALUE = (1 << 32) - 1


@helper
def put_number(out, at, number):
    """Write ``number`` (>= 0) in decimal at ``out[at:]``; return where it ends."""
    digits, bound = 1, 10
    while number >= bound:  # (colour values, mostly: three digits at most)
        digits, bound = digits + 1, bound * 10
    for place in range(digits - 1, -1, -1):
        out[at + place] = 48 + number % 10
        number //= 10
    return at + digits


@helper
def put_colour(out, at, colour, foreground):
    """Write the codes of ``colour`` (packed as above); return where they end."""
    kind, value = colour & ~VALUE, colour & VALUE
    if kind == BASIC:
        return put_number(out, at, value)
    if colour == 0:
        return put_number(out, at, 39 if foreground else 49)
    at = put_number(out, at, 38 if foreground else 48)
    out[at] = 59  # ;
    if kind == PALETTE:
        out[at + 1] = 53  # 5
        out[at + 2] = 59
        return put_number(out, at + 3, value)
    out[at + 1] = 50  # 2
    at += 2
    for shift in (16, 8, 0):
        out[at] = 59
        at = put_number(out, at + 1, (value >> shift) & 0xFF)
    return at
