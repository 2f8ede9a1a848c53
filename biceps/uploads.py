"""A visitor's uploads under ``biceps serve``: a model from the visitor's own computer, put
into its own folder on the server, where the app's open dialog finds it.

Free of the web server, so that what is refused, and why, is tested on its own: a name that
is a path, hidden or unprintable; a file that is not a model (a TOML text file, ``.toml``);
one larger than a configuration may be; one more than :data:`MOST_UPLOADS`. A file is
written to a temporary name beside its place, then renamed over it, so the app never reads
half of one; a name already in the folder as a link or a folder is refused, and the rename
never writes through a link.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from biceps.engine.config import LARGEST_FILE
from biceps.engine.names import printable
from biceps.tui.visitor import models_in

SUFFIX = ".toml"
LONGEST_NAME = 255  # bytes: most file systems' limit
MOST_UPLOADS = 50
"""Models at most in a visitor's folder: uploads, and saved copies, which are models too."""


class UploadRefused(ValueError):
    """An upload that was not written, with the reason to show to the visitor; ``status``
    is the HTTP status that says so."""

    def __init__(self, message: str, status: int = 400) -> None:
        super().__init__(message)
        self.status = status


def upload_name(name: str) -> str:
    """``name``, the file's name as the browser sent it, if it may be a model's name in a
    visitor's folder; raises :class:`UploadRefused` saying why not."""
    shown = printable(name)
    if not name.strip():
        raise UploadRefused("the file has no name: give it one ending in .toml")
    if "/" in name or "\\" in name:
        raise UploadRefused(f"{shown}: send a file's name, not a path")
    if not name.isprintable():
        raise UploadRefused(f"{shown}: a name may not hold control characters; rename the file")
    if name.startswith(".") or name != name.strip():
        raise UploadRefused(f"{shown}: a name may not start with '.' or a space, nor end "
                            "with a space; rename the file")
    if len(os.fsencode(name)) > LONGEST_NAME:
        raise UploadRefused(f"{printable(name[:20])}...: the name is longer than "
                            f"{LONGEST_NAME} bytes; rename the file")
    if not name.lower().endswith(SUFFIX) or name.lower() == SUFFIX:
        raise UploadRefused(f"{shown} is not a model: a model is a TOML configuration file, "
                            f"its name ending in {SUFFIX}")
    return name


def check_size(size: int) -> None:
    """Refuse an upload of ``size`` bytes larger than a configuration may be."""
    if size > LARGEST_FILE:
        raise UploadRefused(f"the file is larger than {LARGEST_FILE >> 20} MiB, too large to "
                            "be a model", status=413)


def save_upload(folder: Path, name: str, data: bytes) -> bool:
    """Write ``data`` as the model ``name`` (checked by :func:`upload_name`) into ``folder``;
    True if it replaced an earlier file of that name. Raises :class:`UploadRefused` for a
    file that is not text, too large, or one model too many, and writes nothing then."""
    check_size(len(data))
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise UploadRefused(f"{printable(name)} is not a model: it is not a text file (byte "
                            f"{error.start} is not UTF-8); a model is a TOML text file") from None
    target = folder / upload_name(name)
    replaces = os.path.lexists(target)
    if replaces and (target.is_symlink() or not target.is_file()):
        raise UploadRefused(f"{printable(name)} is in your folder already, and is not a "
                            "file: rename yours to upload it")
    if not replaces and len(models_in(folder)) >= MOST_UPLOADS:
        raise UploadRefused(f"your folder holds {MOST_UPLOADS} models already, the most it "
                            "may", status=409)
    handle, temporary = tempfile.mkstemp(prefix=".upload-", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return replaces
