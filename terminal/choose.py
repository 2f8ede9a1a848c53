"""What the app makes of the terminal's answers (``terminal/detect.py``): how the picture reaches
the terminal and in which colours, each with the reason; and what ``biceps doctor`` prints.

Graphics (:func:`choose`): real pixels where the terminal has a protocol for them (kitty's
graphics, iTerm2's images, sixel within the size and colours the terminal allows), else text
cells (``terminal/cells.py``): sextants where the terminal draws block characters itself
(whatever its font: kitty, WezTerm, foot, Ghostty, VTE's terminals, Windows Terminal), else
half-blocks, which every font has. Inside tmux, sixel where tmux draws it itself (3.4 built
with sixel); kitty's images through tmux's passthrough where they can be placed by Unicode
placeholders (kitty 0.28 and later: Debian 12's 0.26 would show missing-glyph boxes); images
placed at the cursor would land where the outer cursor happens to be, and stay when tmux
shows another window. Inside GNU screen, text.

Colours (:func:`colours`): 24-bit where the terminal keeps a 24-bit colour (it read one back,
or terminfo's ``Tc`` or ``RGB``), or where tmux sends it 24-bit colour (its ``RGB``
feature), else the environment (``COLORTERM``), else 256. tmux answers neither question for
the terminal behind it; over SSH, where the ``tmux`` command cannot be asked, a tmux of 3.2
or later is taken to send 24-bit colour, as it does to the terminals it knows (XTerm, kitty,
iTerm2, mintty, and those whose terminfo says so). GNU screen 4 has 256 colours at most.
"""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass, field
from typing import Mapping

from biceps.terminal.detect import ANSWER_TIME, VTE, Answers, Place

DEFAULT_CELL = (10, 20)  # pixels, when the terminal does not say
PLACEHOLDERS_SINCE = (0, 28)  # the kitty whose Unicode placeholders place images inside tmux
PLACEHOLDER_TERMINALS = ("kitty", "ghostty")  # as tmux names them
# Terminals that draw block characters themselves, sextants among them, by the name they
# answer XTVERSION with (lower case) or tmux knows them by.
SEXTANT_TERMINALS = ("kitty", "wezterm", "foot", "ghostty")
TEXT = ("halfblocks", "quadrants", "sextants")
NAMES = {"halfblocks": "Half-blocks", "quadrants": "Quadrants", "sextants": "Sextants"}
TRUE_COLOUR_TMUX = (3, 2)  # tmux's terminal features, RGB among them, since 3.2


@dataclass(frozen=True)
class Choice:
    """How the picture is sent, why, and what else the terminal could have shown."""

    graphics: str  # "kitty", "sixel", "iterm", or text: "halfblocks", "quadrants", "sextants"
    reason: str
    cell: tuple[int, int] = DEFAULT_CELL  # the terminal's pixels per cell
    colours: int = 256  # sixel colour registers
    could: str | None = None  # something better the terminal has, when not used
    notes: tuple[str, ...] = field(default_factory=tuple)
    multiplexer: str | None = None  # what the images go through: "tmux" or None
    sixel_limit: tuple[int, int] | None = None  # the largest sixel image, in pixels


@dataclass(frozen=True)
class Colours:
    """The colours the picture goes out in, and why."""

    system: str  # "truecolor" or "256", as Rich and Textual name them
    reason: str


def multiplexer(answers: Answers, place: Place) -> str | None:
    """The multiplexer in front of the terminal, as its answers or the environment say (a
    tmux reached over SSH may have set TERM=screen)."""
    return answers.multiplexer or place.multiplexer


def _version(name: str, program: str) -> tuple[int, ...] | None:
    """The version in an XTVERSION answer such as ``kitty(0.26.5)`` or ``tmux 3.3a``."""
    found = re.search(re.escape(program) + r"[ (](\d+)\.(\d+)", name, re.IGNORECASE)
    return (int(found[1]), int(found[2])) if found else None


