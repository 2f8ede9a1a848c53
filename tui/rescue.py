"""After an error nothing caught: the model the app had, and the question offering to save it.

Textual ends an app on such an error, whatever state its screens and message queues are
in. The model itself is an immutable scene, untouched: run_app (tui/app.py) opens it in a
new app, which asks this question first, and the process ends with exit status 1.
"""

from __future__ import annotations

from dataclasses import dataclass

from biceps.engine.config import Config
from biceps.engine.names import printable
from biceps.engine.scene import Scene
from biceps.tui.screens.choice import Answer, Choice


@dataclass(frozen=True)
class Rescue:
    """What an app that ended on an error left: the model as it was, the file it came from
    (and the scene last saved there), and the error, in a line."""

    config: Config
    scene: Scene
    saved: Scene
    error: str


def rescue_question(rescue: Rescue) -> Choice:
    """Says what went wrong; dismissed with "save", "save_as", "quit", or None (escape: go
    on working)."""
    question = (
        f"biceps stopped on an error it did not expect:\n\n{printable(rescue.error)}\n\n"
        f"Your model is as it was, with edits not saved to "
        f"{printable(rescue.config.path.name)}. Save them before you go (escape: keep "
        "working)."
    )
    answers = [
        Answer("s", "Save, quit", "save", "primary"),
        Answer("a", "Save as, quit", "save_as"),
        Answer("q", "Quit, don't save", "quit", "error"),
    ]
    return Choice("biceps ran into an error", question, answers)
