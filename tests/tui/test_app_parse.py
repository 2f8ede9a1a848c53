"""What people type into the dialogs is read, or refused with a reason."""

from pathlib import Path

import pytest

from biceps.engine.export import parse_size
from biceps.tui.parse import parse_number, parse_path
from biceps.tui.suggest import PathSuggester


@pytest.mark.parametrize("text, value", [("2", 2.0), (" 0.35 ", 0.35), ("1e-1", 0.1), ("-3", -3.0)])
def test_numbers(text, value):
    assert parse_number(text) == value


@pytest.mark.parametrize("text", ["", "abc", "1,5", "nan", "inf", "2 cm"])
def test_not_numbers(text):
    with pytest.raises(ValueError):
        parse_number(text)


@pytest.mark.parametrize("text, size", [("1920x1080", (1920, 1080)), (" 800 × 600 ", (800, 600)),
                                        ("64,48", (64, 48)), ("10X20", (10, 20))])
def test_sizes(text, size):
    assert parse_size(text) == size


@pytest.mark.parametrize("text, reason", [("big", "not a size"), ("0x100", "1 to 8192"),
                                          ("100000x10", "1 to 8192"), ("-5x5", "not a size")])
def test_not_sizes(text, reason):
    with pytest.raises(ValueError, match=reason):
        parse_size(text)


def test_a_path_expands_the_home_directory():
    assert parse_path("~/x.toml") == Path.home() / "x.toml"


@pytest.mark.parametrize("text, reason", [
    ("  ", "give a file name"),
    (".", "is a directory"),
    ("~nosuchuser/x.toml", "there is no user 'nosuchuser' for ~nosuchuser to stand for"),
    ("x" * 256 + ".toml", "the name is 261 bytes long; a file name here has at most 255"),
])
def test_not_paths(text, reason):
    with pytest.raises(ValueError, match=reason):
        parse_path(text)


async def test_file_names_are_completed_from_their_directory(tmp_path):
    (tmp_path / "biceps.toml").write_text("")
    (tmp_path / "biceps.png").write_text("")
    (tmp_path / "configs").mkdir()
    suggester = PathSuggester((".toml",))
    assert await suggester.get_suggestion(f"{tmp_path}/bi") == f"{tmp_path}/biceps.toml"
    assert await suggester.get_suggestion(f"{tmp_path}/co") == f"{tmp_path}/configs/"
    assert await suggester.get_suggestion(f"{tmp_path}/none/x") is None
    assert await suggester.get_suggestion("~nosuchuser/x") is None
