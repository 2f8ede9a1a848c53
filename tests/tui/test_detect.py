"""What the terminal's answers mean, and what the app chooses from them."""

from __future__ import annotations

import pytest
from textual.geometry import Size

from biceps.tui import detect
from biceps.tui.detect import Answers, Place, choose, colour_system, hint, parse, report
from biceps.tui.halfblocks import HalfBlocks
from biceps.tui.pixels import ItermImages, KittyGraphics, KittyPlaceholders, Sixel, encoder_for

KITTY_ANSWERS = (b"\x1b_Gi=31;OK\x1b\\\x1bP>|kitty(0.26.5)\x1b\\\x1b[6;20;10t"
                 b"\x1b[4;800;1000t\x1b[?62;c")
XTERM_ANSWERS = b"\x1bP>|XTerm(379)\x1b\\\x1b[?1;0;256S\x1b[?63;1;2;4;6;9;15;16;22;28c"
TMUX_SIXEL_ANSWERS = b"\x1bP>|tmux 3.4\x1b\\\x1b[?1;2;4c"


def test_kitty_answers():
    answers = parse(KITTY_ANSWERS, 0.004)
    assert answers == Answers(True, 0.004, ("62", ""), "OK", "kitty(0.26.5)", None, (10, 20),
                              (1000, 800))
    assert not answers.sixel


def test_xterm_answers_sixel_and_its_colour_registers():
    answers = parse(XTERM_ANSWERS, 0.001)
    assert answers.sixel and answers.colour_registers == 256 and answers.kitty is None
    assert answers.name == "XTerm(379)"


def test_no_answer_is_not_taken_for_one():
    answers = parse(b"\x1b_Gi=31;OK\x1b\\", 0.5)  # no device attributes: not in time
    assert not answers.answered and answers.round_trip is None


@pytest.mark.parametrize("data, graphics", [
    (KITTY_ANSWERS, "kitty"),
    (XTERM_ANSWERS, "sixel"),
    (b"\x1bP>|iTerm2 3.5.0\x1b\\\x1b[?62;4c", "iterm"),  # iTerm2 has sixel too: its own first
    (b"\x1b[?62;22c", "halfblocks"),
    (b"", "halfblocks"),
])
def test_auto_takes_the_best_the_terminal_has(data, graphics):
    assert choose("auto", parse(data, 0.01), Place()).graphics == graphics


def test_auto_says_when_the_terminal_did_not_answer():
    choice = choose("auto", parse(b""), Place())
    assert choice.graphics == "halfblocks" and "did not answer within 2 s" in choice.reason


def test_halfblocks_by_default_and_a_hint_once_when_the_terminal_has_more():
    choice = choose("halfblocks", parse(KITTY_ANSWERS, 0.01), Place())
    assert choice.graphics == "halfblocks" and choice.could == "kitty"
    assert hint(choice) == ("This terminal can show real pixels (kitty): start biceps with "
                            "--graphics kitty, or set graphics = \"kitty\" under [render] in "
                            "the config.")
    assert hint(choose("halfblocks", parse(b"\x1b[?62c", 0.01), Place())) is None


def test_inside_tmux_sixel_when_tmux_draws_it():
    tmux = Place(multiplexer="tmux", outer_terminal="xterm-256color")
    assert choose("auto", parse(TMUX_SIXEL_ANSWERS, 0.01), tmux).graphics == "sixel"
    choice = choose("auto", parse(b"\x1b[?1;2c", 0.01), tmux)
    assert choice.graphics == "halfblocks"
    assert "inside tmux (in xterm-256color), which does not draw sixel" in choice.reason
    asked = choose("iterm", parse(b"\x1b[?1;2c", 0.01), tmux)
    assert asked.graphics == "halfblocks" and asked.reason.startswith("iterm was asked, but")


def test_inside_tmux_in_kitty_kitty_through_the_passthrough_when_it_is_on():
    # tmux answers for itself (kitty's query never reaches kitty): tmux names the terminal.
    answers = parse(b"\x1b[?1;2c", 0.01)
    closed = choose("auto", answers, Place(multiplexer="tmux", outer_terminal="xterm-kitty"))
    assert closed.graphics == "halfblocks"
    assert "tmux set -g allow-passthrough on" in closed.reason
    open_ = choose("auto", answers, Place(multiplexer="tmux", outer_terminal="xterm-kitty",
                                          passthrough=True))
    assert open_.graphics == "kitty" and open_.multiplexer == "tmux"
    assert isinstance(encoder_for(open_), KittyPlaceholders)
    assert isinstance(encoder_for(choose("kitty", answers, Place())), KittyGraphics)


