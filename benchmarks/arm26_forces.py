"""The force reference: OpenSim's Thelen2003Muscle on arm26, equilibrated, against the model
of ``engine/hill.py``, first at OpenSim's own musculotendon lengths and moment arms, then at
the arm's own (end to end).

    .venv/bin/pip install -e '.[reference]'   # the opensim package (4.6), about 100 MB
    .venv/bin/python benchmarks/arm26_forces.py [--write]

OpenSim loads ``shared/data/arm26.osim`` headless (it warns that the bone meshes it names
are missing, which does not matter here), sets the shoulder to 0, and at every 10 degrees
of elbow flexion from 0 to 130 and each activation 0, 0.5 and 1 (OpenSim raises 0 to the
muscles' minimum activation, 0.01) sets every muscle's activation, equilibrates the muscles
(``equilibrateMuscles``: fibre and tendon force equal, at rest) and reads, for each of the
six, the musculotendon length and moment arm about the elbow, the fibre length, pennation,
active and passive fibre force and the tendon force. With the muscles switched off it also
asks inverse dynamics for the torque that holds the forearm's own weight at each angle.
``--write`` stores all of it, and the muscles' parameters as OpenSim read them, in
``tests/engine/data/arm26_forces.json``, which the tests compare the model with, so that
they need no opensim.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT.parent / "shared" / "data" / "arm26.osim"
OUTPUT = ROOT / "tests" / "engine" / "data" / "arm26_forces.json"
FLEXIONS = list(range(0, 131, 10))
ACTIVATIONS = (0.0, 0.5, 1.0)
ARM26_MUSCLES = ("BIClong", "BICshort", "BRA", "TRIlong", "TRIlat", "TRImed")


def opensim_reference(model_path: Path) -> dict:
    """Every muscle at every flexion and activation, equilibrated; the forearm's weight."""
    import opensim

    model = opensim.Model(str(model_path))
    state = model.initSystem()
    coordinates = model.getCoordinateSet()
    elbow = coordinates.get("r_elbow_flex")
    coordinates.get("r_shoulder_elev").setValue(state, 0.0)
    muscles = {name: opensim.Thelen2003Muscle.safeDownCast(model.getMuscles().get(name))
               for name in ARM26_MUSCLES}
    rows = []
    for flexion in FLEXIONS:
        elbow.setValue(state, math.radians(flexion))
        for activation in ACTIVATIONS:
            for muscle in muscles.values():
                muscle.setActivation(state, activation)
            model.equilibrateMuscles(state)
            model.realizeDynamics(state)
            for name, muscle in muscles.items():
                rows.append({
                    "muscle": name,
                    "flexion_deg": flexion,
                    "activation": activation,
                    "length_mm": 1000.0 * muscle.getLength(state),
                    "moment_arm_mm": 1000.0 * muscle.computeMomentArm(state, elbow),
                    "fibre_length_mm": 1000.0 * muscle.getFiberLength(state),
                    "pennation_deg": math.degrees(muscle.getPennationAngle(state)),
                    "active_force_n": muscle.getActiveFiberForce(state),
                    "passive_force_n": muscle.getPassiveFiberForce(state),
                    "tendon_force_n": muscle.getTendonForce(state),
                })
    return {
        "source": "OpenSim 4.6, arm26.osim, Thelen2003Muscle, muscles equilibrated at rest, "
                  "shoulder at 0: benchmarks/arm26_forces.py --write",
        "parameters": {name: _parameters(muscle) for name, muscle in muscles.items()},
        "forearm_torque_nm": _forearm_torques(model, elbow, coordinates),
        "rows": rows,
    }


def _parameters(muscle) -> dict:
    """A muscle's parameters as OpenSim read them from the model file, in SI units."""
    return {
        "max_isometric_force_n": muscle.getMaxIsometricForce(),
        "optimal_fibre_length_m": muscle.getOptimalFiberLength(),
        "tendon_slack_length_m": muscle.getTendonSlackLength(),
        "pennation_rad": muscle.getPennationAngleAtOptimalFiberLength(),
        "FmaxTendonStrain": muscle.get_FmaxTendonStrain(),
        "FmaxMuscleStrain": muscle.get_FmaxMuscleStrain(),
        "KshapeActive": muscle.get_KshapeActive(),
        "KshapePassive": muscle.get_KshapePassive(),
        "minimum_activation": muscle.getMinimumActivation(),
        "maximum_pennation_rad": muscle.getMaximumPennationAngle(),
    }


def _forearm_torques(model, elbow, coordinates) -> list[float]:
    """The elbow torque (N m, flexing) that holds the forearm still against gravity at each of
    ``FLEXIONS``: inverse dynamics at rest, with the muscles switched off."""
    import opensim

    state = model.initSystem()
    coordinates.get("r_shoulder_elev").setValue(state, 0.0)
    for index in range(model.getMuscles().getSize()):
        model.getMuscles().get(index).setAppliesForce(state, False)
    solver = opensim.InverseDynamicsSolver(model)
    elbow_index = [coordinates.get(i).getName() for i in range(coordinates.getSize())].index(
        elbow.getName())
    torques = []
    for flexion in FLEXIONS:
        elbow.setValue(state, math.radians(flexion))
        model.realizeDynamics(state)
        torques.append(solver.solve(state, opensim.Vector(state.getNU(), 0.0)).get(elbow_index))
    return torques


def write(reference: dict) -> None:
    """The reference as JSON, a row to a line, so that a change to one reads as one line."""
    lines = ["{"]
    for key in ("source", "parameters", "forearm_torque_nm"):
        lines.append(f"  {json.dumps(key)}: {json.dumps(reference[key])},")
    lines.append('  "rows": [')
    rows = [f"    {json.dumps(row)}" for row in reference["rows"]]
    lines.append(",\n".join(rows))
    lines.append("  ]")
    lines.append("}")
    OUTPUT.write_text("\n".join(lines) + "\n")


