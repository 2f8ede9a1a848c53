"""The muscles as actuators: their lengths and moment arms from one call, their forces and
torques at an activation."""

from dataclasses import fields

import numpy as np
import pytest

from biceps.configs import FOLDER
from biceps.engine.actuation import (RECORD, MuscleForce, forces_across, muscle_forces,
                                     musculotendon)
from biceps.engine.arm26_forces import PARAMETERS
from biceps.engine.config import load_config
from biceps.engine.hill import equilibrate

ELBOW = load_config(FOLDER / "elbow.toml").arm


@pytest.mark.parametrize("flexion", [0.0, 35.0, 90.0, 130.0])
@pytest.mark.parametrize("config", ["elbow.toml", "biceps.toml"])
def test_the_lengths_and_moment_arms_are_the_arms_own(config, flexion):
    # One source of geometry: the arm's paths, as the arm at that flexion reports them
    # (arm26's via points and wraps on elbow.toml, the straight skeleton on biceps.toml).
    arm = load_config(FOLDER / config).arm
    lengths, moment_arms = musculotendon(arm, flexion)
    posed = arm.at_flexion(flexion)
    assert len(lengths) == len(moment_arms) == len(arm.names)
    assert lengths == pytest.approx(posed.lengths, rel=1e-12)
    assert moment_arms == pytest.approx(posed.moment_arms, rel=1e-9, abs=1e-12)
    assert moment_arms[0] == pytest.approx(posed.moment_arm, rel=1e-9)


def test_a_moment_arm_is_the_length_lost_per_radian_of_flexion():
    step = 0.01  # degrees, a coarser difference than the function's own
    for flexion in (20.0, 75.0, 120.0):
        lengths_before, _ = musculotendon(ELBOW, flexion - step)
        lengths_after, _ = musculotendon(ELBOW, flexion + step)
        _, moment_arms = musculotendon(ELBOW, flexion)
        lost = (lengths_before - lengths_after) / np.radians(2 * step)
        assert moment_arms == pytest.approx(lost, abs=1e-6)
    # Flexors pull in front of the elbow, the triceps behind it.
    signs = dict(zip(ELBOW.names, np.sign(musculotendon(ELBOW, 90.0)[1])))
    assert signs == {"BIClong": 1, "BRA": 1, "BICshort": 1, "TRImed": -1, "TRIlat": -1,
                     "TRIlong": -1}


def test_a_muscles_torque_is_its_tendon_force_times_its_moment_arm():
    flexions = [10.0, 60.0, 110.0]
    parameters = [PARAMETERS[name] for name in ELBOW.names]
    poses = forces_across(ELBOW, parameters, flexions, 0.5)
    assert [len(pose) for pose in poses] == [6, 6, 6]
    for flexion, pose in zip(flexions, poses):
        lengths, moment_arms = musculotendon(ELBOW, flexion)
        for i, muscle in enumerate(pose):
            state = equilibrate(PARAMETERS[muscle.name], lengths[i], 0.5)
            assert muscle.name == ELBOW.names[i]
            assert muscle.tendon_force == float(state.tendon_force)
            assert muscle.torque == pytest.approx(
                muscle.tendon_force * moment_arms[i] / 100, rel=1e-15)
            assert muscle.length == lengths[i] and muscle.moment_arm == moment_arms[i]


def test_one_activation_a_muscle():
    lengths = np.array([[40.0, 30.0]])
    moment_arms = np.array([[4.0, -2.0]])
    (pose,) = muscle_forces(["BIClong", "TRIlong"], [PARAMETERS["BIClong"], PARAMETERS["TRIlong"]],
                            lengths, moment_arms, [1.0, 0.0])
    assert [muscle.activation for muscle in pose] == [1.0, 0.01]
    assert pose[0].torque > 0 > pose[1].torque
    record = pose[1].record()
    assert record["name"] == "TRIlong" and record["torque_nm"] == pose[1].torque
    assert set(record) >= {"fibre_length_cm", "active_force_n", "passive_force_n",
                           "tendon_force_n", "torque_nm"}
    # Every field is in the record, each under one name.
    assert sorted(field for field, _ in RECORD) == sorted(f.name for f in fields(MuscleForce))
    assert len(record) == len(RECORD) and list(record.values()) == [
        getattr(pose[1], field) for field, _ in RECORD]
