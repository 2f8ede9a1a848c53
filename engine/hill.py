"""A Hill-type muscle after Thelen (2003), as OpenSim's ``Thelen2003Muscle`` computes it, at
rest: a contractile fibre and a passive element side by side, pennate at constant thickness,
in series with an elastic tendon.

Thelen, "Adjustment of muscle mechanics model parameters to simulate dynamic contractions
in older adults", J Biomech Eng 125 (2003) 70-77; the curves as OpenSim 4.6 writes them
(``OpenSim/Actuators/Thelen2003Muscle.cpp``), which ``tests/engine/test_arm26_forces.py``
checks against OpenSim's own numbers. With ``n`` the fibre length over its optimal length:

- active force-length: ``fal(n) = exp(-(n - 1)^2 / active_shape)``;
- passive force-length: ``fpe(n) = (exp(passive_shape (n - 1) / passive_strain) - 1) /
  (exp(passive_shape) - 1)`` above ``n = 1``, 0 below;
- tendon force-strain (strain ``e``, ``e0`` the tendon strain at the maximum isometric
  force): exponential up to ``e_toe``, linear after, ``fse = 0.33 (exp(3 e / e_toe) - 1) /
  (exp(3) - 1)``, then ``0.33 + k_lin (e - e_toe)``, with OpenSim's exact ``e_toe = 99 e0
  e^3 / (166 e^3 - 67)`` (Thelen rounds it to ``0.609 e0``) and ``k_lin = 0.67 / (e0 -
  e_toe)``; 0 when the tendon is slack;
- pennation at constant thickness: the fibre's height ``h = optimal_fibre_length
  sin(pennation)`` stays, so ``sin(phi) = h / fibre_length``, and the fibre may shorten
  only to where ``phi`` reaches OpenSim's maximum pennation, ``acos(0.1)``;
- activation from the muscle's ``minimum_activation`` (OpenSim raises anything below it to
  it) to 1.

At rest the fibre does not move, so the force-velocity multiplier is 1 and Thelen's
velocity constants (``Af``, ``Flen``) play no part. Equilibrium: the fibre's force along the
tendon equals the tendon's,

    Fmax (a fal(n) + fpe(n)) cos(phi) = Fmax fse((length - x) / tendon_slack_length - 1),

with ``x = fibre_length cos(phi)`` the fibre's length along the tendon. It is solved for
``x`` by Newton's method kept inside a bracket that shrinks by bisection whenever a Newton
step would leave it: ``x`` lies between the shortest fibre and the fibre that leaves the
tendon slack (where the fibre pulls and the tendon does not, so the error is positive);
until the force error is at most ``FORCE_TOLERANCE`` times the maximum isometric force, or
the bracket is narrower than ``LENGTH_TOLERANCE``. Where the error is positive even at the
shortest fibre (a musculotendon path shorter than the tendon at rest and the shortest
fibre), the fibre stays at its shortest, as OpenSim clamps it, and the tendon carries what
its own length gives (nothing, when slack).

Units: lengths in cm, forces in N, ``pennation`` in degrees. Arrays broadcast: a length
``(k,)`` and one activation give ``(k,)`` of everything.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Sequence

import numpy as np

MAXIMUM_PENNATION = math.acos(0.1)
"""OpenSim's maximum pennation angle for a Thelen2003Muscle (radians, 84.26 degrees): the
fibre shortens no further than this (arm26 leaves it at OpenSim's default)."""

FORCE_TOLERANCE = 1e-12
"""The largest force error of a solved equilibrium, over the maximum isometric force (OpenSim
stops at 1e-8)."""

LENGTH_TOLERANCE = 1e-12
"""The narrowest bracket (cm) the solver works to, where the force error cannot shrink
further in floating point."""

MOST_STEPS = 200
"""Solver steps: bisection alone would halve a 100 cm bracket to 1e-12 cm in 47."""

TOE_FORCE = 0.33
TOE_SHAPE = 3.0
"""The tendon's toe region: the normalised force at which the curve turns linear, and the
exponential's shape (Thelen 2003, as OpenSim)."""


@dataclass(frozen=True)
class HillParameters:
    """One muscle's Hill-type parameters (``engine/arm26_forces.py`` has arm26's six); or
    several muscles', each field an array (:func:`stacked`)."""

    max_isometric_force: float  # N
    optimal_fibre_length: float  # cm
    tendon_slack_length: float  # cm
    pennation: float  # degrees, at the optimal fibre length
    tendon_strain: float  # the tendon's strain at the maximum isometric force (FmaxTendonStrain)
    passive_strain: float  # fibre strain at which the passive force is Fmax (FmaxMuscleStrain)
    active_shape: float  # the active force-length Gaussian's width (KshapeActive)
    passive_shape: float  # the passive force-length exponential's shape (KshapePassive)
    minimum_activation: float  # activations below it act as it

    @property
    def height(self):
        """The fibre's constant height across the muscle (cm): ``h`` of the pennation."""
        return self.optimal_fibre_length * np.sin(np.radians(self.pennation))


def stacked(parameters: Sequence[HillParameters]) -> HillParameters:
    """Several muscles' parameters as one, each field an (n,) array, to solve them together:
    :func:`equilibrate` broadcasts them against lengths (..., n)."""
    return HillParameters(*(np.array([getattr(p, field.name) for p in parameters])
                            for field in fields(HillParameters)))


@dataclass(frozen=True)
class Equilibrium:
    """A muscle at rest at some musculotendon lengths and activations: arrays of one shape,
    float64. Forces in N: the active and passive along the fibre, the tendon's along the
    tendon, ``(active + passive) cos(pennation)`` once solved."""

    activation: np.ndarray  # as it acts: raised to the minimum, at most 1
    fibre_length: np.ndarray  # cm
    normalised_fibre_length: np.ndarray  # over the optimal fibre length
    pennation: np.ndarray  # radians
    active_force: np.ndarray
    passive_force: np.ndarray
    tendon_force: np.ndarray
    force_per_activation: np.ndarray  # N: d(tendon force)/d(activation), from within 0 to 1
    error: np.ndarray  # N: fibre force along the tendon less the tendon's


def active_force_length(n: np.ndarray, p: HillParameters) -> tuple[np.ndarray, np.ndarray]:
    """``fal`` at normalised fibre lengths ``n``, and its slope."""
    fal = np.exp(-((n - 1.0) ** 2) / p.active_shape)
    return fal, -2.0 * (n - 1.0) / p.active_shape * fal


def passive_force_length(n: np.ndarray, p: HillParameters) -> tuple[np.ndarray, np.ndarray]:
    """``fpe`` at normalised fibre lengths ``n``, and its slope."""
    stretched = n > 1.0
    rise = np.exp(p.passive_shape * np.where(stretched, n - 1.0, 0.0) / p.passive_strain)
    scale = 1.0 / np.expm1(p.passive_shape)
    fpe = np.where(stretched, (rise - 1.0) * scale, 0.0)
    return fpe, np.where(stretched, p.passive_shape / p.passive_strain * rise * scale, 0.0)


def tendon_force_strain(strain: np.ndarray, p: HillParameters) -> tuple[np.ndarray, np.ndarray]:
    """``fse`` at tendon strains ``strain``, and its slope."""
    e0, e3 = p.tendon_strain, np.exp(TOE_SHAPE)
    toe = 99.0 * e0 * e3 / (166.0 * e3 - 67.0)
    linear = (1.0 - TOE_FORCE) / (e0 - toe)
    scale = TOE_FORCE / np.expm1(TOE_SHAPE)
    curve = np.exp(TOE_SHAPE * np.clip(strain, 0.0, toe) / toe)
    fse = np.where(strain > toe, TOE_FORCE + linear * (strain - toe),
                   np.where(strain > 0.0, scale * (curve - 1.0), 0.0))
    slope = np.where(strain > toe, linear,
                     np.where(strain > 0.0, scale * TOE_SHAPE / toe * curve, 0.0))
    return fse, slope


def equilibrate(p: HillParameters, length, activation, near=None) -> Equilibrium:
    """The muscle at rest at musculotendon ``length`` (cm) and ``activation`` (0 to 1),
    either of them an array: the fibre length that balances fibre and tendon, and the
    forces it gives. ``near``: an equilibrium close by (at a nearby activation, say) to
    start from, rather than OpenSim's starting point; the answer is the same."""
    length, activation, low = np.broadcast_arrays(
        np.asarray(length, dtype=float), np.asarray(activation, dtype=float),
        p.height / math.tan(MAXIMUM_PENNATION))  # low: the shortest fibre, along the tendon
    acting = np.clip(activation, p.minimum_activation, 1.0)
    high = length - p.tendon_slack_length  # the tendon just slack
    clamped = (high <= low) | (_Balance(p, length, acting, low).error >= 0.0)
    high = np.where(clamped, low, high)
    # OpenSim's starting point: the tendon 1 % past slack.
    start = (length - 1.01 * p.tendon_slack_length if near is None
             else near.fibre_length * np.cos(near.pennation))
    along = np.clip(start, low, high)
    tolerance = FORCE_TOLERANCE * p.max_isometric_force
    for _ in range(MOST_STEPS):
        balance = _Balance(p, length, acting, along)
        error = balance.error
        done = clamped | (np.abs(error) <= tolerance) | (high - low <= LENGTH_TOLERANCE)
        if done.all():
            break
        low = np.where(error < 0.0, along, low)
        high = np.where(error > 0.0, along, high)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = along - error / balance.slope
        inside = np.isfinite(newton) & (newton > low) & (newton < high)
        along = np.where(done, along, np.where(inside, newton, 0.5 * (low + high)))
    else:
        balance = _Balance(p, length, acting, along)
    fmax = p.max_isometric_force
    # Implicitly: d(error)/d(activation) = Fmax fal cos(phi) moves the fibre by -that/slope,
    # and the tendon's force by Fmax fse' / tendon_slack_length per cm the fibre shortens.
    # Nothing moves with a clamped fibre, nor below the minimum activation.
    with np.errstate(divide="ignore", invalid="ignore"):
        per_activation = (fmax * balance.fse_slope / p.tendon_slack_length
                          * fmax * balance.fal * balance.cosine / balance.slope)
    moving = ~clamped & (activation >= p.minimum_activation)
    return Equilibrium(
        activation=acting,
        fibre_length=balance.fibre,
        normalised_fibre_length=balance.fibre / p.optimal_fibre_length,
        pennation=np.arccos(np.clip(balance.cosine, -1.0, 1.0)),
        active_force=fmax * acting * balance.fal,
        passive_force=fmax * balance.fpe,
        tendon_force=fmax * balance.fse,
        force_per_activation=np.where(moving, per_activation, 0.0),
        error=balance.error,
    )


class _Balance:
    """Fibre and tendon with the fibre ``along`` cm along the tendon: the fibre's length
    (cm) and its pennation's cosine, the curves' values there, the force error (N, the
    fibre's pull along the tendon less the tendon's) and its slope in ``along`` (N/cm)."""

    def __init__(self, p: HillParameters, length, acting, along) -> None:
        self.fibre = np.hypot(along, p.height)
        with np.errstate(divide="ignore", invalid="ignore"):
            self.cosine = np.where(p.height == 0.0, 1.0, along / self.fibre)
            # d(fibre)/d(along) = cos(phi); d(cos(phi))/d(along) = h^2 / fibre^3.
            bending = np.where(self.fibre > 0.0, p.height ** 2 / self.fibre ** 3, 0.0)
        n = self.fibre / p.optimal_fibre_length
        self.fal, fal_slope = active_force_length(n, p)
        self.fpe, fpe_slope = passive_force_length(n, p)
        self.fse, self.fse_slope = tendon_force_strain(
            (length - along) / p.tendon_slack_length - 1.0, p)
        fibre_force = acting * self.fal + self.fpe
        fmax = p.max_isometric_force
        self.error = fmax * (fibre_force * self.cosine - self.fse)
        self.slope = fmax * ((acting * fal_slope + fpe_slope) / p.optimal_fibre_length
                             * self.cosine ** 2 + fibre_force * bending
                             + self.fse_slope / p.tendon_slack_length)
