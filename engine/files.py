"""A user's files: read only when they are regular files of a sane size, and written so that
a reader sees the old file or the new one, never half of one, and the file stays the
user's (its link, permissions and owner)."""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from biceps.engine.errors import FileError
from biceps.engine.names import printable

_KINDS = {stat.S_IFDIR: "a directory", stat.S_IFIFO: "a pipe (FIFO)", stat.S_IFSOCK: "a socket",
          stat.S_IFCHR: "a character device", stat.S_IFBLK: "a block device"}


def read_regular_file(path: str | os.PathLike, largest: int) -> bytes:
    """The bytes of the regular file at ``path`` (links followed), at most ``largest``;
    raises :class:`FileError` for anything else: no such file, a directory, a pipe (which
    would wait for a writer for ever), a device (``/dev/zero`` never ends), a file larger
    than ``largest`` bytes."""
    path = Path(path)
    check_name(path)
    try:
        # Non-blocking, so that opening a pipe returns at once instead of waiting for a
        # writer; a regular file reads the same either way.
        handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise FileError(f"{printable(path)}: no such file") from None
    except OSError as error:
        raise FileError(f"{printable(path)}: {_kind_of(path) or error.strerror}") from None
    try:
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode):
            raise FileError(f"{printable(path)}: {_kind(status.st_mode)}")
        data = _read_at_most(handle, largest + 1)  # one more, to see a file that grew
    except OSError as error:
        raise FileError(f"{printable(path)}: cannot be read: {error.strerror}") from None
    finally:
        os.close(handle)
    if len(data) > largest:
        raise FileError(f"{printable(path)}: is larger than {_size(largest)}, too large to be "
                        "a configuration")
    return data


def _read_at_most(handle: int, count: int) -> bytes:
    chunks, left = [], count
    while left > 0:
        chunk = os.read(handle, min(left, 1 << 20))
        if not chunk:
            break
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def _kind(mode: int) -> str:
    return f"is {_KINDS.get(stat.S_IFMT(mode), 'not a regular file')}, not a regular file"


def _kind_of(path: Path) -> str | None:
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return None
    return None if stat.S_ISREG(mode) else _kind(mode)


def _size(count: int) -> str:
    return f"{count / (1 << 20):g} MiB" if count >= 1 << 20 else f"{count:,} bytes"


def check_name(path: Path) -> None:
    """Raise :class:`FileError` if a part of ``path`` (the file's name or a folder's) is
    longer than its file system allows (most allow 255 bytes), or the whole path is longer
    than the system takes one (4,095 bytes on Linux): every later step would fail on it with
    ENAMETOOLONG."""
    folder = "."  # the folder holding ``part``, extended part by part, not rebuilt for each
    for depth, part in enumerate(path.parts):
        length = len(os.fsencode(part))
        longest = _longest_name(folder)
        folder = os.path.join(folder, part) if depth else part
        if length > longest:
            what = "the name" if depth == len(path.parts) - 1 else \
                f"the folder name {printable(_shortened(part))}"
            raise FileError(f"{printable(path)}: {what} is {length:,} bytes long; a file name "
                            f"here has at most {longest}")
    length, longest = len(os.fsencode(path)), _longest_path()
    if length > longest:
        raise FileError(f"{printable(path)}: the path is {length:,} bytes long; a path has at "
                        f"most {longest:,}")


def _longest_name(folder: str) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):  # no such folder (yet), or no such limit
        return 255


def _longest_path() -> int:
    try:
        return os.pathconf("/", "PC_PATH_MAX") - 1  # the limit counts the closing NUL
    except (OSError, ValueError):
        return 4095


def _shortened(name: str) -> str:
    return name if len(name) <= 24 else f"{name[:20]}..."


def same_file(path: str | os.PathLike, other: str | os.PathLike) -> bool:
    """Whether both name one file (through links); False if either is not there."""
    try:
        return os.path.samefile(path, other)
    except OSError:
        return False


def write_atomically(path: str | os.PathLike, data: bytes) -> None:
    """Replace ``path`` with ``data`` atomically, or raise :class:`FileError` and touch nothing.

    Writes a temporary file beside the target (the same file system, so the rename is
    atomic), flushes it to disk, gives it the old file's permissions and owner, then renames
    it over. A symbolic link is followed, so the file it points to is replaced and the
    link stays a link. A read-only file, or one whose owner could not be kept, is refused.
    """
    path = Path(path)
    check_name(path)
    target = Path(os.path.realpath(path))
    existing = _status(path, target)
    try:
        handle, temporary = tempfile.mkstemp(prefix=".biceps-", suffix=".tmp", dir=target.parent)
    except OSError as error:
        raise FileError(f"{printable(path)}: cannot write in {printable(target.parent)}: "
                        f"{error.strerror}") from None
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        _keep_permissions(path, temporary, existing)
        os.replace(temporary, target)
        _flush_folder(target.parent)
    except BaseException as error:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(error, OSError):
            raise FileError(f"{printable(path)}: cannot write: {error.strerror}") from None
        raise


def _status(path: Path, target: Path) -> os.stat_result | None:
    """The target's status, or None if there is none yet; :class:`FileError` if it is not
    a file this may replace."""
    try:
        status = os.stat(target)
    except FileNotFoundError:
        return None
    except OSError as error:
        raise FileError(f"{printable(path)}: cannot write: {error.strerror}") from None
    if not stat.S_ISREG(status.st_mode):
        raise FileError(f"{printable(path)}: {_kind(status.st_mode)}")
    # The write bits, not only access(): root may write anything, but a file marked
    # read-only is still one its owner meant to keep as it is.
    if not status.st_mode & 0o222 or not os.access(target, os.W_OK):
        raise FileError(f"{printable(path)}: is read-only; nothing was written (save a copy "
                        "under another name, or make it writable)")
    return status


def _keep_permissions(path: Path, temporary: str, existing: os.stat_result | None) -> None:
    if existing is None:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        return
    written = os.stat(temporary)
    if (written.st_uid, written.st_gid) != (existing.st_uid, existing.st_gid):
        try:
            os.chown(temporary, existing.st_uid, existing.st_gid)
        except PermissionError:
            raise FileError(
                f"{printable(path)}: belongs to user {existing.st_uid}, group "
                f"{existing.st_gid}; replacing it would make it yours, so nothing was written "
                "(save a copy under another name)"
            ) from None
    os.chmod(temporary, stat.S_IMODE(existing.st_mode))


def _flush_folder(folder: Path) -> None:
    # The rename is one of the folder's entries: flush them too, or a crash could lose it.
    # Best effort: the file is already in place, and some file systems cannot.
    try:
        handle = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(handle)
        finally:
            os.close(handle)
    except OSError:
        pass