def drawing_terminal(answers: Answers, place: Place) -> str | None:
    """The terminal that draws the cells, if it is one known to draw sextants itself,
    whatever its font; None if it is not, or cannot be told."""
    if multiplexer(answers, place) == "tmux":  # tmux hands the characters on
        named = f"{place.outer_version or ''} {place.outer_terminal or ''}".lower()
        return next((name for name in SEXTANT_TERMINALS if name in named), None)
    if multiplexer(answers, place) is not None:
        return None
    named = f"{answers.name or ''} {place.terminal_program}".lower()
    found = next((name for name in SEXTANT_TERMINALS if name in named), None)
    if found:
        return found
    if answers.secondary[:1] == (VTE,) or place.vte:
        return "a VTE terminal"
    return "Windows Terminal" if place.windows_terminal else None


def best(answers: Answers, place: Place) -> tuple[str | None, str]:
    """The best protocol for real pixels that ``answers`` show, and why; None if none."""
    name = (answers.name or place.terminal_program or "").lower()
    inside = multiplexer(answers, place)
    if inside == "screen":
        return None, "inside GNU screen, whose passthrough cannot place images"
    if inside == "tmux":
        return _through_tmux(answers, place)
    if answers.kitty == "OK":
        return "kitty", "the terminal answered kitty's graphics query with OK"
    if "iterm" in name:
        return "iterm", f"the terminal is iTerm2 ({answers.name or place.terminal_program})"
    if answers.sixel:
        return "sixel", "the terminal's device attributes include 4, sixel graphics"
    if not answers.answered:
        return None, f"the terminal did not answer within {ANSWER_TIME:g} s"
    return None, "the terminal answered, but with no protocol for real pixels"


def _through_tmux(answers: Answers, place: Place) -> tuple[str | None, str]:
    if answers.sixel:
        return "sixel", "tmux draws sixel images itself (its device attributes say 4)"
    if place.multiplexer != "tmux":  # tmux answered, but its command is not here
        return None, (f"inside tmux ({answers.name or 'it answered as tmux'}), from another "
                      "machine (over SSH): which terminal is behind it cannot be asked")
    outer = place.outer_terminal or ""
    kitty = next((name for name in PLACEHOLDER_TERMINALS if name in outer), None)
    if kitty is None:
        within = f" (in {outer})" if outer else ""
        return None, (f"inside tmux{within}, which does not draw sixel itself, and images other "
                      "than kitty's placeholders would land where the outer cursor is, and "
                      "stay when tmux shows another window")
    if not place.passthrough:
        return None, (f"inside tmux in {outer}, with allow-passthrough off (tmux set -g "
                      "allow-passthrough on lets kitty's images through)")
    version = _version(place.outer_version or "", "kitty")
    if kitty == "kitty" and version is None:
        return None, (f"inside tmux in {outer}, whose version tmux does not know: kitty's "
                      "Unicode placeholders, which place images inside tmux, need 0.28")
    if kitty == "kitty" and version < PLACEHOLDERS_SINCE:
        return None, (f"inside tmux in {place.outer_version}, older than kitty 0.28, whose "
                      "Unicode placeholders place images inside tmux")
    return "kitty", (f"inside tmux in {place.outer_version or outer}, with allow-passthrough "
                     "on: kitty images through it, placed by Unicode placeholders")


def choose(asked: str, answers: Answers | None, place: Place) -> Choice:
    """What the app uses when ``--graphics`` (or the config) says ``asked``."""
    found, why = best(answers or Answers(), place)
    if answers is None:
        why = "there is no terminal to ask (not a terminal)"
    answers = answers or Answers()
    cell, cell_note = _cell(answers)
    colours = min(answers.colour_registers or 256, 256)
    notes = (cell_note,)
    if answers.sixel and answers.colour_registers is not None and answers.colour_registers < 64:
        notes += (f"sixel has only {answers.colour_registers} colours here; xterm takes more "
                  "with -xrm 'XTerm*numColorRegisters: 256'",)
    limit = answers.sixel_limit
    window = answers.window or (answers.size[2:] if answers.size and all(answers.size[2:])
                                else None)
    if found == "sixel" and limit is not None and window is not None:
        if limit[0] < window[0] or limit[1] < window[1]:
            notes += (f"sixel images are at most {limit[0]}x{limit[1]} pixels here: the "
                      "picture is drawn that large at most, in the middle of its cells "
                      "(xterm takes larger with -xrm 'XTerm*maxGraphicSize: 4000x4000')",)
    through = "tmux" if multiplexer(answers, place) == "tmux" else None
    drawer = drawing_terminal(answers, place)
    text = "sextants" if drawer else "halfblocks"
    text_why = (f"sextants, which {drawer} draws itself" if drawer else
                "half-blocks, which every font has")
    details = dict(cell=cell, colours=colours, notes=notes, sixel_limit=limit)
    if asked == "auto":
        if found:
            return Choice(found, f"auto: {why}", multiplexer=through, **details)
        return Choice(text, f"auto: {why}: {text_why}", **details)
    if asked in TEXT:
        better = found or (text if text != asked and asked == "halfblocks" else None)
        reason = f"{asked}, as asked" + (" (the default)" if asked == "halfblocks" else "")
        return Choice(asked, reason, could=better, **details)
    lacking = (why if multiplexer(answers, place) is not None else
               _lacking(asked, answers))
    if found != asked and lacking:
        return Choice("halfblocks", f"{asked} was asked, but {lacking}: half-blocks",
                      could=found, **details)
    return Choice(asked, f"{asked}, as asked", multiplexer=through, **details)


