"""A weight in the hand: the least-effort activations balance the load, stay within their
bounds, cannot be bettered by any small feasible change, or the load is refused."""

import itertools
import json
import re
from pathlib import Path

import numpy as np
import pytest

from biceps.configs import FOLDER
from biceps.engine.actuation import musculotendon, torque
from biceps.engine.arm26_forces import PARAMETERS
from biceps.engine.config import load_config
from biceps.engine.errors import RefusedChange
from biceps.engine.hill import equilibrate
from biceps.engine.hold import hold, hold_arm, load_at, strongest_torques

NAMES = list(PARAMETERS)
REFERENCE = json.loads((Path(__file__).parent / "data" / "arm26_forces.json").read_text())
ELBOW = load_config(FOLDER / "elbow.toml").arm


def opensim_geometry(flexion):
    """arm26's musculotendon lengths and moment arms (cm) at ``flexion``, as OpenSim has them."""
    rows = {row["muscle"]: row for row in REFERENCE["rows"]
            if row["flexion_deg"] == flexion and row["activation"] == 0.0}
    return (np.array([rows[name]["length_mm"] / 10 for name in NAMES]),
            np.array([rows[name]["moment_arm_mm"] / 10 for name in NAMES]))


def model_geometry(flexion):
    """configs/elbow.toml's own, in arm26's order of names."""
    lengths, moment_arms = musculotendon(ELBOW, flexion)
    order = [ELBOW.names.index(name) for name in NAMES]
    return lengths[order], moment_arms[order]


GEOMETRIES = {"opensim": opensim_geometry, "model": model_geometry}
CASES = [(0, 5.0), (30, 2.0), (60, 0.0), (90, 5.0), (100, 10.0), (130, 5.0)]


def torques(lengths, moment_arms, activations):
    """Each muscle's torque (N m) at ``activations``, and its slope per unit activation."""
    out = [equilibrate(PARAMETERS[name], lengths[i], activations[i])
           for i, name in enumerate(NAMES)]
    return (np.array([torque(float(s.tendon_force), moment_arms[i]) for i, s in enumerate(out)]),
            np.array([torque(float(s.force_per_activation), moment_arms[i])
                      for i, s in enumerate(out)]))


def solved(geometry, flexion, mass):
    lengths, moment_arms = GEOMETRIES[geometry](flexion)
    held = hold(NAMES, list(PARAMETERS.values()), lengths, moment_arms,
                load_at(25.4, flexion, mass))
    return held, lengths, moment_arms, np.array([m.activation for m in held.muscles])


@pytest.mark.parametrize("geometry", GEOMETRIES)
@pytest.mark.parametrize("flexion, mass", CASES)
def test_the_torques_balance_the_load_within_bounds(geometry, flexion, mass):
    held, lengths, moment_arms, activations = solved(geometry, flexion, mass)
    assert abs(held.torque - held.load.torque) <= 0.01
    assert abs(torques(lengths, moment_arms, activations)[0].sum() - held.load.torque) <= 1e-8
    assert np.all((0.0 <= activations) & (activations <= 1.0))
    assert np.all(activations >= 0.01)  # arm26's minimum activation
    assert held.cost == pytest.approx(float(activations @ activations), rel=1e-15)


@pytest.mark.parametrize("geometry", GEOMETRIES)
@pytest.mark.parametrize("flexion, mass", CASES)
def test_the_karush_kuhn_tucker_conditions_hold(geometry, flexion, mass):
    held, lengths, moment_arms, activations = solved(geometry, flexion, mass)
    _, slopes = torques(lengths, moment_arms, activations)
    # d/da_i of sum(a^2) - lambda (sum(torque) - load): zero where free, >= 0 at the lower
    # bound (raising a_i costs), <= 0 at the upper (lowering it costs).
    gradient = 2 * activations - held.multiplier * slopes
    at_low, at_high = activations <= 0.01 + 1e-12, activations >= 1.0 - 1e-12
    free = ~(at_low | at_high)
    assert np.all(np.abs(gradient[free]) <= 1e-7)
    assert np.all(gradient[at_low] >= -1e-7) and np.all(gradient[at_high] <= 1e-7)


def _muscle_torque(j, lengths, moment_arms, activation):
    """Muscle ``j``'s torque (N m) at ``activation`` and its slope."""
    state = equilibrate(PARAMETERS[NAMES[j]], lengths[j], activation)
    return (torque(float(state.tendon_force), moment_arms[j]),
            torque(float(state.force_per_activation), moment_arms[j]))


