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
"""

from __future__ import annotations

import codecs
from functools import partial
from typing import Callable

from textual import events
from textual._xterm_parser import XTermParser  # the parser the driver reads keys with
from textual.keys import Keys


def decode_leniently() -> Callable[..., str]:
    """A new incremental UTF-8 decoder's ``decode(data, final=False)``, which turns each byte
    that is not UTF-8 into U+FFFD; what the driver reads the terminal with."""
    return _lenient_decoder("utf-8")().decode


def _lenient_decoder(encoding: str) -> Callable[[], codecs.IncrementalDecoder]:
    return partial(codecs.getincrementaldecoder(encoding), errors="replace")


class LenientParser(XTermParser):
    """Textual's parser of what the terminal sends, which drops a Kitty key sequence it
    cannot make sense of (rather than type its characters as keys)."""

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
