"""Completing file names, and the bundled models' names, in dialogs, as a shell's tab does
(accept with → or end)."""

from __future__ import annotations

from pathlib import Path

from textual.suggester import Suggester

from biceps.configs import bundled_names
from biceps.tui import visitor


class PathSuggester(Suggester):
    """Suggests the first name in the typed directory that starts with what follows the last /."""

    def __init__(self, suffixes: tuple[str, ...] = ()) -> None:
        # No cache: the directory may change while the dialog is open (an export lands).
        super().__init__(use_cache=False, case_sensitive=True)
        self._suffixes = suffixes

    async def get_suggestion(self, value: str) -> str | None:
        head = value[: value.rfind("/") + 1]
        start = value[len(head) :]
        try:
            visitor.confined(Path(head or "."))  # under biceps serve, no names from elsewhere
        except ValueError:
            return None
        try:
            directory = Path(head).expanduser() if head else Path(".")
            entries = sorted(directory.iterdir())
        except (OSError, RuntimeError):  # no such folder, or ~someone who does not exist
            return None
        for entry in entries:
            name = entry.name
            if not name.startswith(start) or (name.startswith(".") and not start.startswith(".")):
                continue
            try:
                is_dir = entry.is_dir()
            except OSError:
                continue
            if is_dir:
                return f"{head}{name}/"
            if not self._suffixes or entry.suffix.lower() in self._suffixes:
                return f"{head}{name}"
        return None


class ModelSuggester(PathSuggester):
    """Suggests a configuration file, as :class:`PathSuggester` does, or where no file's name
    starts so, a bundled model's name (``el`` -> ``elbow``), as the open dialog reads them
    (``configs/`` before it too)."""

    def __init__(self) -> None:
        super().__init__((".toml",))

    async def get_suggestion(self, value: str) -> str | None:
        found = await super().get_suggestion(value)
        if found is not None:
            return found
        head = "configs/" if value.startswith("configs/") else ""
        start = value[len(head):]
        if not start or "/" in start:
            return None
        return next((f"{head}{name}" for name in bundled_names() if name.startswith(start)),
                    None)
