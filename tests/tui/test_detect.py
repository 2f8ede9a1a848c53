"""What terminals answer, read; and what the app chooses from the answers: how the picture
reaches the terminal, in which colours, and what biceps doctor says of it. The answers are
those of the real terminals, recorded (Debian 12's xterm 379, kitty 0.26.5, alacritty, VTE
0.70 in xfce4-terminal, mlterm 3.9, tmux 3.3a)."""

from __future__ import annotations

import pytest
from textual.geometry import Size

from biceps.terminal import detect
from biceps.terminal.cells import SEXTANTS
from biceps.terminal.choose import choose, colours, hint, notice, report
from biceps.terminal.detect import Answers, Place, parse
from biceps.tui.halfblocks import HalfBlocks, TextCells
from biceps.tui.pixels import ItermImages, KittyGraphics, KittyPlaceholders, Sixel, encoder_for

FIRST = {  # the first round's answers
    "xterm": b"\x1bP>|XTerm(379)\x1b\\\x1b[>41;379;0c\x1b[?1;3S\x1b[?2;3S"
             b"\x1b[?64;1;2;6;9;15;16;17;18;21;22;28c",
    "vt340": b"\x1bP>|XTerm(379)\x1b\\\x1b[>19;379;0c\x1b[?1;0;256S\x1b[?2;0;1000;1000S"
             b"\x1b[?63;1;2;4;6;9;15;16;22;28c",
    "kitty": b"\x1bP>|kitty(0.26.5)\x1b\\\x1b[>1;4000;26c\x1b[6;20;9t\x1b[4;500;720t\x1b[?62;c",
    "alacritty": b"\x1b[>0;1700;1c\x1b[4;588;792t\x1b[?6c",
    "vte": b"\x1b[>65;7006;1c\x1b[?1;1S\x1b[?2;1S\x1b[4;552;800t\x1b[?65;1;9c",
    "mlterm": b"\x1b[>24;279;0c\x1b[?1;0;1024S\x1b[?1;3;0S\x1b[6;22;10t\x1b[4;528;800t"
              b"\x1b[?63;1;2;3;4;6;7;15;18;22;29c",
    "tmux": b"\x1bP>|tmux 3.3a\x1b\\\x1b[>84;0;0c\x1b[?1;2c",
}
SECOND = {  # the second round's, where there was one
    "xterm": b"\x1bP1$r0;38:2::1:2:3m\x1b\\\x1b[?64;1;2;6;9;15;16;17;18;21;22;28c",
    "vt340": b"\x1bP1$r0;38:2::1:2:3m\x1b\\\x1b[?63;1;2;4;6;9;15;16;22;28c",
    "kitty": b"\x1b_Gi=31;OK\x1b\\\x1bP1$r38:2:1:2:3m\x1b\\\x1bP0+r5463\x1b\\"
             b"\x1bP0+r524742\x1b\\\x1b[?62;c",
    "alacritty": b"\x1b[?6c",
    "vte": b"\x1bP0$r\x1b\\\x1b[?65;1;9c",
    "mlterm": b"\x1bP1$r0;38;5;16m\x1b\\\x1bP0+r\x1b\\\x1b[?63;1;2;3;4;6;7;15;18;22;29c",
}


def answers_of(terminal: str, size=(100, 30, 0, 0)) -> Answers:
    both = terminal in SECOND
    return parse(FIRST[terminal] + SECOND.get(terminal, b""), 0.002, size, both)


def test_the_answers_are_read():
    kitty = answers_of("kitty")
    assert (kitty.kitty, kitty.name, kitty.cell, kitty.window) == ("OK", "kitty(0.26.5)",
                                                                   (9, 20), (720, 500))
    assert kitty.true_colour and not kitty.sixel and kitty.multiplexer is None
    vt340 = answers_of("vt340")
    assert vt340.sixel and vt340.colour_registers == 256 and vt340.sixel_limit == (1000, 1000)
    assert answers_of("xterm").true_colour and not answers_of("xterm").sixel
    assert answers_of("mlterm").true_colour is False  # it keeps 24-bit colours as its 256
    assert answers_of("vte").true_colour is None and answers_of("vte").secondary[0] == "65"
    assert answers_of("tmux").multiplexer == "tmux" and answers_of("tmux").name == "tmux 3.3a"
    assert parse(b"\x1b[>83;40900;0c\x1b[?1;2c").multiplexer == "screen"
    assert parse(b"\x1bP1+r524742\x1b\\\x1b[?62c").capabilities == {"RGB"}


