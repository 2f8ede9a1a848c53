"""Terminal output with only the colour codes that change.

Textual writes every segment as ``CSI <all its codes> m``, the text, then ``CSI 0 m``. A
picture of thousands of segments in a row repeats the reset, and often a colour that has
not changed. :func:`minimized` rewrites such output so that each SGR (Select Graphic
Rendition) sequence sends only what differs from what the terminal already has; what the
terminal shows, cell by cell, is the same.

The kernel reads the output once, keeping two states (codes that are on, foreground,
background): the one the output asks for and the one sent so far. SGR sequences only
change the first; before anything is drawn (text, an escape sequence other than a cursor
move or a new line, which Textual never writes where it would scroll) the difference is
sent. A code it does not know (underline colour, colons) is sent as it is, and the rest of
that output too, unchanged.

Each write is taken on its own: Textual ends every write with the terminal in its default
state, so that is where the state starts, and each write ends with the state its own codes
leave, as it would have without the rewriting.
"""

from __future__ import annotations

import numpy as np
from textual.driver import Driver
from textual.strip import SGR_STYLES

from biceps.engine.jit import helper, ngjit
from biceps.terminal.writing import BASIC, PALETTE, RGB, put_colour, put_number

ESC, BEL, LF, CR = 0x1B, 0x07, 0x0A, 0x0D

# The attributes Textual writes, one bit each, and the codes that turn them off again.
ATTRIBUTES = np.array([int(code) for code in SGR_STYLES], np.int64)
ATTRIBUTES_OFF = {22: (1, 2), 23: (3,), 24: (4, 21), 25: (5, 6), 27: (7,), 28: (8,),
                  29: (9,), 54: (51, 52), 55: (53,)}


def _off_masks() -> np.ndarray:
    """For each code, the bits of the attributes it turns off."""
    masks = np.zeros(max(ATTRIBUTES_OFF) + 1, np.int64)
    bits = {int(code): bit for bit, code in enumerate(ATTRIBUTES)}
    for code, attributes in ATTRIBUTES_OFF.items():
        for attribute in attributes:
            masks[code] |= 1 << bits[attribute]
    return masks


OFF_MASKS = _off_masks()

MAX_PARAMETERS = 64


@helper
def _put_sgr(out, at, sent, wanted, attributes, reset):
    """Write an SGR sequence taking the terminal from ``sent`` to ``wanted`` (each
    attributes, foreground, background): from a reset, or changing only what differs."""
    start = at
    out[at] = ESC
    out[at + 1] = 91  # [
    at += 2
    if reset:
        out[at] = 48  # 0
        at += 1
    added = wanted[0] if reset else wanted[0] & ~sent[0]
    for bit in range(len(attributes) if added else 0):
        if added & (1 << bit):
            if at > start + 2:
                out[at] = 59  # ;
                at += 1
            at = put_number(out, at, attributes[bit])
    for index in (1, 2):
        if wanted[index] != (0 if reset else sent[index]):
            if at > start + 2:
                out[at] = 59
                at += 1
            at = put_colour(out, at, wanted[index], index == 1)
    out[at] = 109  # m
    return at + 1


@helper
def _put_change(out, at, sent, wanted, attributes):
    """Write the shortest SGR sequence taking the terminal from ``sent`` to ``wanted``, if
    they differ; return where it ends."""
    if sent[0] == wanted[0] and sent[1] == wanted[1] and sent[2] == wanted[2]:
        return at
    end = at
    if (sent[0] & ~wanted[0]) == 0:  # no attribute to turn off: the change alone will do
        end = _put_sgr(out, at, sent, wanted, attributes, False)
    # With both colours set (a picture's every cell), a reset writes all that the change
    # does, and more.
    if end == at or wanted[1] == 0 or wanted[2] == 0:
        reset_end = _put_sgr(out, end, sent, wanted, attributes, True)
        if end == at or reset_end - end < end - at:
            _copy(out, end, reset_end, out, at)  # the reset's way is shorter: keep it
            end = at + reset_end - end
    for index in range(3):
        sent[index] = wanted[index]
    return end


@helper
def _parse_sgr(source, start, end, state, attributes, off_masks, parameters):
    """Apply the SGR parameters in ``source[start:end]`` to ``state``; False (and
    ``state`` undefined) if one is not understood."""
    count, number, digits = 0, 0, 0
    for index in range(start, end + 1):
        byte = source[index] if index < end else 59
        if 48 <= byte <= 57:
            number = number * 10 + byte - 48
            digits += 1
            if digits > 9:
                return False
        elif byte == 59:
            if count == MAX_PARAMETERS:
                return False
            parameters[count] = number
            count += 1
            number, digits = 0, 0
        else:
            return False
    index = 0
    while index < count:
        code = parameters[index]
        if code == 0:
            state[0], state[1], state[2] = 0, 0, 0
        elif 30 <= code <= 37 or 90 <= code <= 97:
            state[1] = BASIC | code
        elif 40 <= code <= 47 or 100 <= code <= 107:
            state[2] = BASIC | code
        elif code == 39 or code == 49:
            state[1 if code == 39 else 2] = 0
        elif code == 38 or code == 48:
            target = 1 if code == 38 else 2
            if index + 2 < count and parameters[index + 1] == 5 and parameters[index + 2] < 256:
                state[target] = PALETTE | parameters[index + 2]
                index += 2
            elif (index + 4 < count and parameters[index + 1] == 2 and parameters[index + 2] < 256
                  and parameters[index + 3] < 256 and parameters[index + 4] < 256):
                state[target] = (RGB | parameters[index + 2] << 16 | parameters[index + 3] << 8
                                 | parameters[index + 4])
                index += 4
            else:
                return False
        elif code < len(off_masks) and off_masks[code]:
            state[0] &= ~off_masks[code]
        else:
            for bit in range(len(attributes)):
                if attributes[bit] == code:
                    state[0] |= 1 << bit
                    break
            else:
                return False
        index += 1
    return True


