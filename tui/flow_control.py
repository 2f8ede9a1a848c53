"""The terminal's flow control (XON/XOFF) off for as long as the app runs, and the terminal
given back exactly as it was.

Textual puts the terminal in raw mode, flow control off, and back in its own mode as it
closes, before it writes its last output and waits for it to be written. Input typed
ahead and not yet read (a flood of keys; a paste holding ctrl+s) is read by the terminal
in its own mode then, a ctrl+s among it stops all output, and the app waited for ever to
write its last bytes (an app found after a storm, its writer thread blocked, the terminal
with ixon). Off from the start, a ctrl+s stays a key; at the end the terminal's mode comes
back as it was, and what was typed for the app and never read is dropped rather than left
for the shell to run.
"""

from __future__ import annotations

import termios
import tty
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def no_flow_control(fd: int = 0) -> Iterator[None]:
    """Flow control off on terminal ``fd`` within the block, its mode restored after; where
    ``fd`` is not a terminal, nothing."""
    try:
        before = termios.tcgetattr(fd)
    except termios.error:
        yield
        return
    during = list(before)
    during[tty.IFLAG] &= ~(termios.IXON | termios.IXOFF)
    termios.tcsetattr(fd, termios.TCSANOW, during)
    try:
        yield
    finally:
        try:
            termios.tcsetattr(fd, termios.TCSAFLUSH, before)
        except termios.error:  # the terminal has gone (a closed window)
            pass