def _lacking(asked: str, answers: Answers) -> str | None:
    """What the terminal's answers show it lacks for ``asked``, if they do: sixel without 4
    in its device attributes, kitty's images without an answer to kitty's query (iTerm2's
    images have no question to tell them by)."""
    if asked == "sixel" and answers.answered and not answers.sixel:
        vt340 = (" (xterm draws sixel as a VT340: xterm -ti vt340)"
                 if (answers.name or "").startswith("XTerm") else "")
        return (f"the terminal's device attributes ({';'.join(answers.device_attributes)}) "
                f"do not include 4, sixel{vt340}")
    if asked == "kitty" and answers.asked_all and answers.kitty != "OK":
        return "the terminal did not answer kitty's graphics query"
    return None


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


def _per_cell(pixels: tuple[int, int], columns: int, rows: int) -> tuple[int, int] | None:
    """Pixels per cell, or None if they round to nothing or the size in cells is unknown:
    a pseudo-terminal nobody gave a size (``script`` into a pipe, some editors' shells)
    says 0 columns and 0 rows."""
    if columns <= 0 or rows <= 0:
        return None
    cell = pixels[0] // columns, pixels[1] // rows
    return cell if all(cell) else None


def colours(asked: str, answers: Answers | None, place: Place,
            environ: Mapping[str, str] = os.environ) -> Colours:
    """The colours the picture goes out in for ``asked`` (``--colors``, or the config's:
    ``auto``, ``truecolor`` or ``256``), never fewer than 256: in 16 the shaded muscle is a
    flat yellow stick, and every terminal in use has 256 (xterm since 1999)."""
    if asked != "auto":
        return Colours(asked, f"{_named(asked)}, as asked")
    chosen = environ.get("TEXTUAL_COLOR_SYSTEM", "auto")
    if chosen in ("truecolor", "256"):
        return Colours(chosen, f"{_named(chosen)}: TEXTUAL_COLOR_SYSTEM={chosen}")
    answers = answers or Answers()
    inside = multiplexer(answers, place)
    if inside == "tmux":
        return _tmux_colours(answers, place)
    if inside == "screen":
        return Colours("256", "256: GNU screen (4) shows 256 colours at most")
    if answers.true_colour:
        how = ("it read back a 24-bit colour (DECRQSS)" if answers.reads_back_24_bit else
               f"its terminfo says {' and '.join(sorted(answers.capabilities))} (XTGETTCAP)")
        return Colours("truecolor", f"24-bit: {how}")
    if answers.true_colour is False:
        return Colours("256", f"256: it keeps a 24-bit colour as one of its palette "
                              f"(DECRQSS read back {answers.sgr})")
    colorterm = environ.get("COLORTERM", "")
    if colorterm in ("truecolor", "24bit"):
        return Colours("truecolor", f"24-bit: COLORTERM={colorterm}")
    said = "the terminal did not say it keeps a 24-bit colour, and COLORTERM is " + (
        colorterm or "unset")
    return Colours("256", f"256: {said} (--colors truecolor if it shows 24-bit colour)")


def _named(system: str) -> str:
    return "24-bit" if system == "truecolor" else "256"


