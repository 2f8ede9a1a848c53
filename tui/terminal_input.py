"""What the terminal sends, read leniently: a byte that is not UTF-8 is a U+FFFD, not a crash.

Textual's Linux driver decodes the terminal's bytes as strict UTF-8 (Textual 8.2,
``textual/drivers/linux_driver.py``, ``run_input_thread``), so one byte that is not UTF-8 (a
paste from a Latin-1 terminal, ``tmux send-keys -H ff``) raises UnicodeDecodeError in its
input thread, and the app ends. Reported upstream as Textualize/textual#6456 (open; the
proposed fix is ``errors="replace"``). Until it is fixed there, the driver is given decoders
that do what a terminal does with such a byte: show U+FFFD in its place.
"""

from __future__ import annotations

import codecs
from functools import partial
from typing import Callable


def decode_leniently() -> Callable[..., str]:
    """A new incremental UTF-8 decoder's ``decode(data, final=False)``, which turns each byte
    that is not UTF-8 into U+FFFD; what the driver reads the terminal with."""
    return _lenient_decoder("utf-8")().decode


def _lenient_decoder(encoding: str) -> Callable[[], codecs.IncrementalDecoder]:
    return partial(codecs.getincrementaldecoder(encoding), errors="replace")


def read_terminal_leniently() -> None:
    """Make Textual's Linux driver decode its input with :func:`decode_leniently`."""
    try:
        from textual.drivers import linux_driver
    except ImportError:  # no termios: Windows, whose driver reads keys, not bytes
        return
    # The driver makes its decoder with the name it imported, getincrementaldecoder:
    # give that name the lenient one.
    linux_driver.getincrementaldecoder = _lenient_decoder
