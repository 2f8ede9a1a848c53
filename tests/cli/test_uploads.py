"""A visitor's uploads under ``biceps serve`` (biceps/uploads.py): what is refused and why,
and that nothing is written outside the visitor's folder, nor half a file inside it."""

import os

import pytest

from biceps.engine.config import BUNDLED, LARGEST_FILE
from biceps.uploads import MOST_UPLOADS, UploadRefused, save_upload, upload_name

MODEL = (BUNDLED / "toy.toml").read_bytes()


@pytest.fixture
def folder(tmp_path):
    own = tmp_path / "visitor"
    own.mkdir()
    return own


def _everything(root) -> set[str]:
    return {str(path.relative_to(root)) for path in root.rglob("*")}


def test_a_model_is_written_into_the_folder_whole(folder):
    assert save_upload(folder, "mine.toml", MODEL) is False
    assert (folder / "mine.toml").read_bytes() == MODEL
    assert _everything(folder) == {"mine.toml"}  # no temporary file left


def test_a_second_upload_of_a_name_replaces_the_first(folder):
    save_upload(folder, "mine.toml", b"# first\n")
    assert save_upload(folder, "mine.toml", MODEL) is True
    assert (folder / "mine.toml").read_bytes() == MODEL


@pytest.mark.parametrize("name, reason", [
    ("../mine.toml", "not a path"),
    ("/tmp/mine.toml", "not a path"),
    ("sub/mine.toml", "not a path"),
    ("..\\mine.toml", "not a path"),
    ("..", "start with '.'"),
    (".hidden.toml", "start with '.'"),
    (" mine.toml", "start with '.' or a space"),
    ("mine\x1b[2J.toml", "control characters"),
    ("mine\x00.toml", "control characters"),
    ("", "has no name"),
    ("a" * 300 + ".toml", "longer than 255 bytes"),
    ("picture.png", "is not a model"),
    (".toml", "start with '.'"),
    ("mine.toml.exe", "is not a model"),
])
def test_a_bad_name_is_refused_and_nothing_is_written(tmp_path, folder, name, reason):
    before = _everything(tmp_path)
    with pytest.raises(UploadRefused, match=reason.replace(".", r"\.").replace("(", r"\(")):
        save_upload(folder, name, MODEL)
    assert _everything(tmp_path) == before


def test_names_as_browsers_give_them_are_kept():
    for name in ("My model (2).toml", "élbow.TOML", "arm-26_v3.toml"):
        assert upload_name(name) == name


def test_a_file_too_large_is_refused(folder):
    with pytest.raises(UploadRefused, match="larger than 1 MiB") as refusal:
        save_upload(folder, "big.toml", b"#" * (LARGEST_FILE + 1))
    assert refusal.value.status == 413
    assert not any(folder.iterdir())


def test_a_file_that_is_not_text_is_refused(folder):
    with pytest.raises(UploadRefused, match=r"mine\.toml is not a model: it is not a text file "
                                            r"\(byte 3 is not UTF-8\)"):
        save_upload(folder, "mine.toml", b"abc\xff\xfe")
    assert not any(folder.iterdir())


def test_a_link_of_that_name_is_not_written_through(tmp_path, folder):
    secret = tmp_path / "secret.toml"
    secret.write_bytes(b"# the server's\n")
    (folder / "link.toml").symlink_to(secret)
    (folder / "sub.toml").mkdir()
    for name in ("link.toml", "sub.toml"):
        with pytest.raises(UploadRefused, match="is in your folder already, and is not a file"):
            save_upload(folder, name, MODEL)
    assert secret.read_bytes() == b"# the server's\n"
    assert (folder / "link.toml").is_symlink()


def test_a_folder_holds_a_bounded_number_of_models(folder):
    for number in range(MOST_UPLOADS):
        save_upload(folder, f"m{number}.toml", MODEL)
    with pytest.raises(UploadRefused, match=f"holds {MOST_UPLOADS} models already") as refusal:
        save_upload(folder, "one-more.toml", MODEL)
    assert refusal.value.status == 409
    assert save_upload(folder, "m0.toml", MODEL) is True  # replacing one is still allowed


def test_a_failed_write_leaves_no_temporary_file(folder, monkeypatch):
    def fail(*args):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OSError):
        save_upload(folder, "mine.toml", MODEL)
    assert not any(folder.iterdir())