@helper
def _sequence_end(source, at):
    """Where the escape sequence starting at ``source[at]`` (ESC) ends; an unfinished one
    ends with ``source``."""
    size = len(source)
    if at + 1 >= size:
        return size
    kind = source[at + 1]
    if kind == 91:  # [ : CSI, up to a final byte in @ to ~
        for index in range(at + 2, size):
            if 0x40 <= source[index] <= 0x7E:
                return index + 1
        return size
    if kind == 93 or kind == 80 or kind == 95:  # ] P _ : OSC, DCS, APC, up to BEL or ST
        for index in range(at + 2, size):
            if source[index] == BEL:
                return index + 1
            if source[index] == ESC and index + 1 < size and source[index + 1] == 92:
                return index + 2
        return size
    return at + 2


@ngjit
def minimize_sgr(source, out, length, attributes, off_masks, states, parameters):
    """Rewrite ``source`` into ``out`` with only the SGR codes that change anything.

    source: (n,) uint8 UTF-8; out: (m,) uint8, written; length: (1,) int64, set to the
    bytes written, or -1 if ``out`` was too small. ``attributes``: the attribute codes, one
    bit each; ``off_masks[code]``: the bits a code turns off. states: (3, 3) int64 zeros
    and parameters: (MAX_PARAMETERS,) int64, scratch (passed in: numba's ``np.zeros`` costs
    a cold start a few tenths of a second to compile).
    """
    # Each state: attributes, foreground, background.
    sent, wanted, trial = states[0], states[1], states[2]
    size, room = len(source), len(out) - 256  # two ways to change state take less
    at, written, verbatim = 0, 0, False
    while at < size:
        if source[at] == LF or source[at] == CR:
            # A new line draws nothing, as a cursor move does: Textual, full screen (the
            # app is never inline), writes one between the rows of an update, never below
            # the screen's last row, so it never scrolls (which would fill the new row
            # with the background then in force).
            end = at + 1
        elif source[at] != ESC:
            end = _text_end(source, at)
            written = _put_change(out, written, sent, wanted, attributes)
        else:
            end = _sequence_end(source, at)
            final = source[end - 1] if end - at > 2 and source[at + 1] == 91 else 0  # CSI
            if final == 109:  # m: SGR
                _copy(wanted, 0, 3, trial, 0)
                if _parse_sgr(source, at + 2, end - 1, trial, attributes, off_masks, parameters):
                    _copy(trial, 0, 3, wanted, 0)
                    at = end
                    continue
                verbatim, end = True, size  # not understood: the rest goes as it is
            if final != 72 and final != 102:  # a cursor move (H, f) draws nothing
                written = _put_change(out, written, sent, wanted, attributes)
        if written + end - at > room:
            length[0] = -1
            return
        _copy(source, at, end, out, written)
        written += end - at
        at = end
    if not verbatim:
        written = _put_change(out, written, sent, wanted, attributes)
    length[0] = written


@helper
def _copy(source, start, end, target, at):
    """target[at:at + end - start] = source[start:end], front to back (overlapping only with
    at <= start). A loop, not slice assignment: numba compiles that with its error message,
    string formatting and all, which took a large share of this module's first, cold
    compilation, before the app could show anything."""
    for index in range(end - start):
        target[at + index] = source[start + index]


@helper
def _text_end(source, at):
    """Where the text starting at ``source[at]`` ends: at the next ESC or new line, or the
    end."""
    for index in range(at, len(source)):
        if source[index] == ESC or source[index] == LF or source[index] == CR:
            return index
    return len(source)


def minimized(text: str) -> str:
    """``text`` with only the colour codes that change anything."""
    if "\x1b[" not in text or "m" not in text:  # (an SGR code ends in m)
        return text  # a cursor question, say: not worth the kernel's call
    source = np.frombuffer(text.encode("utf-8", "surrogatepass"), np.uint8)
    out = np.empty(len(source) + len(source) // 2 + 512, np.uint8)
    length = np.zeros(1, np.int64)
    minimize_sgr(source, out, length, ATTRIBUTES, OFF_MASKS, np.zeros((3, 3), np.int64),
                 np.empty(MAX_PARAMETERS, np.int64))
    if length[0] < 0:  # longer than it was: a pathological mix of codes, leave it be
        return text
    return out[: length[0]].tobytes().decode("utf-8", "surrogatepass")


def lean(driver_class: type[Driver]) -> type[Driver]:
    """``driver_class``, writing its output :func:`minimized`."""

    class LeanDriver(driver_class):
        def write(self, data: str) -> None:
            super().write(minimized(data))

    LeanDriver.__name__ = LeanDriver.__qualname__ = f"Lean{driver_class.__name__}"
    return LeanDriver
