"""A user's files: saving respects the file (its link, its permissions, its owner, and what
someone else wrote into it since), and reading refuses what is not a regular file."""

import os
import re
import stat
from pathlib import Path

import pytest

from biceps.engine.config import load_config, save_config
from biceps.engine.errors import FileChanged, FileError
from biceps.engine.files import read_regular_file, write_atomically

AS_ROOT = pytest.mark.skipif(os.geteuid() != 0, reason="only root can give a file to another "
                                                        "user, to see whose it stays")
SOMEONE_ELSE = 65534  # nobody


def _contract_and_save(path: Path, **options) -> None:
    config = load_config(path)
    save_config(config, config.arm.at_length(30.0), config.view, config.light, config.render,
                **options)


def test_saving_through_a_link_replaces_the_file_it_points_to_and_keeps_the_link(config_path):
    link = config_path.parent / "link.toml"
    link.symlink_to(config_path.name)
    _contract_and_save(link)
    assert link.is_symlink() and os.readlink(link) == config_path.name
    assert load_config(config_path).arm.length == 30.0
    assert sorted(p.name for p in config_path.parent.iterdir()) == ["biceps.toml", "link.toml"]


def test_a_read_only_file_is_not_replaced(config_path):
    before = config_path.read_bytes()
    config_path.chmod(0o444)
    with pytest.raises(FileError, match="biceps.toml: is read-only; nothing was written"):
        _contract_and_save(config_path)
    assert config_path.read_bytes() == before
    assert stat.S_IMODE(config_path.stat().st_mode) == 0o444
    assert [p.name for p in config_path.parent.iterdir()] == ["biceps.toml"]


def test_a_file_changed_on_disk_since_it_was_read_is_not_overwritten(config_path):
    config = load_config(config_path)
    theirs = config_path.read_text().replace("length = 33.0", "length = 34.0")
    config_path.write_text(theirs)
    with pytest.raises(FileChanged, match="biceps.toml: changed on disk since it was read"):
        save_config(config, config.arm.at_length(30.0), config.view, config.light, config.render)
    assert config_path.read_text() == theirs
    save_config(config, config.arm.at_length(30.0), config.view, config.light, config.render,
                overwrite=True)
    assert load_config(config_path).arm.length == 30.0


def test_saving_twice_is_not_a_change_on_disk(config_path):
    config = load_config(config_path)
    saved = save_config(config, config.arm.at_length(30.0), config.view, config.light,
                        config.render)
    save_config(saved, saved.arm.at_length(31.0), saved.view, saved.light, saved.render)
    assert load_config(config_path).arm.length == 31.0


@AS_ROOT
def test_a_file_of_another_user_stays_theirs(config_path):
    os.chown(config_path, SOMEONE_ELSE, SOMEONE_ELSE)
    _contract_and_save(config_path)
    status = config_path.stat()
    assert (status.st_uid, status.st_gid) == (SOMEONE_ELSE, SOMEONE_ELSE)
    assert load_config(config_path).arm.length == 30.0


@AS_ROOT
def test_a_file_whose_owner_could_not_be_kept_is_not_replaced(config_path, monkeypatch):
    os.chown(config_path, SOMEONE_ELSE, SOMEONE_ELSE)
    before = config_path.read_bytes()

    def refused(*args):
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "chown", refused)  # as for anyone but root
    with pytest.raises(FileError, match=f"belongs to user {SOMEONE_ELSE}, group "
                                        f"{SOMEONE_ELSE}; replacing it would make it yours"):
        _contract_and_save(config_path)
    assert config_path.read_bytes() == before
    assert [p.name for p in config_path.parent.iterdir()] == ["biceps.toml"]


def test_a_pipe_is_not_written_into(tmp_path):
    pipe = tmp_path / "pipe.toml"
    os.mkfifo(pipe)
    with pytest.raises(FileError, match="pipe.toml: is a pipe \\(FIFO\\), not a regular file"):
        write_atomically(pipe, b"x")
    assert stat.S_ISFIFO(pipe.stat().st_mode)


def test_a_name_too_long_is_refused_before_anything_is_written(tmp_path):
    with pytest.raises(FileError, match="the name is 300 bytes long; a file name here has at "
                                        "most 255"):
        write_atomically(tmp_path / ("x" * 300), b"x")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("parts, message", [
    (["x" * 256, "f"], "the folder name xxxxxxxxxxxxxxxxxxxx... is 256 bytes long; a file name "
                       "here has at most 255"),
    (["ab"] * 1400, "the path is 4,"),
])
def test_a_folder_named_too_long_or_a_path_too_long_is_refused(tmp_path, parts, message):
    with pytest.raises(FileError, match=re.escape(message)):
        write_atomically(tmp_path.joinpath(*parts), b"x")
    with pytest.raises(FileError, match=re.escape(message)):
        read_regular_file(tmp_path.joinpath(*parts), 1000)


@pytest.mark.parametrize("size", [0, 10, 1000])
def test_a_regular_file_is_read_whole_up_to_the_limit(tmp_path, size):
    path = tmp_path / "f"
    path.write_bytes(b"a" * size)
    assert read_regular_file(path, 1000) == b"a" * size


def test_a_file_one_byte_over_the_limit_is_refused(tmp_path):
    path = tmp_path / "f"
    path.write_bytes(b"a" * 1001)
    with pytest.raises(FileError, match="f: is larger than 1,000 bytes"):
        read_regular_file(path, 1000)
