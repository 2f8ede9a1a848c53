"""The reference curves: OpenSim's arm26 model, its muscles' lengths and elbow moment arms
from 0 to 130 degrees of elbow flexion, and how far the program's own lie from them.

    .venv/bin/pip install -e '.[reference]'   # the opensim package (4.6), about 100 MB
    .venv/bin/python benchmarks/arm26_reference.py [--write]

OpenSim loads ``shared/data/arm26.osim`` headless (it warns that the bone meshes it names
are missing, which does not matter here), sets the shoulder to 0 and the elbow coordinate
``r_elbow_flex`` to each angle, and asks each muscle for its path length (``getLength``),
its moment arm about the elbow (``computeMomentArm``) and the points its path runs through
(``getCurrentPath``). ``--write`` stores BIClong's at every 10 degrees as
``engine/data/arm26_biclong.json``, which the single biceps of ``configs/biceps.toml`` is
compared with and which the app's plots draw beside the model's, and all six muscles' at
every 5 degrees as ``tests/engine/data/arm26_elbow.json``, which the engine's arm26 paths
and ``configs/elbow.toml`` are compared with: so the tests need no opensim. It prints how
far each of the program's curves lies from arm26's.
"""

from __future__ import annotations

import argparse
import json
import math
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT.parent / "shared" / "data" / "arm26.osim"
OUTPUT = ROOT / "engine" / "data" / "arm26_biclong.json"  # shipped: the app's plots draw it
ELBOW_OUTPUT = ROOT / "tests" / "engine" / "data" / "arm26_elbow.json"
FLEXIONS = list(range(0, 131, 10))
ELBOW_FLEXIONS = list(range(0, 131, 5))
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


def opensim_elbow(model_path: Path) -> dict:
    """Each of arm26's six muscles at every ``ELBOW_FLEXIONS`` degrees: its path's length
    and moment arm about the elbow (mm), and the points its path runs through (their names,
    and where they are in mm, in the humerus's frame: arm26's via points, and the tangent
    points where it meets a wrapping surface, named pwpt1 and pwpt2)."""
    import opensim

    model = opensim.Model(str(model_path))
    state = model.initSystem()
    elbow = model.getCoordinateSet().get("r_elbow_flex")
    model.getCoordinateSet().get("r_shoulder_elev").setValue(state, 0.0)
    humerus = model.getBodySet().get("r_humerus")
    lengths = {name: [] for name in ARM26_MUSCLES}
    moment_arms = {name: [] for name in ARM26_MUSCLES}
    paths = {name: [] for name in ARM26_MUSCLES}
    for flexion in ELBOW_FLEXIONS:
        elbow.setValue(state, math.radians(flexion))
        model.realizePosition(state)
        for name in ARM26_MUSCLES:
            muscle = model.getMuscles().get(name)
            lengths[name].append(round(1000.0 * muscle.getLength(state), 4))
            moment_arms[name].append(round(1000.0 * muscle.computeMomentArm(state, elbow), 4))
            current = muscle.getGeometryPath().getCurrentPath(state)
            points = []
            for index in range(current.getSize()):
                point = current.get(index)
                where = point.getParentFrame().findStationLocationInAnotherFrame(
                    state, point.getLocation(state), humerus)
                points.append([point.getName(), *(round(1000.0 * where.get(k), 4) for k in range(3))])
            paths[name].append(points)
    return {
        "source": "OpenSim 4.6, arm26.osim, shoulder at 0: benchmarks/arm26_reference.py --write",
        "flexion_deg": ELBOW_FLEXIONS,
        "length_mm": lengths,
        "moment_arm_mm": moment_arms,
        "path_points_mm": paths,
    }


def elbow_curves() -> dict[str, tuple[list[float], list[float]]]:
    """configs/elbow.toml's muscles' lengths and moment arms (mm) at each of
    ``ELBOW_FLEXIONS``, by name."""
    from biceps.configs import FOLDER
    from biceps.engine.config import load_config

    arm = load_config(FOLDER / "elbow.toml").arm
    curves = {name: ([], []) for name in arm.names}
    for flexion in ELBOW_FLEXIONS:
        posed = arm.at_flexion(flexion)
        for name, length, moment_arm in zip(posed.names, posed.lengths, posed.moment_arms):
            curves[name][0].append(10.0 * length)
            curves[name][1].append(10.0 * moment_arm)
    return curves


def path_curves() -> dict[str, tuple[list[float], list[float]]]:
    """The engine's own arm26 paths (engine/arm26.py): each muscle's length and moment arm
    (mm) at each of ``ELBOW_FLEXIONS``, by name."""
    from biceps.engine import arm26

    return {name: ([10.0 * arm26.path(name).length_at(f) for f in ELBOW_FLEXIONS],
                   [10.0 * arm26.path(name).moment_arm_at(f) for f in ELBOW_FLEXIONS])
            for name in ARM26_MUSCLES}


def model_curve() -> tuple[list[float], list[float]]:
    """The default skeleton's muscle length and moment arm (mm) at each of ``FLEXIONS``."""
    from biceps.engine.skeleton import Skeleton

    skeleton = Skeleton()
    lengths = [10.0 * skeleton.length_at(f) for f in FLEXIONS]
    moment_arms = [10.0 * skeleton.moment_arm(f) for f in FLEXIONS]
    return lengths, moment_arms


def _compact(text: str) -> str:
    """JSON ``text`` with each innermost list (numbers, a point) on one line."""
    return re.sub(r"\[\s+([^\[\]{}]*?)\s+\]",
                  lambda match: "[" + " ".join(match.group(1).split()) + "]", text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help=f"store the curve in {OUTPUT}")
    args = parser.parse_args()
    reference = opensim_curve(MODEL)
    elbow = opensim_elbow(MODEL)
    if args.write:
        OUTPUT.parent.mkdir(parents=True, exist_ok=True)
        OUTPUT.write_text(json.dumps(reference, indent=2) + "\n")
        ELBOW_OUTPUT.write_text(_compact(json.dumps(elbow, indent=2)) + "\n")
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
    for title, ours in (("engine/arm26.py's paths", path_curves()),
                        ("configs/elbow.toml's muscles", elbow_curves())):
        print(f"\n{title} against arm26 at every 5 degrees: the worst difference (mm)")
        for name in ARM26_MUSCLES:
            lengths, arms = ours[name]
            worst_length = max(abs(o - t) for o, t in zip(lengths, elbow["length_mm"][name]))
            worst_arm = max(abs(o - t) for o, t in zip(arms, elbow["moment_arm_mm"][name]))
            print(f"{name:>9}: length {worst_length:6.3f}, moment arm {worst_arm:6.3f}")

if __name__ == "__main__":
    main()
