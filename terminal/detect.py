"""What the terminal can show, asked before the app takes the screen (``terminal/choose.py`` makes
the choices from the answers).

:func:`ask` writes questions to the terminal and reads the answers, in two rounds:

1. questions every terminal and multiplexer takes in its stride: XTVERSION (``CSI > 0 q``,
   the terminal's name and version: ``XTerm(379)``, ``kitty(0.26.5)``, ``tmux 3.3a``), the
   secondary device attributes (``CSI > c``: 65 is VTE, 83 GNU screen, 84 tmux),
   XTSMGRAPHICS (``CSI ? 1 ; 1 ; 0 S`` and ``CSI ? 2 ; 4 ; 0 S``: sixel's colour registers
   and the largest sixel image, which xterm keeps to 1000x1000 pixels unless told more),
   ``CSI 16 t`` and ``CSI 14 t`` (the size of a cell, and of the window, in pixels);
2. unless a multiplexer answered (or the environment says one is there): kitty's graphics
   query (an image of one pixel that is checked, not stored: ``a=q``), which tmux would
   take for a window title and GNU screen for its status line; a 24-bit colour set and read
   back (DECRQSS ``m``: a terminal that keeps it answers with ``38:2``, one that maps it
   onto its palette with ``38;5``), which screen would hand on to the terminal behind it;
   and terminfo's ``Tc`` and ``RGB`` (XTGETTCAP).

Each round ends with the primary device attributes (DA1, ``CSI c``): every terminal
answers them (4 among them meaning sixel), and answers in order, so once they are in, every
answer that is coming has come. A terminal answers a round in one round trip; the time
limit (:data:`ANSWER_TIME`) is for one that does not answer at all (no terminal descended
from the VT100 is one), long enough for a slow SSH link. Answers that came later still
would reach the app as keys.

Inside tmux the app talks to tmux, which answers for itself; the ``tmux`` command (when the
app runs where tmux does, not over SSH from inside it) says which terminal tmux is in, that
terminal's own XTVERSION answer, and whether tmux sends it 24-bit colour.
"""

from __future__ import annotations

import fcntl
import os
import re
import select
import shutil
import struct
import subprocess
import termios
import time
import tty
from dataclasses import dataclass
from typing import Mapping

ANSWER_TIME = 2.0  # seconds to wait for a terminal that does not answer at all
ANY_TERMINAL = (
    "\x1b[>0q"  # XTVERSION
    "\x1b[>c"  # DA2
    "\x1b[?1;1;0S"  # XTSMGRAPHICS: sixel colour registers
    "\x1b[?2;4;0S"  # XTSMGRAPHICS: the largest sixel image
    "\x1b[16t"  # cell size in pixels
    "\x1b[14t"  # text area in pixels
    "\x1b[c"  # DA1, answered last
)
NO_MULTIPLEXER = (
    "\x1b_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\x1b\\"  # kitty graphics
    "\x1b[38;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m"  # a 24-bit colour, read back (DECRQSS)
    "\x1bP+q5463;524742\x1b\\"  # XTGETTCAP Tc, RGB
    "\x1b[c"  # DA1, answered last
)
DEVICE_ATTRIBUTES = re.compile(rb"\x1b\[\?([\d;]*)c")
SECONDARY_ATTRIBUTES = re.compile(rb"\x1b\[>([\d;]*)c")
KITTY = re.compile(rb"\x1b_Gi=31;([^\x1b]*)\x1b\\")
VERSION = re.compile(rb"\x1bP>\|([^\x1b]*)\x1b\\")
REGISTERS = re.compile(rb"\x1b\[\?1;0;(\d+)S")
GEOMETRY = re.compile(rb"\x1b\[\?2;0;(\d+);(\d+)S")
CELL = re.compile(rb"\x1b\[6;(\d+);(\d+)t")
WINDOW = re.compile(rb"\x1b\[4;(\d+);(\d+)t")
SGR = re.compile(rb"\x1bP([01])\$r([^\x1b]*)\x1b\\")
CAPABILITY = re.compile(rb"\x1bP1\+r([0-9A-Fa-f]+)")
SIXEL_ATTRIBUTE = "4"
TMUX, SCREEN, VTE = "84", "83", "65"  # secondary device attributes' first parameter
TRUE_COLOUR_CAPABILITIES = {"Tc", "RGB"}


