"""``biceps sweep``: one row per elbow angle, exact numbers, read back as a script would."""

import csv
import io
import json

import pytest
from click.testing import CliRunner

from biceps.cli import main
from biceps.engine.config import DEFAULT_CONFIG


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def _csv_rows(*args) -> list[dict[str, str]]:
    result = run("sweep", DEFAULT_CONFIG, "--csv", *args)
    assert result.exit_code == 0, result.output
    return list(csv.DictReader(io.StringIO(result.stdout)))


def test_the_csv_reads_back_with_the_volume_kept_and_the_muscle_shortening():
    rows = _csv_rows("--from", 0, "--to", 130, "--step", 5)
    assert [float(row["flexion_deg"]) for row in rows] == [5.0 * k for k in range(27)]
    assert all(float(row["volume_relative_error"]) < 1e-12 for row in rows)
    lengths = [float(row["length_cm"]) for row in rows]
    assert all(shorter < longer for longer, shorter in zip(lengths, lengths[1:]))


@pytest.mark.parametrize("flexion", ["0.0", "37.5", "90.0", "130.0"])
def test_the_radii_are_those_info_gives_at_the_same_angle(flexion):
    (row,) = _csv_rows("--from", flexion, "--to", flexion)
    info = json.loads(run("info", DEFAULT_CONFIG, "--flexion", row["flexion_deg"], "--json").stdout)
    radii = [float(row[f"radius_{i}_cm"]) for i in range(1, info["nodes"] + 1)]
    assert radii == info["radii_cm"]  # exactly: the same doubles
    assert float(row["length_cm"]) == info["length_cm"]
    assert float(row["girth_cm"]) == info["girth_cm"]


def test_every_number_is_printed_in_its_shortest_exact_form():
    for row in _csv_rows("--step", 0.1, "--from", 60, "--to", 61):
        for text in row.values():
            assert text == repr(float(text))


def test_the_moment_arm_grows_from_a_straight_arms_lever():
    rows = _csv_rows("--from", 0, "--to", 90, "--step", 30)
    arms = [float(row["moment_arm_cm"]) for row in rows]
    # The insertion in front of the forearm's axis: 0.64 cm straight (arm26: 0.94).
    assert arms[0] == pytest.approx(0.641, abs=1e-3)
    assert arms == sorted(arms) and arms[-1] > 4.0  # about 5 cm at a right angle


def test_the_json_holds_the_same_numbers_as_the_csv():
    result = run("sweep", DEFAULT_CONFIG, "--json", "--from", 30, "--to", 50)
    records = json.loads(result.stdout)
    csv_row = _csv_rows("--from", 30, "--to", 50)[0]
    assert len(records) == 3
    assert records[0]["length_cm"] == float(csv_row["length_cm"])
    assert records[0]["radii_cm"][7] == float(csv_row["radius_8_cm"])


@pytest.mark.parametrize(("args", "message"), [
    (["--step", "0"], "the step must be above 0 degrees"),
    (["--to", "150"], "outside the joint's range"),
    (["--step", "1e-9"], "take a larger step"),
    (["--from", "inf"], "--from"),
])
def test_a_sweep_that_cannot_be_made_prints_no_row(args, message):
    result = run("sweep", DEFAULT_CONFIG, *args)
    assert result.exit_code == 2
    assert message in result.stderr
    assert result.stdout == ""


def test_with_length_limits_in_the_config_the_sweep_and_the_cycle_keep_within_them(
        config_path, tmp_path):
    text = config_path.read_text()
    assert "# min_length = 28.0" in text and "# max_length = 35.0" in text
    config_path.write_text(text.replace("# min_length", "min_length")
                           .replace("# max_length", "max_length"))
    result = run("sweep", config_path, "--step", 1)
    assert result.exit_code == 0, result.output
    lengths = [float(row["length_cm"]) for row in csv.DictReader(io.StringIO(result.stdout))]
    assert lengths[0] == pytest.approx(35.0) and lengths[-1] >= 28.0
    out = tmp_path / "cycle.apng"
    result = run("animate", config_path, "-o", out, "--size", "64x36", "--frames", 4)
    assert result.exit_code == 0, result.output