def test_no_answer_is_not_taken_for_one():
    answers = parse(b"\x1b_Gi=31;OK\x1b\\", 0.5)  # no device attributes: not in time
    assert not answers.answered and answers.round_trip is None


@pytest.mark.parametrize("terminal, graphics", [
    ("kitty", "kitty"),
    ("vt340", "sixel"),
    ("mlterm", "sixel"),
    ("vte", "sextants"),  # VTE draws block characters itself
    ("xterm", "halfblocks"),
    ("alacritty", "halfblocks"),
])
def test_auto_takes_the_best_the_terminal_has(terminal, graphics):
    assert choose("auto", answers_of(terminal), Place()).graphics == graphics


def test_auto_takes_iterm2s_own_images_and_says_when_the_terminal_did_not_answer():
    assert choose("auto", parse(b"\x1bP>|iTerm2 3.5.0\x1b\\\x1b[?62;4c", 0.01),
                  Place()).graphics == "iterm"  # iTerm2 has sixel too: its own first
    choice = choose("auto", parse(b""), Place())
    assert choice.graphics == "halfblocks" and "did not answer within 2 s" in choice.reason


@pytest.mark.parametrize("terminal, asked, why", [
    ("xterm", "sixel", "do not include 4, sixel (xterm draws sixel as a VT340: xterm -ti "
                       "vt340): half-blocks"),
    ("vte", "kitty", "the terminal did not answer kitty's graphics query: half-blocks"),
])
def test_a_protocol_the_terminal_answers_it_lacks_is_not_sent_blank(terminal, asked, why):
    choice = choose(asked, answers_of(terminal), Place())
    assert choice.graphics == "halfblocks" and choice.reason.endswith(why)
    assert notice(asked, choice).startswith(f"Half-blocks: {asked} was asked, but")


def test_a_protocol_asked_by_name_is_used_where_nothing_says_it_is_not_there():
    # The user knows best: their terminal may not answer the questions (an old WezTerm).
    assert choose("iterm", answers_of("xterm"), Place()).graphics == "iterm"
    assert choose("sixel", parse(b""), Place()).graphics == "sixel"


def test_half_blocks_by_default_and_a_hint_once_when_the_terminal_has_more():
    choice = choose("halfblocks", answers_of("kitty"), Place())
    assert choice.graphics == "halfblocks" and choice.could == "kitty"
    assert hint(choice) == ("This terminal can show real pixels (kitty): start biceps with "
                            "--graphics kitty, or set graphics = \"kitty\" under [render] in "
                            "the config.")
    vte = choose("halfblocks", answers_of("vte"), Place())
    assert hint(vte).startswith("This terminal can show finer cells (sextants)")
    assert hint(choose("halfblocks", answers_of("alacritty"), Place())) is None


def test_sixel_within_the_terminals_limits():
    answers = parse(FIRST["vt340"] + SECOND["vt340"] + b"\x1b[4;1000;1600t", 0.002,
                    (160, 48, 1600, 1000), True)
    choice = choose("auto", answers, Place())
    assert choice.sixel_limit == (1000, 1000)
    assert any("at most 1000x1000 pixels" in note for note in choice.notes)
    encoder = encoder_for(choice)
    assert isinstance(encoder, Sixel) and encoder.limit == (1000, 1000)
    few = parse(FIRST["vt340"].replace(b"256S", b"16S"), 0.01)
    choice = choose("sixel", few, Place())
    assert choice.colours == 16 and encoder_for(choice).colours == 16
    assert any("numColorRegisters" in note for note in choice.notes)
    assert encoder_for(choose("sixel", answers_of("mlterm"), Place())).colours == 256


KITTY_TMUX = dict(multiplexer="tmux", outer_terminal="xterm-kitty", passthrough=True)


