"""What the terminal sends, read leniently: a byte or a sequence the app cannot make sense
of is dropped or shown as U+FFFD, never a crash.

Textual's Linux driver (8.2, ``textual/drivers/linux_driver.py``, ``run_input_thread``) reads
the terminal with two things that fail on input a terminal can send, and a failure there
kills its input thread, which ends the app:

- a strict UTF-8 decoder: one byte that is not UTF-8 (a paste from a Latin-1 terminal,
  ``tmux send-keys -H ff``) raises UnicodeDecodeError. Reported upstream as
  Textualize/textual#6456 (open; the proposed fix is ``errors="replace"``).
- ``XTermParser``, which reads a CSI ``u`` or ``~`` sequence of the Kitty keyboard protocol
  with ``int()`` on each field, so a field with a colon (``ESC [ 97:65 ; 2 u``, the
  protocol's alternate keys, or any ``ESC [ : u``) raises ValueError.

Until they are fixed there, the driver is given a decoder that does what a terminal does
with such a byte, shows U+FFFD in its place, and a parser that drops a sequence it cannot
read (``tui/textual_private.py``: both are given through Textual's internals, so not on the
public path).

The decoder also keeps a paste a paste. Inside a bracketed paste (``ESC [ 200 ~`` to
``ESC [ 201 ~``) Textual's parser takes an escape character for the start of a sequence,
and what follows it, unread as paste, it types as keys once the sequence has grown too long
to be one: a paste holding an escape (terminal output copied with its colours) typed its
text, and ``/`` subdivided the muscle, ``[`` rolled the model. Inside a paste the decoder
writes an escape as U+FFFD, as a stray byte.
"""

from __future__ import annotations

import codecs
from typing import Callable

from biceps.tui.textual_private import lenient_parser, read_input_with


def decode_leniently() -> Callable[..., str]:
    """A new incremental UTF-8 decoder's ``decode(data, final=False)``, which turns each byte
    that is not UTF-8 into U+FFFD, and an escape inside a paste too; what the driver reads
    the terminal with."""
    return TerminalDecoder().decode


class TerminalDecoder(codecs.getincrementaldecoder("utf-8")):  # type: ignore[misc]
    """UTF-8, a byte that is not as U+FFFD, a paste kept whole (see the module)."""

    def __init__(self, errors: str = "replace") -> None:
        super().__init__("replace")
        self._paste = PasteGuard()

    def decode(self, data: bytes, final: bool = False) -> str:
        return self._paste.read(super().decode(data, final))


PASTE_START = "\x1b[200~"
PASTE_END = "\x1b[201~"


class PasteGuard:
    """What the terminal sends, read after read, with each escape inside a bracketed paste
    but its end written as U+FFFD. A read may end part way into the paste's end: that part
    is held until the next read says whether it is the end."""

    def __init__(self) -> None:
        self._inside = False
        self._started = 0  # characters of PASTE_START just read, outside a paste
        self._held = ""  # inside a paste: the start of what may be its end

    def read(self, text: str) -> str:
        out = []
        for character in text:
            if not self._inside:
                out.append(character)
                self._started = _matched(PASTE_START, self._started, character)
                if self._started == len(PASTE_START):
                    self._inside, self._started = True, 0
                continue
            held = self._held + character
            if PASTE_END.startswith(held):
                self._held = held
                if held == PASTE_END:
                    out.append(held)
                    self._inside, self._held = False, ""
                continue
            # Not the end after all: what was held is pasted text, and this character
            # may begin the end afresh.
            out.append(self._held.replace("\x1b", "\ufffd"))
            self._held = ""
            if character == "\x1b":
                self._held = character
            else:
                out.append(character)
        return "".join(out)


def _matched(marker: str, matched: int, character: str) -> int:
    """How much of ``marker`` has been read once ``character`` follows ``matched`` of it
    (no prefix of either marker recurs inside it, so a mismatch starts afresh)."""
    if character == marker[matched]:
        return matched + 1
    return 1 if character == marker[0] else 0


def _lenient_decoder(encoding: str) -> type[codecs.IncrementalDecoder]:
    return TerminalDecoder


def read_terminal_leniently() -> bool:
    """Make Textual's Linux driver read its input with :func:`decode_leniently`'s decoder and
    ``tui/textual_private.py``'s lenient parser; False if it cannot be (the public path,
    Windows)."""
    return read_input_with(_lenient_decoder, lenient_parser())
