"""``python -m biceps``: the same as the ``biceps`` command."""

from biceps.cli import run

run()