def test_inside_tmux_kitty_placeholders_only_from_kitty_028():
    tmux = answers_of("tmux")
    old = choose("auto", tmux, Place(outer_version="kitty(0.26.5)", **KITTY_TMUX))
    # No images: the finer cells kitty draws itself, and why no images.
    assert old.graphics == "sextants"
    assert "in kitty(0.26.5), older than kitty 0.28, whose Unicode placeholders" in old.reason
    asked = choose("kitty", tmux, Place(outer_version="kitty(0.26.5)", **KITTY_TMUX))
    assert asked.graphics == "halfblocks" and "older than kitty 0.28" in asked.reason
    new = choose("auto", tmux, Place(outer_version="kitty(0.35.2)", **KITTY_TMUX))
    assert new.graphics == "kitty" and new.multiplexer == "tmux"
    assert isinstance(encoder_for(new), KittyPlaceholders)
    closed = choose("auto", tmux, Place(multiplexer="tmux", outer_terminal="xterm-kitty",
                                        outer_version="kitty(0.35.2)"))
    assert closed.graphics == "sextants" and "tmux set -g allow-passthrough on" in closed.reason


def test_inside_tmux_sixel_when_tmux_draws_it_and_nothing_it_cannot_place():
    tmux = Place(multiplexer="tmux", outer_terminal="xterm-256color")
    drawing = parse(b"\x1bP>|tmux 3.4\x1b\\\x1b[?1;2;4c", 0.01)
    assert choose("auto", drawing, tmux).graphics == "sixel"
    choice = choose("auto", answers_of("tmux"), tmux)
    assert choice.graphics == "halfblocks"
    assert "inside tmux (in xterm-256color), which does not draw sixel" in choice.reason
    asked = choose("iterm", answers_of("tmux"), tmux)
    assert asked.graphics == "halfblocks" and asked.reason.startswith("iterm was asked, but")


@pytest.mark.parametrize("term", ["tmux-256color", "screen-256color"])
def test_tmux_over_ssh_is_known_by_its_answers(term):
    # (an older tmux, or a tmux.conf, may name its terminal screen)
    place = Place(multiplexer="screen" if term.startswith("screen") else None, term=term)
    choice = choose("auto", answers_of("tmux"), place)
    assert choice.graphics == "halfblocks"
    assert "from another machine (over SSH): which terminal is behind it" in choice.reason
    assert colours("auto", answers_of("tmux"), place, {}).system == "truecolor"


def test_inside_screen_text():
    choice = choose("sixel", answers_of("vt340"), Place(multiplexer="screen"))
    assert choice.graphics == "halfblocks" and "GNU screen" in choice.reason


@pytest.mark.parametrize("answers, cell", [
    (Answers(cell=(9, 18), window=(900, 720), size=(100, 40, 1000, 800)), (9, 18)),
    (Answers(window=(900, 720), size=(100, 40, 0, 0)), (9, 18)),
    (Answers(size=(100, 40, 700, 600)), (7, 15)),  # the kernel's (xterm keeps it)
    (Answers(size=(100, 40, 0, 0)), (10, 20)),
    # A pseudo-terminal nobody sized (script into a pipe) says 0 by 0 cells.
    (Answers(window=(900, 720), size=(0, 0, 0, 0)), (10, 20)),
    (Answers(size=(0, 0, 700, 600)), (10, 20)),
])
def test_the_cell_size_from_the_best_source_there_is(answers, cell):
    assert choose("sixel", answers, Place()).cell == cell


def test_the_encoder_for_each_choice():
    answers = Answers(cell=(9, 20))  # (no answer says any is missing)
    encoders = {name: encoder_for(choose(name, answers, Place()), 0.5)
                for name in ("kitty", "sixel", "iterm", "halfblocks", "sextants")}
    assert isinstance(encoders["kitty"], KittyGraphics) and encoders["kitty"].cell == Size(4, 10)
    assert isinstance(encoders["iterm"], ItermImages) and encoders["iterm"].cell == Size(4, 10)
    # Sixel cannot be scaled up by the terminal: always the terminal's own pixels.
    assert isinstance(encoders["sixel"], Sixel) and encoders["sixel"].cell == Size(9, 20)
    assert isinstance(encoders["halfblocks"], HalfBlocks)
    sextants = encoders["sextants"]
    assert isinstance(sextants, TextCells) and sextants.shape == SEXTANTS
    assert sextants.aspect == pytest.approx((9 / 2) / (20 / 3))  # kitty's cell, in six


