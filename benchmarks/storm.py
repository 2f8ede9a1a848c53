"""Storms of what a terminal sends (``tests/storm.py``) on the real app: keys, pastes with
control characters, invalid UTF-8, broken sequences, mouse reports and resizes, then the app
quit as a person quits it. Each run says whether the app was alive after the storm, how it
ended (``q`` and "n" to saving must end it with 0), how long quitting took and whether the
model file was left as it was; at the end, the tally.

    .venv/bin/python benchmarks/storm.py [--seconds 60] [--seeds 5] [--harness pty,tmux]
                                         [--models configs/biceps.toml,configs/elbow.toml]
                                         [--folder /tmp/storms]

The suite runs a few seconds of the same storm, one seed a model (tests/system/test_storm.py);
this is the long form, run by hand.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from storm import run_storm  # noqa: E402  (tests/ is where the storm is kept)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--harness", default="pty,tmux")
    parser.add_argument("--models", default="configs/biceps.toml,configs/elbow.toml")
    parser.add_argument("--folder", type=Path, default=None,
                        help="where each run's copy of the model is kept (a temporary folder)")
    options = parser.parse_args()
    folder = options.folder or Path(tempfile.mkdtemp(prefix="storms-"))
    passed = total = 0
    for harness in options.harness.split(","):
        for model in options.models.split(","):
            model_path = (ROOT / model).resolve()
            for seed in range(options.first_seed, options.first_seed + options.seeds):
                run_folder = folder / f"{harness}-{model_path.stem}-{seed}"
                run_folder.mkdir(parents=True)
                start = time.monotonic()
                outcome = run_storm(harness, model_path, run_folder, options.seconds, seed)
                total += 1
                passed += outcome.passed
                quit_in = ("did not quit" if outcome.quit_seconds is None
                           else f"quit in {outcome.quit_seconds:.1f} s")
                print(f"{harness:4} {model_path.name:11} seed {seed}: "
                      f"{'ok  ' if outcome.passed else 'FAIL'} alive after: "
                      f"{outcome.alive_after}, exit {outcome.exit_status}, {quit_in}, model "
                      f"{'untouched' if outcome.model_untouched else 'CHANGED'}, "
                      f"{outcome.quits_held} quits held; "
                      f"{time.monotonic() - start:.0f} s; sent "
                      + ", ".join(f"{count} {kind}" for kind, count in
                                  sorted(outcome.sent.items())), flush=True)
                if not outcome.passed:
                    print("  shown at the end:", repr(outcome.shown_at_the_end[-1500:]),
                          flush=True)
                    if outcome.stacks:
                        print("  the app's threads:\n" + outcome.stacks, flush=True)
    print(f"{passed} of {total} runs passed")
    return 0 if passed == total else 1


if __name__ == "__main__":
    sys.exit(main())
