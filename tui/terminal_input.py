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
read.

The parser also keeps a paste a paste. Inside a bracketed paste (``ESC [ 200 ~`` to
``ESC [ 201 ~``) Textual's parser takes an escape character for the start of a sequence,
and what follows it, unread as paste, it types as keys once the sequence has grown too long
to be one: a paste holding an escape (terminal output copied with its colours) typed its
text, and ``/`` subdivided the muscle, ``[`` rolled the model. Inside a paste an escape is
written as U+FFFD, as a stray byte, before Textual's parser reads it.

And it ends a paste whose end never comes (a terminal that died part way, or a storm of
random input), which made every key after it pasted text, ``q`` included, for ever:
Textual's parser has no timeout. A terminal writes a paste in one burst, so once the input
thread has seen nothing for :data:`PASTE_SILENCE`, the paste is over. (Silence is judged by
the thread's regular ticks, not by the time between reads: a thread kept waiting finds the
rest of a paste queued, and reads it at once.)
"""

from __future__ import annotations

import codecs
from functools import partial
from time import monotonic
from typing import Callable, Iterable

from textual import events
from textual._xterm_parser import XTermParser  # the parser the driver reads keys with
from textual.keys import Keys


def decode_leniently() -> Callable[..., str]:
    """A new incremental UTF-8 decoder's ``decode(data, final=False)``, which turns each byte
    that is not UTF-8 into U+FFFD; what the driver reads the terminal with."""
    return codecs.getincrementaldecoder("utf-8")("replace").decode


PASTE_START = "\x1b[200~"
PASTE_END = "\x1b[201~"
PASTE_SILENCE = 1.0  # seconds without input inside a paste after which it is over


class PasteGuard:
    """What the terminal sends, read after read, with each escape inside a bracketed paste
    but its end written as U+FFFD. A read may end part way into the paste's end: that part
    is held until the next read says whether it is the end."""

    def __init__(self) -> None:
        self.inside = False
        self._started = 0  # characters of PASTE_START just read, outside a paste
        self._held = ""  # inside a paste: the start of what may be its end

    def read(self, text: str) -> str:
        out = []
        for character in text:
            if not self.inside:
                out.append(character)
                self._started = _matched(PASTE_START, self._started, character)
                if self._started == len(PASTE_START):
                    self.inside, self._started = True, 0
                continue
            held = self._held + character
            if PASTE_END.startswith(held):
                self._held = held
                if held == PASTE_END:
                    out.append(held)
                    self.inside, self._held = False, ""
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

    def cut_off(self) -> str:
        """The end of the paste, which never came: what to read in its place."""
        held, self._held, self.inside = self._held, "", False
        return held.replace("\x1b", "\ufffd") + PASTE_END


def _matched(marker: str, matched: int, character: str) -> int:
    """How much of ``marker`` has been read once ``character`` follows ``matched`` of it
    (no prefix of either marker recurs inside it, so a mismatch starts afresh)."""
    if character == marker[matched]:
        return matched + 1
    return 1 if character == marker[0] else 0


def _lenient_decoder(encoding: str) -> Callable[[], codecs.IncrementalDecoder]:
    return partial(codecs.getincrementaldecoder(encoding), "replace")


class LenientParser(XTermParser):
    """Textual's parser of what the terminal sends, which keeps a paste a paste, ends one
    whose end never comes, and drops a Kitty key sequence it cannot make sense of (rather
    than type its characters as keys). See the module."""

    def __init__(self, debug: bool = False, clock: Callable[[], float] = monotonic) -> None:
        super().__init__(debug)
        self._paste = PasteGuard()
        self._clock = clock
        self._last_input = clock()

    def feed(self, data: str) -> Iterable[events.Event]:
        if not data:  # the end of input
            return super().feed(data)
        self._last_input = self._clock()
        # Empty when all of it is held (the start of what may be the paste's end), which
        # must not reach Textual's parser: to it, no text is the end of input.
        guarded = self._paste.read(data)
        return super().feed(guarded) if guarded else ()

    def tick(self) -> Iterable[events.Event]:
        # Called by the input thread after each wait for input (at most 0.1 s).
        yield from super().tick()
        if self._paste.inside and self._clock() - self._last_input > PASTE_SILENCE:
            yield from super().feed(self._paste.cut_off())

    def _parse_extended_key(self, sequence: str) -> list[events.Key] | None:
        try:
            return super()._parse_extended_key(sequence)
        except ValueError:  # a field int() cannot read, such as "97:65"
            return [events.Key(Keys.Ignore, sequence)]  # what the parser drops


def read_terminal_leniently() -> None:
    """Make Textual's Linux driver read its input with :func:`decode_leniently` and
    :class:`LenientParser`."""
    try:
        from textual.drivers import linux_driver
    except ImportError:  # no termios: Windows, whose driver reads keys, not bytes
        return
    # The driver makes both with the names it imported: give those names these.
    linux_driver.getincrementaldecoder = _lenient_decoder
    linux_driver.XTermParser = LenientParser
