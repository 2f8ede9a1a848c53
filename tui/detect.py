"""What the terminal can show, asked before the app takes the screen, and what the app makes
of the answers.

:func:`ask` writes a few questions to the terminal at once and reads the answers:

- kitty's graphics query (an image of one pixel that is checked, not stored:
  ``a=q``): kitty, WezTerm, Ghostty and Konsole answer ``OK``;
- XTVERSION (``CSI > 0 q``): the terminal's name and version;
- XTSMGRAPHICS (``CSI ? 1 ; 1 ; 0 S``): how many colour registers sixel images have;
- ``CSI 16 t`` and ``CSI 14 t``: the size of a cell, and of the window, in pixels;
- the primary device attributes (DA1, ``CSI c``), asked last: every terminal answers
  them, 4 among them meaning sixel, and answers in order, so once they are in, every
  answer that is coming has come.

A terminal answers in one round trip, however many questions there are; the time limit
(:data:`ANSWER_TIME`) is for one that does not answer at all (no terminal descended from
the VT100 is one), and is long enough for a slow SSH link: two seconds is longer than any
round trip people type over. Answers that came later still would reach the app as keys.

Inside tmux or GNU screen the multiplexer answers, not the terminal. tmux says sixel only
when it draws sixel itself (tmux 3.4 built with sixel), and that is used. Otherwise, in a
kitty (as tmux names the outer terminal) and with tmux's ``allow-passthrough`` on, kitty's
images go through the passthrough, placed by Unicode placeholders (kitty 0.28 or later),
which tmux draws, moves and hides as text. Images placed at the cursor (sixel and iTerm2
through the passthrough, kitty's without placeholders) would be drawn where the outer
cursor happens to be and stay when tmux shows another window: half-blocks, and why.

:func:`choose` turns the answers and the asked ``--graphics`` into a :class:`Choice`;
``biceps doctor`` prints both.
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
from dataclasses import dataclass, field
from typing import Mapping

from rich.console import Console

ANSWER_TIME = 2.0  # seconds to wait for a terminal that does not answer at all
DEFAULT_CELL = (10, 20)  # pixels, when the terminal does not say
QUESTIONS = (
    "\x1b_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\x1b\\"  # kitty graphics
    "\x1b[>0q"  # XTVERSION
    "\x1b[?1;1;0S"  # XTSMGRAPHICS: sixel colour registers
    "\x1b[16t"  # cell size in pixels
    "\x1b[14t"  # text area in pixels
    "\x1b[c"  # DA1, answered last
)
DEVICE_ATTRIBUTES = re.compile(rb"\x1b\[\?([\d;]*)c")
KITTY = re.compile(rb"\x1b_Gi=31;([^\x1b]*)\x1b\\")
VERSION = re.compile(rb"\x1bP>\|([^\x1b]*)\x1b\\")
REGISTERS = re.compile(rb"\x1b\[\?1;0;(\d+)S")
CELL = re.compile(rb"\x1b\[6;(\d+);(\d+)t")
WINDOW = re.compile(rb"\x1b\[4;(\d+);(\d+)t")
SIXEL_ATTRIBUTE = "4"
PLACEHOLDER_TERMINALS = ("kitty", "ghostty")  # as tmux names them: Unicode placeholders


@dataclass(frozen=True)
class Answers:
    """What the terminal (or the multiplexer in front of it) said, and how fast."""

    answered: bool = False  # the device attributes came back in time
    round_trip: float | None = None  # seconds from the questions to the device attributes
    device_attributes: tuple[str, ...] = ()
    kitty: str | None = None  # the graphics query's answer: "OK" or an error
    name: str | None = None  # XTVERSION's
    colour_registers: int | None = None
    cell: tuple[int, int] | None = None  # pixels, width x height
    window: tuple[int, int] | None = None  # pixels, width x height, of the text area
    # The kernel's idea of the same (TIOCGWINSZ), which xterm keeps though it refuses to
    # answer CSI 14 t and 16 t by default; (columns, rows, width, height).
    size: tuple[int, int, int, int] | None = None

    @property
    def sixel(self) -> bool:
        return SIXEL_ATTRIBUTE in self.device_attributes


def parse(data: bytes, round_trip: float | None = None,
          size: tuple[int, int, int, int] | None = None) -> Answers:
    """The answers in ``data``, what the terminal wrote back; ``size``: the terminal's size
    as the kernel has it, in cells and pixels."""
    attributes = DEVICE_ATTRIBUTES.search(data)
    kitty, version = KITTY.search(data), VERSION.search(data)
    registers, cell, window = REGISTERS.search(data), CELL.search(data), WINDOW.search(data)
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
    )


def ask(timeout: float = ANSWER_TIME) -> Answers | None:
    """Ask the controlling terminal; None when there is none (output to a pipe, say)."""
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
            os.write(fd, QUESTIONS.encode())
            data, answered = _read_answers(fd, start + timeout)
            return parse(data, time.monotonic() - start if answered else None, _size(fd))
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
    """Where the app runs: a multiplexer in front of the terminal, and the colours."""

    multiplexer: str | None = None  # "tmux" or "screen"
    outer_terminal: str | None = None  # the terminal tmux runs in, as tmux names it
    term: str = ""
    colorterm: str = ""
    terminal_program: str = ""  # TERM_PROGRAM or LC_TERMINAL
    passthrough: bool = False  # tmux's allow-passthrough is on

    @classmethod
    def here(cls, environ: Mapping[str, str] = os.environ) -> Place:
        multiplexer = "tmux" if environ.get("TMUX") else "screen" if environ.get("STY") else None
        inside_tmux = multiplexer == "tmux"
        outer = _tmux("display-message", "-p", "#{client_termname}") if inside_tmux else None
        passthrough = inside_tmux and _tmux("show-options", "-gv", "allow-passthrough") in (
            "on", "all")
        return cls(multiplexer, outer, environ.get("TERM", ""), environ.get("COLORTERM", ""),
                   environ.get("LC_TERMINAL") or environ.get("TERM_PROGRAM", ""), passthrough)


def _tmux(*arguments: str) -> str | None:
    """What the tmux command says, or None if it cannot say (no tmux, too old an option)."""
    if shutil.which("tmux") is None:
        return None
    try:
        result = subprocess.run(["tmux", *arguments], capture_output=True, text=True, timeout=2)
    except (OSError, subprocess.SubprocessError):
        return None
    return result.stdout.strip() or None if result.returncode == 0 else None


@dataclass(frozen=True)
class Choice:
    """How the picture is sent, why, and what else the terminal could have shown."""

    graphics: str  # "kitty", "sixel", "iterm" or "halfblocks"
    reason: str
    cell: tuple[int, int] = DEFAULT_CELL  # the terminal's pixels per cell
    colours: int = 256  # sixel colour registers
    could: str | None = None  # the real pixels the terminal has, when not used
    notes: tuple[str, ...] = field(default_factory=tuple)
    multiplexer: str | None = None  # what the images go through: "tmux" or None


def best(answers: Answers, place: Place) -> tuple[str | None, str]:
    """The best protocol for real pixels that ``answers`` show, and why; None if none."""
    name = (answers.name or place.terminal_program or "").lower()
    if place.multiplexer == "screen":
        return None, "inside GNU screen, whose passthrough cannot place images: half-blocks"
    if place.multiplexer == "tmux":
        if answers.sixel:
            return "sixel", "tmux draws sixel images itself (its device attributes say 4)"
        outer = place.outer_terminal or ""
        kitty = any(name in outer for name in PLACEHOLDER_TERMINALS)
        if kitty and place.passthrough:
            return "kitty", (f"inside tmux in {outer}, with allow-passthrough on: kitty images "
                             "through it, placed by Unicode placeholders (kitty 0.28 or later)")
        if kitty:
            return None, (f"inside tmux in {outer}, with allow-passthrough off: half-blocks "
                          "(tmux set -g allow-passthrough on lets kitty's images through)")
        within = f" (in {outer})" if outer else ""
        return None, (f"inside tmux{within}, which does not draw sixel itself, and images "
                      "other than kitty's placeholders would land where the outer cursor is, "
                      "and stay when tmux shows another window: half-blocks")
    if answers.kitty == "OK":
        return "kitty", "the terminal answered kitty's graphics query with OK"
    if "iterm" in name:
        return "iterm", f"the terminal is iTerm2 ({answers.name or place.terminal_program})"
    if answers.sixel:
        return "sixel", "the terminal's device attributes include 4, sixel graphics"
    if not answers.answered:
        return None, f"the terminal did not answer within {ANSWER_TIME:g} s: half-blocks"
    return None, "the terminal answered, but with no protocol for real pixels: half-blocks"


def choose(asked: str, answers: Answers | None, place: Place) -> Choice:
    """What the app uses when ``--graphics`` (or the config) says ``asked``."""
    found, why = best(answers or Answers(), place)
    if answers is None:
        why = "there is no terminal to ask (not a terminal): half-blocks"
    answers = answers or Answers()
    cell, cell_note = _cell(answers)
    colours = min(answers.colour_registers or 256, 256)
    notes = (cell_note,)
    if answers.sixel and answers.colour_registers is not None and answers.colour_registers < 64:
        notes += (f"sixel has only {answers.colour_registers} colours here; xterm takes more "
                  "with -xrm 'XTerm*numColorRegisters: 256'",)
    through = place.multiplexer if place.multiplexer == "tmux" else None
    if asked == "auto":
        graphics = found or "halfblocks"
        return Choice(graphics, f"auto: {why}", cell, colours, None, notes, through)
    if asked == "halfblocks":
        reason = "halfblocks, as asked (the default)"
        return Choice("halfblocks", reason, cell, colours, found, notes)
    if place.multiplexer is not None and found != asked:
        return Choice("halfblocks", f"{asked} was asked, but {why}", cell, colours, found, notes)
    return Choice(asked, f"{asked}, as asked", cell, colours, None, notes, through)


def _cell(answers: Answers) -> tuple[tuple[int, int], str]:
    if answers.cell:
        return answers.cell, "cell size from the terminal (CSI 16 t)"
    columns, rows, width, height = answers.size or (*shutil.get_terminal_size(), 0, 0)
    if answers.window and (cell := _per_cell(answers.window, columns, rows)):
        return cell, "cell size from the window's (CSI 14 t)"
    if cell := _per_cell((width, height), columns, rows):
        return cell, "cell size from the kernel's (TIOCGWINSZ)"
    width, height = DEFAULT_CELL
    return DEFAULT_CELL, f"the terminal did not say its cell size: {width}x{height} assumed"


def colour_system(asked: str = "auto", environ: Mapping[str, str] = os.environ) -> str:
    """The colours the picture goes out in, ``truecolor`` or ``256``, for ``asked`` (the
    command line's ``--colors``). ``auto`` takes TEXTUAL_COLOR_SYSTEM if it is set, else what
    Rich reads from COLORTERM and TERM, but never fewer than 256 colours: Rich reads
    TERM=xterm, Debian's xterm's own and a common one over SSH, as 16, in which the shaded
    muscle is a flat yellow stick, while xterm has had 256 since 1999 (patch 111) and every
    terminal in use has them."""
    if asked != "auto":
        return asked
    chosen = environ.get("TEXTUAL_COLOR_SYSTEM", "auto")
    if chosen in ("truecolor", "256"):
        return chosen
    found = Console(force_terminal=True, color_system="auto", _environ=dict(environ))
    return "truecolor" if found.color_system == "truecolor" else "256"


def _per_cell(pixels: tuple[int, int], columns: int, rows: int) -> tuple[int, int] | None:
    """Pixels per cell, or None if they round to nothing or the size in cells is unknown:
    a pseudo-terminal nobody gave a size (``script`` into a pipe, some editors' shells)
    says 0 columns and 0 rows."""
    if columns <= 0 or rows <= 0:
        return None
    cell = pixels[0] // columns, pixels[1] // rows
    return cell if all(cell) else None


def hint(choice: Choice) -> str | None:
    """What to tell a person whose terminal could show real pixels, once."""
    if choice.could is None:
        return None
    return (f"This terminal can show real pixels ({choice.could}): start biceps with "
            f"--graphics {choice.could}, or set graphics = \"{choice.could}\" under [render] "
            "in the config.")


def notice(asked: str, choice: Choice) -> str | None:
    """What the app says once it is up: that real pixels could be had, or why the real
    pixels asked for are half-blocks."""
    if asked != "halfblocks" and choice.graphics == "halfblocks":
        return f"Half-blocks: {choice.reason}"
    return hint(choice)


def report(asked: str, answers: Answers | None, place: Place, choice: Choice) -> str:
    """What ``biceps doctor`` prints: what was asked, what came back, what follows."""
    a = answers or Answers()
    lines = [
        ("terminal", f"{a.name or 'did not say its name'} (TERM={place.term or 'unset'}"
                     f"{', ' + place.terminal_program if place.terminal_program else ''})"),
        ("multiplexer", place.multiplexer + (f" in {place.outer_terminal}"
                                             if place.outer_terminal else "")
         + (", allow-passthrough on" if place.passthrough else "")
         if place.multiplexer else "none"),
        ("round trip", "no terminal to ask (not a terminal)" if answers is None else
         f"{1000 * a.round_trip:.1f} ms" if a.round_trip is not None else
         f"no answer within {ANSWER_TIME:g} s"),
        ("kitty graphics", a.kitty or "no answer"),
        ("sixel", ("yes" if a.sixel else "no") + f" (device attributes "
                  f"{';'.join(a.device_attributes) or 'none'})"
                  + (f", {a.colour_registers} colour registers" if a.colour_registers else "")),
        ("cell size", f"{choice.cell[0]}x{choice.cell[1]} pixels"),
        ("colours", f"COLORTERM={place.colorterm or 'unset'}: "
                    + ("24-bit" if colour_system() == "truecolor" else
                       "256 (start with --colors truecolor if the terminal has 24-bit)")),
        ("graphics", f"{choice.graphics}: {choice.reason}"),
    ]
    text = "\n".join(f"  {label:<15} {value}" for label, value in lines)
    notes = [*choice.notes] + ([hint(choice)] if hint(choice) else [])
    return text + "".join(f"\n  - {note}" for note in notes)
