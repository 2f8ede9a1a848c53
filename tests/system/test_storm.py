"""A few seconds of a storm (tests/storm.py) on the real app, one seed a bundled model, one
in a raw pseudo-terminal and the other in tmux: alive after it, quit with q (and no to
saving) with exit 0, the model file as it was. benchmarks/storm.py runs the long form
(60 s, five seeds, each model in both)."""

import os
import shutil

import pytest
from storm import run_storm

from biceps.configs import FOLDER

SECONDS = 4.0


@pytest.mark.parametrize("harness, model, seed", [("pty", "biceps.toml", 101),
                                                   ("tmux", "elbow.toml", 202)])
def test_the_app_lives_through_a_storm_and_quits_as_asked(private_path, tmp_path, harness,
                                                          model, seed):
    # On the private path: a storm's bytes that are not UTF-8 and pastes that never end are
    # read leniently only through Textual's internals (tui/textual_private.py); on the
    # public path the first such byte ends the app, as Textual's own reading does.
    if harness == "tmux" and shutil.which("tmux") is None:
        if os.environ.get("CI"):
            pytest.fail("tmux is missing: .ci/run installs it")
        pytest.skip("needs tmux")
    outcome = run_storm(harness, FOLDER / model, tmp_path, SECONDS, seed)
    assert sum(outcome.sent.values()) > 0
    assert outcome.alive_after, outcome.shown_at_the_end
    assert outcome.quit_seconds is not None, (outcome.shown_at_the_end
                                              + "\nThe app's threads:\n" + outcome.stacks)
    assert outcome.exit_status == 0, outcome.shown_at_the_end
    assert outcome.model_untouched
