"""The muscles' Hill-type parameters in a configuration: arm26's by default, a
``[forces.NAME]`` table's where it gives them."""

from dataclasses import replace

import pytest

from biceps.configs import FOLDER
from biceps.engine.arm26_forces import CURVES, PARAMETERS
from biceps.engine.config import load_config, save_config
from biceps.engine.errors import ConfigError
from biceps.engine.hill import HillParameters

ELBOW = (FOLDER / "elbow.toml").read_text()
BICEPS = (FOLDER / "biceps.toml").read_text()


def written(tmp_path, text, name="arm.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_elbows_six_take_arm26s_parameters():
    config = load_config(FOLDER / "elbow.toml")
    assert config.force_parameters() == tuple(PARAMETERS[name] for name in config.arm.names)


def test_a_single_muscle_file_is_arm26s_long_head_of_the_biceps():
    assert load_config(FOLDER / "biceps.toml").force_parameters() == (PARAMETERS["BIClong"],)


def test_a_table_overrides_the_parameters_it_names_and_keeps_the_rest(tmp_path):
    path = written(tmp_path, ELBOW + "\n[forces.BRA]\nmax_isometric_force = 1200.0\n"
                   "minimum_activation = 0.02\n")
    config = load_config(path)
    assert config.forces["BRA"] == replace(PARAMETERS["BRA"], max_isometric_force=1200.0,
                                           minimum_activation=0.02)
    assert config.forces["TRIlong"] == PARAMETERS["TRIlong"]


def test_a_muscle_not_of_arm26_gives_its_own_and_takes_thelens_curves(tmp_path):
    text = BICEPS.replace("[muscle]\n", "[muscle]\nname = \"biceps\"\n", 1)
    path = written(tmp_path, text + "\n[forces.biceps]\nmax_isometric_force = 600\n"
                   "optimal_fibre_length = 12\ntendon_slack_length = 22\npennation = 5\n")
    (parameters,) = load_config(path).force_parameters()
    assert parameters == HillParameters(600.0, 12.0, 22.0, 5.0, **CURVES)


def test_a_muscle_without_any_is_refused_when_forces_are_asked_for(tmp_path):
    text = BICEPS.replace("[muscle]\n", "[muscle]\nname = \"biceps\"\n", 1)
    config = load_config(written(tmp_path, text))  # the shape alone loads as before
    with pytest.raises(ConfigError, match=r"arm\.toml: the muscle 'biceps' has no force "
                                          r"parameters: .*give them in a \[forces\.biceps\] "
                                          r"table: max_isometric_force \(N\)"):
        config.force_parameters()


def test_saving_from_the_app_keeps_the_forces_table(tmp_path):
    path = written(tmp_path, ELBOW + "\n[forces.BRA]  # stronger\nmax_isometric_force = 1200.0\n")
    config = load_config(path)
    saved = save_config(config, config.arm.at_flexion(90.0), config.view, config.light,
                        config.render)
    assert saved.forces["BRA"].max_isometric_force == 1200.0
    assert "[forces.BRA]  # stronger\nmax_isometric_force = 1200.0\n" in path.read_text()