def _tmux_colours(answers: Answers, place: Place) -> Colours:
    if place.outer_features is not None:
        outer = place.outer_terminal or "the terminal"
        if "RGB" in place.outer_features:
            return Colours("truecolor", f"24-bit: tmux sends {outer} 24-bit colour (its RGB "
                                        "feature)")
        return Colours("256", f"256: tmux sends {outer} 256 colours (tmux set -as "
                              "terminal-features ',*:RGB' if it shows 24-bit)")
    version = _version(answers.name or "", "tmux")
    if place.multiplexer != "tmux" and version is not None and version >= TRUE_COLOUR_TMUX:
        return Colours("truecolor", f"24-bit: {answers.name} answered, and tmux 3.2 and later "
                                    "send 24-bit colour to the terminals they know have it "
                                    "(--colors 256 if the picture shows bands)")
    return Colours("256", "256: inside tmux, which does not say whether it sends 24-bit "
                          "colour (--colors truecolor if it does)")


def hint(choice: Choice) -> str | None:
    """What to tell a person whose terminal could show a better picture, once."""
    if choice.could is None:
        return None
    what = "finer cells" if choice.could in TEXT else "real pixels"
    return (f"This terminal can show {what} ({choice.could}): start biceps with "
            f"--graphics {choice.could}, or set graphics = \"{choice.could}\" under [render] "
            "in the config.")


def notice(asked: str, choice: Choice) -> str | None:
    """What the app says once it is up: that a better picture could be had, or why the
    real pixels asked for are not there."""
    if asked not in TEXT and choice.graphics in TEXT:
        return f"{NAMES[choice.graphics]}: {choice.reason}"
    return hint(choice)


def report(asked: str, answers: Answers | None, place: Place, choice: Choice,
           colour: Colours) -> str:
    """What ``biceps doctor`` prints: what was asked, what came back, what follows."""
    a = answers or Answers()
    inside = multiplexer(a, place)
    lines = [
        ("terminal", _terminal_line(a, place)),
        ("multiplexer", _multiplexer_line(a, place) if inside else "none"),
        ("round trip", "no terminal to ask (not a terminal)" if answers is None else
         f"{1000 * a.round_trip:.1f} ms" if a.round_trip is not None else
         f"no answer within {ANSWER_TIME:g} s"),
        ("kitty graphics", a.kitty or ("no answer" if a.asked_all or answers is None else
                                       f"not asked ({inside or 'a multiplexer'} would take the "
                                       "question for a title)")),
        ("sixel", ("yes" if a.sixel else "no") + f" (device attributes "
                  f"{';'.join(a.device_attributes) or 'none'})"
                  + (f", {a.colour_registers} colour registers" if a.colour_registers else "")
                  + (f", at most {a.sixel_limit[0]}x{a.sixel_limit[1]} pixels"
                     if a.sixel_limit else "")),
        ("cell size", f"{choice.cell[0]}x{choice.cell[1]} pixels"
                      + (f", in a terminal of {a.size[0]}x{a.size[1]} cells" if a.size else "")),
        ("colours", f"{colour.reason} (COLORTERM={place.colorterm or 'unset'})"),
        ("graphics", f"{choice.graphics}: {choice.reason}"),
    ]
    text = "\n".join(f"  {label:<15} {value}" for label, value in lines)
    notes = [*choice.notes] + ([hint(choice)] if hint(choice) else [])
    return text + "".join(f"\n  - {note}" for note in notes)


def _terminal_line(answers: Answers, place: Place) -> str:
    term = (f"TERM={place.term or 'unset'}"
            + (f", {place.terminal_program}" if place.terminal_program else ""))
    if multiplexer(answers, place) is None:
        return f"{answers.name or 'did not say its name'} ({term})"
    behind = place.outer_version or place.outer_terminal
    answered = f"{answers.name} answered for it" if answers.name else "the multiplexer answered"
    if behind:
        return f"{behind}, behind the multiplexer ({answered}; {term})"
    return f"behind the multiplexer, which cannot say which ({answered}; {term})"


def _multiplexer_line(answers: Answers, place: Place) -> str:
    inside = multiplexer(answers, place)
    name = "GNU screen" if inside == "screen" else "tmux"
    if place.multiplexer != inside:
        return (f"{name} (it answered as {answers.name or name}; its variables are not here: "
                "over SSH, or from another machine)")
    if place.outer_terminal:
        name += f" in {place.outer_terminal}"
    return name + (", allow-passthrough on" if place.passthrough else "")
