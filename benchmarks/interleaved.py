"""Runs of a benchmark's ``measure()`` in this installation and, optionally, another, in
turns, so that both see the same load on a busy machine.

A script calls :func:`runs` from its ``main()``; run with ``--one-run`` (as :func:`runs`
starts it), the script prints one run's figures as JSON and exits.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from typing import Callable


def runs(script: str, measure: Callable[[], dict[str, float]], description: str,
         default_runs: int) -> tuple[int, dict[str, list[dict[str, float]]]]:
    """The command line's number of runs, and each tree's runs' figures ({name: [figures
    of each run]}: "this tree", then "against" if ``--against PYTHON`` was given); or, with
    ``--one-run``, print ``measure()``'s figures and exit."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--runs", type=int, default=default_runs)
    parser.add_argument("--against", help="the Python of another installation of biceps")
    parser.add_argument("--one-run", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one_run:
        print(json.dumps(measure()))
        raise SystemExit(0)
    pythons = {"this tree": sys.executable}
    if args.against:
        pythons["against"] = args.against
    figures: dict[str, list[dict[str, float]]] = {tree: [] for tree in pythons}
    for _ in range(args.runs):
        for tree, python in pythons.items():
            out = subprocess.run([python, script, "--one-run"], check=True,
                                 capture_output=True, text=True).stdout
            figures[tree].append(json.loads(out.splitlines()[-1]))
    return args.runs, figures
