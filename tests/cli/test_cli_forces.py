"""``biceps sweep --activation`` and ``biceps hold``: the muscles' forces and torques, read
back as a script would."""

import csv
import io
import json

import pytest
from click.testing import CliRunner

from biceps.cli import main
from biceps.configs import FOLDER

ELBOW = FOLDER / "elbow.toml"
MUSCLE_FIELDS = {"name", "activation", "musculotendon_length_cm", "moment_arm_cm",
                 "fibre_length_cm", "normalised_fibre_length", "pennation_deg",
                 "active_force_n", "passive_force_n", "tendon_force_n", "torque_nm"}


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_sweep_with_an_activation_adds_every_muscles_forces_to_every_row():
    result = run("sweep", ELBOW, "--json", "--activation", 0.5, "--step", 13)
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)
    assert [row["flexion_deg"] for row in rows] == [13.0 * k for k in range(11)]
    for row in rows:
        assert [muscle["name"] for muscle in row["muscles"]] == [
            "BIClong", "BRA", "BICshort", "TRImed", "TRIlat", "TRIlong"]
        for muscle in row["muscles"]:
            assert set(muscle) == MUSCLE_FIELDS
            assert muscle["activation"] == 0.5
            assert muscle["torque_nm"] == pytest.approx(
                muscle["tendon_force_n"] * muscle["moment_arm_cm"] / 100, rel=1e-15)
        assert row["elbow_torque_nm"] == pytest.approx(
            sum(muscle["torque_nm"] for muscle in row["muscles"]), rel=1e-12)
        # The driver's path is the one the row's length is of.
        assert row["muscles"][0]["musculotendon_length_cm"] == pytest.approx(row["length_cm"],
                                                                      rel=1e-14)


def test_sweep_without_an_activation_is_as_before():
    rows = json.loads(run("sweep", ELBOW, "--json", "--step", 65).stdout)
    assert all("muscles" not in row and "elbow_torque_nm" not in row for row in rows)


def test_the_csv_names_each_muscles_columns_after_it():
    result = run("sweep", ELBOW, "--csv", "--activation", 1, "--from", 90, "--to", 90)
    (row,) = list(csv.DictReader(io.StringIO(result.stdout)))
    (record,) = json.loads(run("sweep", ELBOW, "--json", "--activation", 1, "--from", 90,
                               "--to", 90).stdout)
    for muscle in record["muscles"]:
        for key, value in muscle.items():
            if key != "name":
                assert float(row[f"{muscle['name']}_{key}"]) == value
    assert float(row["elbow_torque_nm"]) == record["elbow_torque_nm"]


@pytest.mark.parametrize("activation", ["-0.1", "1.5", "nan"])
def test_an_activation_outside_0_to_1_is_refused(activation):
    result = run("sweep", ELBOW, "--activation", activation)
    assert result.exit_code == 2
    assert "Invalid value for '--activation'" in result.output


def test_hold_balances_the_load_and_says_so():
    result = run("hold", ELBOW, "--mass", 5, "--flexion", 90, "--json")
    assert result.exit_code == 0, result.output
    held = json.loads(result.stdout)
    assert held["flexion_deg"] == 90.0 and held["mass_kg"] == 5.0
    assert held["load_torque_nm"] == pytest.approx(
        held["hand_torque_nm"] + held["forearm_torque_nm"], rel=1e-15)
    assert abs(held["elbow_torque_nm"] - held["load_torque_nm"]) <= 0.01
    assert all(0.0 <= muscle["activation"] <= 1.0 for muscle in held["muscles"])
    assert held["sum_of_squared_activations"] == pytest.approx(
        sum(muscle["activation"] ** 2 for muscle in held["muscles"]), rel=1e-12)
    text = run("hold", ELBOW, "--mass", 5, "--flexion", 90).stdout
    assert "5 kg in the hand at 90.00 degrees of flexion" in text
    assert f"net torque  {held['elbow_torque_nm']:.3f} N m" in text
    for muscle in held["muscles"]:
        assert f"{muscle['name']:<8}  {muscle['activation']:10.4f}" in text


def test_hold_defaults_to_the_configs_pose():
    held = json.loads(run("hold", ELBOW, "--mass", 1, "--json").stdout)
    assert held["flexion_deg"] == pytest.approx(60.0, abs=1e-9)  # elbow.toml's pose_flexion


def test_a_mass_too_heavy_is_refused_with_the_strongest_torque():
    result = run("hold", ELBOW, "--mass", 30, "--flexion", 90)
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr.startswith("biceps: 30 kg in the hand at 90 degrees of flexion needs "
                                    "77.46 N m at the elbow")
    assert "the strongest the muscles can hold there is" in result.stderr
    assert "kg there" in result.stderr and "Traceback" not in result.stderr


@pytest.mark.parametrize("args, message", [
    (["--mass", "-1"], "Invalid value for '--mass'"),
    (["--mass", "inf"], "Invalid value for '--mass'"),
    ([], "Missing option '--mass'"),
    (["--mass", "1", "--flexion", "140"], "flexion 140 degrees is outside the joint's range"),
])
def test_hold_refuses_what_it_cannot_take(args, message):
    result = run("hold", ELBOW, *args)
    assert result.exit_code == 2
    assert message in result.output
