"""The report of an error the app did not expect: its traceback, kept in a file to send.

Textual prints the traceback as the app ends, at the terminal's width, which a storm of
resizes may have left one column wide; and a terminal's scrollback rarely survives long
enough to be copied. So the app also keeps it, with what is needed to make sense of it
(versions, the terminal, the model), in a file under ``$XDG_STATE_HOME/biceps/``
(``~/.local/state/biceps/`` when unset), and its last line names the file.
"""

from __future__ import annotations

import io
import os
import platform
import shutil
import traceback
from datetime import datetime, timezone
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from rich.console import Console, RenderableType

from biceps.engine.errors import FileError
from biceps.engine.files import write_atomically

KEPT = 20  # the newest reports kept; older ones are removed as a new one is written

# What says which terminal the app ran in, and through what.
_TERMINAL_VARIABLES = ("TERM", "COLORTERM", "TERM_PROGRAM", "TERM_PROGRAM_VERSION", "TMUX",
                       "STY", "SSH_CONNECTION")


def traceback_of(error: BaseException) -> str:
    return "".join(traceback.format_exception(error))


def text_of(renderables: tuple[RenderableType, ...]) -> str:
    """Rich renderables (what Textual hands to ``App.panic``: a traceback, mostly) as plain
    text, at a width that keeps a traceback readable whatever the terminal's is."""
    console = Console(file=io.StringIO(), width=120, color_system=None, legacy_windows=False)
    for renderable in renderables:
        console.print(renderable)
    return console.file.getvalue()


def crash_folder() -> Path:
    # The XDG base directory specification: a relative path in the variable is ignored.
    state = os.environ.get("XDG_STATE_HOME", "")
    base = Path(state) if os.path.isabs(state) else Path.home() / ".local" / "state"
    return base / "biceps"


def write_crash_report(details: str, model: Path | None, **facts: str) -> Path | None:
    """Write ``details`` (a traceback), with the versions, the terminal, the ``model``'s
    path and ``facts`` about the run, to a new report; its path, or None if it could not be
    written (a read-only home, a full disk: the caller then says the details are above)."""
    now = datetime.now(timezone.utc)
    lines = [f"biceps crash report, {now:%Y-%m-%d %H:%M:%S} UTC", "",
             f"biceps {_version('biceps')}, Textual {_version('textual')}, "
             f"Python {platform.python_version()}, {platform.platform()}",
             f"terminal: {_terminal()}",
             f"model: {model if model is not None else '(none)'}"]
    lines += [f"{name}: {value}" for name, value in facts.items()]
    report = "\n".join(lines) + "\n\n" + details
    folder = crash_folder()
    path = folder / f"crash-{now:%Y%m%d-%H%M%S}-{os.getpid()}.txt"
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        write_atomically(path, report.encode("utf-8", "backslashreplace"))
    except (OSError, FileError):
        return None
    _keep_newest(folder)
    return path


def _version(package: str) -> str:
    try:
        return version(package)
    except PackageNotFoundError:
        return "(not installed)"


def _terminal() -> str:
    size = shutil.get_terminal_size(fallback=(0, 0))
    variables = [f"{name}={os.environ[name]!r}" for name in _TERMINAL_VARIABLES
                 if name in os.environ]
    shown = f"{size.columns}x{size.lines}" if size.columns else "size unknown"
    return ", ".join([shown, *variables])


def _keep_newest(folder: Path) -> None:
    # The names sort by time (and a report of the same second by process).
    for old in sorted(folder.glob("crash-*.txt"))[:-KEPT]:
        try:
            old.unlink(missing_ok=True)
        except OSError:
            pass  # another's file, say: it stays
