"""The Hill-type muscle after Thelen 2003: its curves, and the fibre-tendon equilibrium."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from biceps.engine.arm26_forces import PARAMETERS
from biceps.engine.hill import (
    FORCE_TOLERANCE,
    MAXIMUM_PENNATION,
    active_force_length,
    equilibrate,
    passive_force_length,
    stacked,
    tendon_force_strain,
)

BIC = PARAMETERS["BIClong"]
TRI = PARAMETERS["TRIlong"]  # pennate: 12 degrees at its optimal fibre length


def slope_by_difference(curve, x, p, step=1e-7):
    return (curve(x + step, p)[0] - curve(x - step, p)[0]) / (2 * step)


def test_the_active_curve_peaks_at_the_optimal_length_and_falls_as_a_gaussian():
    fal, slope = active_force_length(np.array([1.0, 1.5, 0.5]), BIC)
    assert fal[0] == 1.0 and slope[0] == 0.0
    # exp(-(0.5)^2 / 0.5) on either side
    assert fal[1:] == pytest.approx([math.exp(-0.5)] * 2, rel=1e-15)


def test_the_passive_curve_is_zero_until_stretched_and_reaches_fmax_at_its_strain():
    fpe, _ = passive_force_length(np.array([0.7, 1.0, 1.0 + BIC.passive_strain]), BIC)
    assert fpe[:2].tolist() == [0.0, 0.0]
    assert fpe[2] == pytest.approx(1.0, rel=1e-14)


def test_the_tendon_curve_reaches_fmax_at_its_strain_and_turns_linear_smoothly():
    e0 = BIC.tendon_strain
    toe = 99 * e0 * math.exp(3) / (166 * math.exp(3) - 67)  # OpenSim's exact e_toe
    assert toe == pytest.approx(0.609 * e0, rel=1e-3)  # Thelen's rounded figure
    fse, _ = tendon_force_strain(np.array([-0.01, 0.0, toe, e0]), BIC)
    assert fse.tolist()[:2] == [0.0, 0.0]
    assert fse[2] == pytest.approx(0.33, rel=1e-14) and fse[3] == pytest.approx(1.0, rel=1e-14)
    below, above = tendon_force_strain(np.array([toe - 1e-9, toe + 1e-9]), BIC)[1]
    assert below == pytest.approx(above, rel=1e-6)  # the slope is continuous at the toe


@pytest.mark.parametrize("curve, points", [
    (active_force_length, [0.4, 0.9, 1.3, 1.8]),
    (passive_force_length, [1.05, 1.3, 1.6]),
    (tendon_force_strain, [0.005, 0.015, 0.03, 0.05]),
])
def test_each_curve_reports_its_own_slope(curve, points):
    x = np.array(points)
    assert curve(x, BIC)[1] == pytest.approx(slope_by_difference(curve, x, BIC), rel=1e-6)


@pytest.mark.parametrize("p", [BIC, TRI], ids=["parallel", "pennate"])
@pytest.mark.parametrize("activation", [0.01, 0.3, 1.0])
def test_the_fibre_and_the_tendon_pull_alike_at_equilibrium(p, activation):
    lengths = p.tendon_slack_length + p.optimal_fibre_length * np.linspace(0.6, 1.5, 10)
    state = equilibrate(p, lengths, activation)
    along_tendon = (state.active_force + state.passive_force) * np.cos(state.pennation)
    assert np.all(np.abs(along_tendon - state.tendon_force)
                  <= FORCE_TOLERANCE * p.max_isometric_force + 1e-12 * state.tendon_force)
    assert np.all(state.tendon_force > 0.0)


def test_a_full_pull_at_the_optimal_fibre_length_stretches_the_tendon_by_its_strain():
    # Fully active at its optimal length the fibre pulls Fmax, which stretches the tendon by
    # exactly tendon_strain: so that is the musculotendon length where it is found.
    length = BIC.optimal_fibre_length + BIC.tendon_slack_length * (1 + BIC.tendon_strain)
    state = equilibrate(BIC, length, 1.0)
    assert float(state.fibre_length) == pytest.approx(BIC.optimal_fibre_length, rel=1e-12)
    assert float(state.tendon_force) == pytest.approx(BIC.max_isometric_force, rel=1e-12)
    assert float(state.passive_force) == pytest.approx(0.0, abs=1e-9)


def test_pennation_keeps_the_fibres_height():
    state = equilibrate(TRI, TRI.tendon_slack_length + TRI.optimal_fibre_length * np.array(
        [0.8, 1.0, 1.2]), 1.0)
    height = TRI.optimal_fibre_length * math.sin(math.radians(TRI.pennation))
    assert state.fibre_length * np.sin(state.pennation) == pytest.approx([height] * 3, rel=1e-12)


def test_activation_below_the_minimum_acts_as_the_minimum_and_more_pulls_harder():
    length = BIC.tendon_slack_length + BIC.optimal_fibre_length
    state = equilibrate(BIC, length, np.array([0.0, 0.005, 0.01, 0.5, 1.0, 1.5]))
    assert state.activation.tolist() == [0.01, 0.01, 0.01, 0.5, 1.0, 1.0]
    assert len(set(state.tendon_force[:3])) == 1
    assert np.all(np.diff(state.tendon_force[2:5]) > 0.0)


@pytest.mark.parametrize("p", [BIC, TRI], ids=["parallel", "pennate"])
def test_the_force_per_activation_is_the_slope_of_the_re_solved_force(p):
    length = p.tendon_slack_length + 1.1 * p.optimal_fibre_length
    activation = np.array([0.2, 0.6, 0.95])
    step = 1e-6
    ahead = equilibrate(p, length, activation + step).tendon_force
    behind = equilibrate(p, length, activation - step).tendon_force
    slope = equilibrate(p, length, activation).force_per_activation
    assert slope == pytest.approx((ahead - behind) / (2 * step), rel=1e-6)


def test_a_path_shorter_than_the_slack_tendon_pulls_nothing_with_the_fibre_at_its_shortest():
    state = equilibrate(TRI, TRI.tendon_slack_length - 0.5, 1.0)
    shortest = TRI.optimal_fibre_length * math.sin(math.radians(TRI.pennation)) / math.sin(
        MAXIMUM_PENNATION)
    assert float(state.tendon_force) == 0.0
    assert float(state.fibre_length) == pytest.approx(shortest, rel=1e-12)
    assert float(state.force_per_activation) == 0.0
    parallel = equilibrate(BIC, BIC.tendon_slack_length - 0.5, 1.0)
    assert float(parallel.tendon_force) == 0.0 and float(parallel.fibre_length) == 0.0


def test_several_muscles_solve_together_as_each_alone():
    names = list(PARAMETERS)
    lengths = np.array([[42.0, 34.0, 14.0, 28.0, 17.0, 16.0],
                        [35.0, 27.0, 11.0, 32.0, 21.0, 20.0]])
    together = equilibrate(stacked(PARAMETERS.values()), lengths, 0.7)
    for i, name in enumerate(names):
        alone = equilibrate(PARAMETERS[name], lengths[:, i], 0.7)
        assert together.tendon_force[:, i] == pytest.approx(alone.tendon_force, rel=1e-12)
        assert together.fibre_length[:, i] == pytest.approx(alone.fibre_length, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(muscle=st.sampled_from(list(PARAMETERS)), stretch=st.floats(-0.5, 2.5),
       activation=st.floats(0.0, 1.0))
def test_any_length_and_activation_balance_or_clamp(muscle, stretch, activation):
    p = PARAMETERS[muscle]
    length = p.tendon_slack_length + stretch * p.optimal_fibre_length
    state = equilibrate(p, length, activation)
    assert np.isfinite(state.tendon_force) and state.tendon_force >= 0.0
    balanced = abs(float(state.error)) <= FORCE_TOLERANCE * p.max_isometric_force
    clamped = float(state.force_per_activation) == 0.0 and (
        float(state.tendon_force) == 0.0 or float(state.error) > 0.0)
    assert balanced or clamped


@pytest.mark.parametrize("p", [BIC, TRI], ids=["parallel", "pennate"])
def test_starting_near_another_equilibrium_finds_the_same_one(p):
    lengths = p.tendon_slack_length + p.optimal_fibre_length * np.linspace(0.7, 1.4, 8)
    near = equilibrate(p, lengths, 0.3)
    for activation in (0.01, 0.35, 1.0):
        alone, started = equilibrate(p, lengths, activation), equilibrate(p, lengths, activation,
                                                                           near)
        assert started.tendon_force == pytest.approx(alone.tendon_force, rel=1e-9, abs=1e-9)
        assert started.fibre_length == pytest.approx(alone.fibre_length, rel=1e-9)