def compare(reference: dict) -> None:
    """How far the model lies from OpenSim, at OpenSim's lengths and at the arm's own."""
    from biceps.configs import FOLDER
    from biceps.engine.actuation import musculotendon
    from biceps.engine.arm26_forces import PARAMETERS
    from biceps.engine.config import load_config
    from biceps.engine.hill import equilibrate

    rows = reference["rows"]
    print("The model at OpenSim's lengths: the largest difference from OpenSim over 0 to 130 "
          "degrees and activations 0, 0.5, 1")
    print(f"{'muscle':>9}{'tendon force':>16}{'(share of 3% or 5 N)':>22}{'fibre length':>15}")
    for name in ARM26_MUSCLES:
        mine = [row for row in rows if row["muscle"] == name]
        worst_force = worst_share = worst_fibre = 0.0
        for row in mine:
            state = equilibrate(PARAMETERS[name], row["length_mm"] / 10.0, row["activation"])
            force = float(state.tendon_force) - row["tendon_force_n"]
            allowed = max(0.03 * abs(row["tendon_force_n"]), 5.0)
            fibre = float(state.fibre_length) * 10.0 / row["fibre_length_mm"] - 1.0
            worst_force = max(worst_force, abs(force), key=abs)
            worst_share = max(worst_share, abs(force) / allowed)
            worst_fibre = max(worst_fibre, abs(fibre))
        print(f"{name:>9}{worst_force:>14.2e} N{worst_share:>21.1e}{100 * worst_fibre:>13.1e} %")

    arm = load_config(FOLDER / "elbow.toml").arm
    geometry = {flexion: musculotendon(arm, flexion) for flexion in FLEXIONS}
    print("\nEnd to end, at configs/elbow.toml's own lengths and moment arms: the largest "
          "difference from OpenSim over 0 to 130 degrees and activations 0, 0.5, 1, and the "
          "rows within the issue's 3 % or 5 N")
    print(f"{'muscle':>9}{'length':>10}{'moment arm':>12}{'tendon force':>14}{'within':>9}"
          f"{'fibre length':>14}{'torque':>11}")
    for index, name in enumerate(arm.names):
        mine = [row for row in rows if row["muscle"] == name]
        worst = dict(length=0.0, moment_arm=0.0, force=0.0, fibre=0.0, torque=0.0)
        within = 0
        for row in mine:
            length, moment_arm = (float(each[index]) for each in geometry[row["flexion_deg"]])
            state = equilibrate(PARAMETERS[name], length, row["activation"])
            force = float(state.tendon_force)
            differences = dict(
                length=10.0 * length - row["length_mm"],
                moment_arm=10.0 * moment_arm - row["moment_arm_mm"],
                force=force - row["tendon_force_n"],
                fibre=100.0 * (10.0 * float(state.fibre_length) / row["fibre_length_mm"] - 1),
                torque=(force * moment_arm / 100.0
                        - row["tendon_force_n"] * row["moment_arm_mm"] / 1000.0))
            for key, value in differences.items():
                worst[key] = max(worst[key], value, key=abs)
            within += abs(differences["force"]) <= max(0.03 * row["tendon_force_n"], 5.0)
        print(f"{name:>9}{worst['length']:>7.3f} mm{worst['moment_arm']:>9.3f} mm"
              f"{worst['force']:>12.3f} N{within:>5}/{len(mine)}"
              f"{worst['fibre']:>12.4f} %{worst['torque']:>7.3f} N m")

    print("\nEnd to end: configs/elbow.toml's own musculotendon lengths and moment arms against "
          "OpenSim's, and the tendon force and torque at activation 1 that follow")
    print(f"{'muscle':>9}{'flexion':>8}{'length mm':>22}{'moment arm mm':>22}"
          f"{'tendon force N':>22}{'torque N m':>20}")
    print(f"{'':>17}{'arm26':>8}{'model':>8}{'diff':>6}{'arm26':>8}{'model':>8}{'diff':>6}"
          f"{'arm26':>8}{'model':>8}{'diff':>6}{'arm26':>7}{'model':>7}{'diff':>6}")
    for index, name in enumerate(arm.names):
        for flexion in FLEXIONS[::3]:
            theirs = next(row for row in rows if row["muscle"] == name
                          and row["flexion_deg"] == flexion and row["activation"] == 1.0)
            length, moment_arm = (float(each[index]) for each in geometry[flexion])
            force = float(equilibrate(PARAMETERS[name], length, 1.0).tendon_force)
            their_torque = theirs["tendon_force_n"] * theirs["moment_arm_mm"] / 1000.0
            torque = force * moment_arm / 100.0
            print(f"{name:>9}{flexion:>8}"
                  f"{theirs['length_mm']:>8.1f}{10 * length:>8.1f}"
                  f"{10 * length - theirs['length_mm']:>6.1f}"
                  f"{theirs['moment_arm_mm']:>8.1f}{10 * moment_arm:>8.1f}"
                  f"{10 * moment_arm - theirs['moment_arm_mm']:>6.1f}"
                  f"{theirs['tendon_force_n']:>8.0f}{force:>8.0f}"
                  f"{force - theirs['tendon_force_n']:>6.0f}"
                  f"{their_torque:>7.1f}{torque:>7.1f}{torque - their_torque:>6.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help=f"store the table in {OUTPUT}")
    args = parser.parse_args()
    reference = opensim_reference(MODEL)
    if args.write:
        write(reference)
        print(f"wrote {OUTPUT}")
    compare(reference)


if __name__ == "__main__":
    main()