@dataclass(frozen=True)
class Answers:
    """What the terminal (or the multiplexer in front of it) said, and how fast."""

    answered: bool = False  # the device attributes came back in time
    round_trip: float | None = None  # seconds from the first questions to their answers
    device_attributes: tuple[str, ...] = ()
    kitty: str | None = None  # the graphics query's answer: "OK" or an error
    name: str | None = None  # XTVERSION's
    colour_registers: int | None = None
    cell: tuple[int, int] | None = None  # pixels, width x height
    window: tuple[int, int] | None = None  # pixels, width x height, of the text area
    # The kernel's idea of the same (TIOCGWINSZ), which xterm keeps though it refuses to
    # answer CSI 14 t and 16 t by default; (columns, rows, width, height).
    size: tuple[int, int, int, int] | None = None
    secondary: tuple[str, ...] = ()  # DA2
    sixel_limit: tuple[int, int] | None = None  # the largest sixel image, in pixels
    asked_all: bool = False  # the second round was asked (no multiplexer in front)
    sgr: str | None = None  # DECRQSS's answer to the 24-bit colour: the SGR it holds
    capabilities: frozenset[str] = frozenset()  # of Tc and RGB, those XTGETTCAP confirmed

    @property
    def sixel(self) -> bool:
        return SIXEL_ATTRIBUTE in self.device_attributes

    @property
    def multiplexer(self) -> str | None:
        """The multiplexer that answered for the terminal, if one did: "tmux" or "screen"."""
        if (self.name or "").startswith("tmux ") or self.secondary[:1] == (TMUX,):
            return "tmux"
        return "screen" if self.secondary[:1] == (SCREEN,) else None

    @property
    def reads_back_24_bit(self) -> bool:
        """Whether DECRQSS read the 24-bit colour back as it was set."""
        return self.sgr is not None and re.search(r"38[:;]2[:;]", self.sgr) is not None

    @property
    def true_colour(self) -> bool | None:
        """Whether the terminal keeps a 24-bit colour as it is (DECRQSS read it back, or
        terminfo's Tc or RGB); False if it read back a palette's; None if nothing said."""
        if self.reads_back_24_bit or self.capabilities & TRUE_COLOUR_CAPABILITIES:
            return True
        if self.sgr is not None and re.search(r"38[:;]5[:;]", self.sgr):
            return False
        return None


def parse(data: bytes, round_trip: float | None = None,
          size: tuple[int, int, int, int] | None = None, asked_all: bool = False) -> Answers:
    """The answers in ``data``, what the terminal wrote back; ``size``: the terminal's size
    as the kernel has it, in cells and pixels; ``asked_all``: both rounds were asked."""
    attributes = DEVICE_ATTRIBUTES.search(data)
    kitty, version = KITTY.search(data), VERSION.search(data)
    registers, cell, window = REGISTERS.search(data), CELL.search(data), WINDOW.search(data)
    secondary, geometry, sgr = (SECONDARY_ATTRIBUTES.search(data), GEOMETRY.search(data),
                                SGR.search(data))
    confirmed = {bytes.fromhex(name.decode()).decode(errors="replace")
                 for name in CAPABILITY.findall(data) if len(name) % 2 == 0}
    return Answers(
        answered=attributes is not None,
        round_trip=round_trip if attributes is not None else None,
        device_attributes=tuple(attributes[1].decode().split(";")) if attributes else (),
        kitty=kitty[1].decode(errors="replace") if kitty else None,
        name=version[1].decode(errors="replace") if version else None,
        colour_registers=int(registers[1]) if registers else None,
        cell=(int(cell[2]), int(cell[1])) if cell and int(cell[1]) and int(cell[2]) else None,
        window=(int(window[2]), int(window[1])) if window else None,
        size=size,
        secondary=tuple(secondary[1].decode().split(";")) if secondary else (),
        sixel_limit=(int(geometry[1]), int(geometry[2])) if geometry else None,
        asked_all=asked_all,
        sgr=sgr[2].decode(errors="replace") if sgr and sgr[1] == b"1" else None,
        capabilities=frozenset(confirmed & TRUE_COLOUR_CAPABILITIES),
    )