def _restoring(j, lengths, moment_arms, activation, wanted):
    """Muscle ``j``'s activation within its bounds at which it gives ``wanted`` N m, or None:
    Newton's method kept inside the bounds (its torque is monotone in its activation)."""
    low, high = 0.01, 1.0
    ends = [_muscle_torque(j, lengths, moment_arms, a)[0] - wanted for a in (low, high)]
    if ends[0] * ends[1] > 0:
        return None
    rising = ends[1] > ends[0]
    for _ in range(60):
        error, slope = _muscle_torque(j, lengths, moment_arms, activation)
        error -= wanted
        if abs(error) <= 1e-12:
            break
        if (error > 0) == rising:
            high = activation
        else:
            low = activation
        step = activation - error / slope if slope else None
        activation = step if step is not None and low < step < high else 0.5 * (low + high)
    return activation


@pytest.mark.parametrize("geometry", GEOMETRIES)
@pytest.mark.parametrize("flexion, mass", [(30, 2.0), (90, 5.0), (130, 5.0)])
def test_no_small_feasible_change_lowers_the_cost(geometry, flexion, mass):
    held, lengths, moment_arms, activations = solved(geometry, flexion, mass)
    target = held.load.torque
    tried = 0
    each, _ = torques(lengths, moment_arms, activations)
    assert abs(each.sum() - target) <= 1e-8
    for i, j in itertools.permutations(range(len(NAMES)), 2):
        for step in (-1e-2, -1e-3, 1e-3, 1e-2):
            moved = activations.copy()
            moved[i] += step
            if not 0.01 <= moved[i] <= 1.0:
                continue
            change = _muscle_torque(i, lengths, moment_arms, moved[i])[0] - each[i]
            restored = _restoring(j, lengths, moment_arms, moved[j], each[j] - change)
            if restored is None:
                continue
            moved[j] = restored
            tried += 1
            assert float(moved @ moved) >= held.cost - 1e-12, (NAMES[i], NAMES[j], step)
    assert tried >= 20


def test_a_mass_beyond_the_strongest_torque_is_refused_naming_it():
    lengths, moment_arms = opensim_geometry(90)
    flexing = moment_arms > 0
    strongest = torques(lengths, moment_arms, np.where(flexing, 1.0, 0.01))[0].sum()
    with pytest.raises(RefusedChange) as refusal:
        hold(NAMES, list(PARAMETERS.values()), lengths, moment_arms, load_at(25.4, 90, 40.0))
    message = str(refusal.value)
    assert f"the strongest the muscles can hold there is {strongest:.2f} N m" in message
    assert "40 kg in the hand at 90 degrees of flexion needs" in message
    heaviest = float(re.search(r"at most ([0-9.]+) kg there", message).group(1))
    hold(NAMES, list(PARAMETERS.values()), lengths, moment_arms, load_at(25.4, 90, heaviest))
    with pytest.raises(RefusedChange):
        hold(NAMES, list(PARAMETERS.values()), lengths, moment_arms,
             load_at(25.4, 90, heaviest + 0.02))


def test_the_straight_arm_holds_any_weight_on_its_bones():
    parameters = [PARAMETERS[name] for name in ELBOW.names]
    held = hold_arm(ELBOW, parameters, 0.0, 500.0)
    assert held.load.torque == 0.0
    # The weight asks nothing of the muscles: the activations are those with the hand
    # empty, which balance only the passive pulls (the biceps' long head, stretched, 66 N).
    empty = hold_arm(ELBOW, parameters, 0.0, 0.0)
    assert [muscle.activation for muscle in held.muscles] == pytest.approx(
        [muscle.activation for muscle in empty.muscles], abs=1e-9)
    assert max(muscle.activation for muscle in held.muscles) < 0.05


def test_the_load_is_the_weight_times_its_horizontal_reach():
    load = load_at(30.0, 30.0, 2.0)
    assert load.hand == pytest.approx(2.0 * 9.8066 * 0.30 * 0.5, rel=1e-15)
    assert load.forearm == pytest.approx(1.534315 * 9.8066 * 0.181479 * 0.5, rel=1e-15)


def test_the_strongest_torque_across_the_range_is_the_refusals():
    parameters = [PARAMETERS[name] for name in ELBOW.names]
    flexions = [30.0, 90.0, 120.0]
    strongest = strongest_torques(ELBOW, parameters, flexions)
    assert strongest.shape == (3,)
    for flexion, most in zip(flexions, strongest):
        with pytest.raises(RefusedChange, match=f"can hold there is {most:.2f} N m"):
            hold_arm(ELBOW, parameters, flexion, 200.0)
