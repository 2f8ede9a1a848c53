"""Names from outside (file names, keys in a file) as they can be shown to a person.

A file name is any bytes but ``/`` and NUL: it can hold an escape sequence that a terminal
obeys (``\\e]52;c;...\\a`` sets its clipboard, ``\\e[2J`` clears it), a newline that makes
one message look like two, or a byte that is not UTF-8 and cannot be printed at all. Every
name a message or a screen shows goes through :func:`printable`, which writes such
characters as escapes, so what reaches the terminal is inert text.
"""

from __future__ import annotations

import os


def printable(name: str | os.PathLike) -> str:
    """``name`` with every character a terminal would act on, or not show, written as an
    escape (``\\x1b``, ``\\u202e``); a byte that is not UTF-8 (kept by ``os.fsdecode`` as a
    lone surrogate) as ``\\xff``."""
    text = os.fsdecode(name) if isinstance(name, (bytes, os.PathLike)) else str(name)
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else _escaped(char) for char in text)


def _escaped(char: str) -> str:
    code = ord(char)
    if 0xDC80 <= code <= 0xDCFF:  # surrogateescape's stand-in for the byte code - 0xDC00
        return f"\\x{code - 0xDC00:02x}"
    if code <= 0xFF:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}"
