"""The reference curve: OpenSim's arm26 BIClong, its length and elbow moment arm, from 0 to
130 degrees of elbow flexion, and how far the biceps model's own curve lies from it.

    .venv/bin/pip install -e '.[reference]'   # the opensim package (4.6), about 100 MB
    .venv/bin/python benchmarks/arm26_reference.py [--write]

OpenSim loads ``shared/data/arm26.osim`` headless (it warns that the bone meshes it names
are missing, which does not matter here), sets the shoulder to 0 and the elbow coordinate
``r_elbow_flex`` to every 10 degrees, and asks the muscle for its path length
(``getLength``) and its moment arm about the elbow (``computeMomentArm``). ``--write``
stores the curve as ``engine/data/arm26_biclong.json``, which the tests compare the model
with, so that they need no opensim, and which the app's plots draw beside the model's; and the lengths of all six of arm26's muscles as
``tests/engine/data/arm26_elbow.json``, which ``configs/elbow.toml``'s muscles are compared
with, and prints how far each of those lies from arm26's.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT.parent / "shared" / "data" / "arm26.osim"
OUTPUT = ROOT / "engine" / "data" / "arm26_biclong.json"  # shipped: the app's plots draw it
ELBOW_OUTPUT = ROOT / "tests" / "engine" / "data" / "arm26_elbow.json"
FLEXIONS = list(range(0, 131, 10))
ARM26_MUSCLES = ("BIClong", "BICshort", "BRA", "TRIlong", "TRIlat", "TRImed")
"""arm26's six muscles, named so in configs/elbow.toml too."""


def opensim_curve(model_path: Path) -> dict:
    """BIClong's length and moment arm (mm) at each of ``FLEXIONS`` (degrees)."""
    import opensim

    model = opensim.Model(str(model_path))
    state = model.initSystem()
    elbow = model.getCoordinateSet().get("r_elbow_flex")
    model.getCoordinateSet().get("r_shoulder_elev").setValue(state, 0.0)
    muscle = model.getMuscles().get("BIClong")
    lengths, moment_arms = [], []
    for flexion in FLEXIONS:
        elbow.setValue(state, math.radians(flexion))
        model.realizePosition(state)
        lengths.append(round(1000.0 * muscle.getLength(state), 4))
        moment_arms.append(round(1000.0 * muscle.computeMomentArm(state, elbow), 4))
    return {
        "source": "OpenSim 4.6, arm26.osim, muscle BIClong, shoulder at 0: "
                  "benchmarks/arm26_reference.py --write",
        "flexion_deg": FLEXIONS,
        "length_mm": lengths,
        "moment_arm_mm": moment_arms,
    }


def opensim_lengths(model_path: Path) -> dict:
    """Each of arm26's six muscles' path length (mm) at each of ``FLEXIONS`` (degrees)."""
    import opensim

    model = opensim.Model(str(model_path))
    state = model.initSystem()
    elbow = model.getCoordinateSet().get("r_elbow_flex")
    model.getCoordinateSet().get("r_shoulder_elev").setValue(state, 0.0)
    lengths = {name: [] for name in ARM26_MUSCLES}
    for flexion in FLEXIONS:
        elbow.setValue(state, math.radians(flexion))
        model.realizePosition(state)
        for name in ARM26_MUSCLES:
            lengths[name].append(round(1000.0 * model.getMuscles().get(name).getLength(state), 4))
    return {
        "source": "OpenSim 4.6, arm26.osim, shoulder at 0: benchmarks/arm26_reference.py --write",
        "flexion_deg": FLEXIONS,
        "length_mm": lengths,
    }


def elbow_curves() -> dict[str, list[float]]:
    """configs/elbow.toml's muscles' lengths (mm) at each of ``FLEXIONS``, by name."""
    from biceps.configs import FOLDER
    from biceps.engine.config import load_config

    arm = load_config(FOLDER / "elbow.toml").arm
    curves = {}
    for flexion in FLEXIONS:
        posed = arm.at_flexion(flexion)
        lengths = dict(zip(posed.names, (muscle.length for muscle in posed.muscles)))
        for name in ARM26_MUSCLES:
            curves.setdefault(name, []).append(10.0 * lengths[name])
    return curves


def model_curve() -> tuple[list[float], list[float]]:
    """The default skeleton's muscle length and moment arm (mm) at each of ``FLEXIONS``."""
    from biceps.engine.skeleton import Skeleton

    skeleton = Skeleton()
    lengths = [10.0 * skeleton.length_at(f) for f in FLEXIONS]
    moment_arms = [10.0 * skeleton.moment_arm(f) for f in FLEXIONS]
    return lengths, moment_arms


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help=f"store the curve in {OUTPUT}")
    args = parser.parse_args()
    reference = opensim_curve(MODEL)
    elbow = opensim_lengths(MODEL)
    if args.write:
        OUTPUT.parent.mkdir(parents=True, exist_ok=True)
        OUTPUT.write_text(json.dumps(reference, indent=2) + "\n")
        ELBOW_OUTPUT.write_text(json.dumps(elbow, indent=2) + "\n")
        print(f"wrote {OUTPUT} and {ELBOW_OUTPUT}")
    lengths, moment_arms = model_curve()
    print(f"{'flexion':>8}{'arm26 dL':>10}{'model dL':>10}{'diff':>7}"
          f"{'arm26 r':>10}{'model r':>10}{'diff':>7}   (mm)")
    for i, flexion in enumerate(FLEXIONS):
        their_change = reference["length_mm"][i] - reference["length_mm"][0]
        our_change = lengths[i] - lengths[0]
        their_arm, our_arm = reference["moment_arm_mm"][i], moment_arms[i]
        print(f"{flexion:>8}{their_change:>10.2f}{our_change:>10.2f}"
              f"{our_change - their_change:>7.2f}{their_arm:>10.2f}{our_arm:>10.2f}"
              f"{our_arm - their_arm:>7.2f}")
    print("\nconfigs/elbow.toml against arm26: each muscle's length change from 0 degrees (mm)")
    ours = elbow_curves()
    for name, theirs in elbow["length_mm"].items():
        change = [(o - ours[name][0]) - (t - theirs[0]) for o, t in zip(ours[name], theirs)]
        worst = max(change, key=abs)
        print(f"{name:>9}: arm26 {theirs[-1] - theirs[0]:+7.2f}, model "
              f"{ours[name][-1] - ours[name][0]:+7.2f} over the range; worst difference "
              f"{worst:+.2f} at {FLEXIONS[change.index(worst)]} degrees")


if __name__ == "__main__":
    main()