def test_inside_screen_half_blocks():
    choice = choose("sixel", parse(XTERM_ANSWERS, 0.01), Place(multiplexer="screen"))
    assert choice.graphics == "halfblocks" and "GNU screen" in choice.reason


def test_a_protocol_asked_by_name_is_used_outside_a_multiplexer():
    # The user knows best: their terminal may not answer the questions (an old WezTerm).
    assert choose("iterm", parse(b"\x1b[?62c", 0.01), Place()).graphics == "iterm"


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


def test_sixel_takes_the_terminals_colour_registers_and_says_when_they_are_few():
    answers = parse(XTERM_ANSWERS.replace(b"256S", b"16S"), 0.01)
    choice = choose("sixel", answers, Place())
    assert choice.colours == 16
    assert any("numColorRegisters" in note for note in choice.notes)
    assert encoder_for(choice).colours == 16


def test_the_encoder_for_each_choice():
    answers = parse(KITTY_ANSWERS, 0.01)
    encoders = {name: encoder_for(choose(name, answers, Place()), 0.5)
                for name in ("kitty", "sixel", "iterm", "halfblocks")}
    assert isinstance(encoders["kitty"], KittyGraphics) and encoders["kitty"].cell == Size(5, 10)
    assert isinstance(encoders["iterm"], ItermImages) and encoders["iterm"].cell == Size(5, 10)
    # Sixel cannot be scaled up by the terminal: always the terminal's own pixels.
    assert isinstance(encoders["sixel"], Sixel) and encoders["sixel"].cell == Size(10, 20)
    assert isinstance(encoders["halfblocks"], HalfBlocks)


def test_the_doctors_report_says_what_came_back_and_why():
    answers = parse(XTERM_ANSWERS, 0.0032, (100, 30, 1000, 600))
    place = Place(term="xterm", colorterm="")
    text = report("auto", answers, place, choose("auto", answers, place))
    assert "XTerm(379) (TERM=xterm)" in text
    assert "round trip      3.2 ms" in text
    assert "sixel           yes (device attributes 63;1;2;4;6;9;15;16;22;28), 256 colour" in text
    assert "cell size       10x20 pixels" in text
    assert "COLORTERM=unset: 256 (start with --colors truecolor" in text
    assert "graphics        sixel: auto: the terminal's device attributes include 4" in text
    assert "no terminal to ask" in report("auto", None, place, choose("auto", None, place))


def test_tmux_is_found_by_its_variable_and_asked_about_itself(monkeypatch):
    said = {("display-message", "-p", "#{client_termname}"): "xterm-kitty",
            ("show-options", "-gv", "allow-passthrough"): "on"}
    monkeypatch.setattr(detect, "_tmux", lambda *arguments: said[arguments])
    assert Place.here({"TMUX": "/tmp/tmux-0/default,1,0", "TERM": "tmux-256color"}) == Place(
        "tmux", "xterm-kitty", "tmux-256color", "", "", True)
    assert Place.here({"STY": "1.pts-0.host"}).multiplexer == "screen"
    assert Place.here({"TERM_PROGRAM": "WezTerm"}).terminal_program == "WezTerm"


@pytest.mark.parametrize("asked, environ, system", [
    ("auto", {"TERM": "xterm"}, "256"),  # Rich reads 16 colours; the muscle would be a stick
    ("auto", {"TERM": "xterm", "COLORTERM": "truecolor"}, "truecolor"),
    ("auto", {"TERM": "xterm-256color"}, "256"),
    ("auto", {"TERM": "xterm", "TEXTUAL_COLOR_SYSTEM": "truecolor"}, "truecolor"),
    ("auto", {}, "256"),
    ("256", {"COLORTERM": "truecolor"}, "256"),  # the command line wins
])
def test_the_colours_are_the_terminals_but_never_fewer_than_256(asked, environ, system):
    assert colour_system(asked, environ) == system