@pytest.mark.parametrize("terminal, place, environ, system, said", [
    ("xterm", Place(), {}, "truecolor", "read back a 24-bit colour (DECRQSS)"),
    ("kitty", Place(), {}, "truecolor", "read back a 24-bit colour"),
    ("mlterm", Place(), {"COLORTERM": "truecolor"}, "256", "as one of its palette"),
    ("vte", Place(), {"COLORTERM": "truecolor"}, "truecolor", "COLORTERM=truecolor"),
    ("alacritty", Place(), {}, "256", "COLORTERM is unset (--colors truecolor if"),
    # tmux over SSH: no variable says it, tmux answers no colour question for the terminal.
    ("tmux", Place(), {}, "truecolor", "tmux 3.2 and later send 24-bit colour"),
    ("tmux", Place(multiplexer="tmux", outer_terminal="xterm",
                   outer_features=frozenset({"256", "RGB", "title"})), {}, "truecolor",
     "tmux sends xterm 24-bit colour (its RGB feature)"),
    ("tmux", Place(multiplexer="tmux", outer_terminal="xterm-256color",
                   outer_features=frozenset({"256", "title"})), {}, "256",
     "tmux sends xterm-256color 256 colours"),
    ("xterm", Place(multiplexer="screen"), {"COLORTERM": "truecolor"}, "256", "GNU screen"),
    ("xterm", Place(), {"TEXTUAL_COLOR_SYSTEM": "256"}, "256", "TEXTUAL_COLOR_SYSTEM=256"),
])
def test_the_colours_are_what_the_terminal_keeps(terminal, place, environ, system, said):
    chosen = colours("auto", answers_of(terminal), place, environ)
    assert chosen.system == system and said in chosen.reason


def test_colours_asked_win_and_none_are_fewer_than_256():
    assert colours("256", answers_of("kitty"), Place(), {}).system == "256"
    assert colours("truecolor", None, Place(), {}).system == "truecolor"
    assert colours("auto", None, Place(), {"TERM": "xterm"}).system == "256"


def test_the_doctors_report_says_what_came_back_and_why():
    answers = parse(FIRST["vt340"] + SECOND["vt340"], 0.0032, (100, 30, 1000, 600), True)
    place = Place(term="xterm", colorterm="")
    text = report("auto", answers, place, choose("auto", answers, place),
                  colours("auto", answers, place, {}))
    assert "XTerm(379) (TERM=xterm)" in text
    assert "multiplexer     none" in text
    assert "round trip      3.2 ms" in text
    assert ("sixel           yes (device attributes 63;1;2;4;6;9;15;16;22;28), 256 colour "
            "registers, at most 1000x1000 pixels") in text
    assert "cell size       10x20 pixels" in text
    assert "colours         24-bit: it read back a 24-bit colour (DECRQSS)" in text
    assert "graphics        sixel: auto: the terminal's device attributes include 4" in text
    nothing = report("auto", None, place, choose("auto", None, place),
                     colours("auto", None, place, {}))
    assert "no terminal to ask" in nothing


def test_the_doctor_inside_tmux_over_ssh_says_so_on_every_line():
    # Its answers came from tmux, but no variable says tmux is there: each line agrees.
    answers, place = parse(FIRST["tmux"], 0.02, (80, 24, 0, 0)), Place(term="tmux-256color")
    text = report("auto", answers, place, choose("auto", answers, place),
                  colours("auto", answers, place, {}))
    assert ("terminal        behind the multiplexer, which cannot say which (tmux 3.3a "
            "answered for it; TERM=tmux-256color)") in text
    assert "multiplexer     tmux (it answered as tmux 3.3a; its variables are not here" in text
    assert "kitty graphics  not asked (tmux would take the question for a title)" in text
    assert "colours         24-bit: tmux 3.3a answered" in text


def test_tmux_is_found_by_its_variable_and_asked_about_the_terminal_behind_it(monkeypatch):
    said = {("display-message", "-p",
             "#{client_termname}|#{client_termtype}|#{client_termfeatures}"):
            "xterm-kitty|kitty(0.26.5)|256,RGB,title",
            ("show-options", "-gv", "allow-passthrough"): "on"}
    monkeypatch.setattr(detect, "_tmux", lambda *arguments: said[arguments])
    assert Place.here({"TMUX": "/tmp/tmux-0/default,1,0", "TERM": "tmux-256color"}) == Place(
        "tmux", "xterm-kitty", "kitty(0.26.5)", frozenset({"256", "RGB", "title"}),
        "tmux-256color", "", "", True)
    assert Place.here({"STY": "1.pts-0.host"}).multiplexer == "screen"
    assert Place.here({"TERM": "screen.xterm-256color"}).multiplexer == "screen"
    assert Place.here({"TERM_PROGRAM": "WezTerm"}).terminal_program == "WezTerm"
    assert Place.here({"VTE_VERSION": "7006"}).vte