def ask(environ: Mapping[str, str] = os.environ, timeout: float = ANSWER_TIME
        ) -> Answers | None:
    """Ask the controlling terminal; None when there is none (output to a pipe, say). The
    second round is left out where ``environ`` says a multiplexer is in front."""
    try:
        fd = os.open("/dev/tty", os.O_RDWR | os.O_NOCTTY)
    except OSError:
        return None
    try:
        if not os.isatty(fd):
            return None
        saved = termios.tcgetattr(fd)
        try:
            tty.setraw(fd, termios.TCSANOW)
            start = time.monotonic()
            os.write(fd, ANY_TERMINAL.encode())
            data, answered = _read_answers(fd, start + timeout)
            round_trip = time.monotonic() - start if answered else None
            first = parse(data)
            asked_all = (answered and first.multiplexer is None
                         and Place.here(environ).multiplexer is None)
            if asked_all:
                os.write(fd, NO_MULTIPLEXER.encode())
                more, _ = _read_answers(fd, time.monotonic() + timeout)
                data += more
            return parse(data, round_trip, _size(fd), asked_all)
        finally:
            termios.tcsetattr(fd, termios.TCSAFLUSH, saved)
    finally:
        os.close(fd)


def _size(fd: int) -> tuple[int, int, int, int] | None:
    try:
        rows, columns, width, height = struct.unpack(
            "HHHH", fcntl.ioctl(fd, termios.TIOCGWINSZ, b"\0" * 8))
    except OSError:
        return None
    return columns, rows, width, height


def _read_answers(fd: int, deadline: float) -> tuple[bytes, bool]:
    data = b""
    while (left := deadline - time.monotonic()) > 0:
        if not select.select([fd], [], [], left)[0]:
            break
        data += os.read(fd, 4096)
        if DEVICE_ATTRIBUTES.search(data):
            return data, True
    return data, False


@dataclass(frozen=True)
class Place:
    """Where the app runs, as its environment says: a multiplexer in front of the terminal,
    and what tmux says of the terminal behind it."""

    multiplexer: str | None = None  # "tmux" or "screen"
    outer_terminal: str | None = None  # the terminal tmux runs in, as tmux names it (TERM)
    outer_version: str | None = None  # its answer to XTVERSION, as tmux keeps it
    outer_features: frozenset[str] | None = None  # tmux's features of it (RGB: 24-bit)
    term: str = ""
    colorterm: str = ""
    terminal_program: str = ""  # TERM_PROGRAM or LC_TERMINAL
    passthrough: bool = False  # tmux's allow-passthrough is on
    vte: bool = False  # VTE_VERSION is set: a VTE terminal (GNOME Terminal, xfce4-terminal)
    windows_terminal: bool = False  # WT_SESSION is set

    @classmethod
    def here(cls, environ: Mapping[str, str] = os.environ) -> Place:
        term = environ.get("TERM", "")
        multiplexer = ("tmux" if environ.get("TMUX") else
                       "screen" if environ.get("STY") or term.startswith("screen") else None)
        outer = version = features = None
        passthrough = False
        if multiplexer == "tmux":
            described = _tmux("display-message", "-p",
                              "#{client_termname}|#{client_termtype}|#{client_termfeatures}")
            if described is not None:
                outer, version, listed = (described.split("|") + ["", ""])[:3]
                outer, version = outer or None, version or None
                features = frozenset(filter(None, listed.split(","))) if listed else None
            passthrough = _tmux("show-options", "-gv", "allow-passthrough") in ("on", "all")
        return cls(multiplexer, outer, version, features, term, environ.get("COLORTERM", ""),
                   environ.get("LC_TERMINAL") or environ.get("TERM_PROGRAM", ""), passthrough,
                   bool(environ.get("VTE_VERSION")), bool(environ.get("WT_SESSION")))


def _tmux(*arguments: str) -> str | None:
    """What the tmux command says, or None if it cannot say (no tmux, too old an option)."""
    if shutil.which("tmux") is None:
        return None
    try:
        result = subprocess.run(["tmux", *arguments], capture_output=True, text=True, timeout=2)
    except (OSError, subprocess.SubprocessError):
        return None
    return result.stdout.strip() or None if result.returncode == 0 else None
