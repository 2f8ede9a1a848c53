"""A weight in the hand: the activations that hold it with the least effort (static
optimisation), or why none can.

The load: a mass in the hand (at the forearm's free end, the skeleton's ``forearm`` cm from
the elbow) and the forearm's own weight (arm26's mass at its centre of mass,
``engine/arm26_forces.py``), each pulling straight down, the upper arm hanging (the shoulder at
0). The muscles must give the torque that holds both still:

    minimise  sum(a_i^2)  over activations  a_min_i <= a_i <= 1
    so that   sum(torque_i(a_i)) = load torque,

``torque_i`` each muscle's tendon force at rest times its moment arm (``engine/hill.py``,
``engine/actuation.py``). The lower bound is each muscle's minimum activation (arm26's
``min_control``, 0.01, which is what OpenSim's own static optimisation takes).

Solved by sequential quadratic programming: each torque is replaced by its tangent at the
current activations, and the problem with that one linear constraint is solved exactly (its
solution is ``a_i = clip(lambda g_i / 2, a_min_i, 1)`` with ``g_i`` the torque's slope, and
the sum of ``g_i a_i`` is piecewise linear and non-decreasing in the multiplier ``lambda``,
so ``lambda`` follows from its breakpoints). A fixed point of that step satisfies the
Karush-Kuhn-Tucker conditions of the problem itself; the torques are nearly linear in the
activations (only the tendon's stretch bends them), so it converges in a few steps, to
``TORQUE_TOLERANCE``. No general solver is needed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Sequence

import numpy as np

from biceps.engine.actuation import (MuscleForce, muscle_forces, musculotendon,
                                     musculotendon_across, torque)
from biceps.engine.arm26_forces import FOREARM_CENTRE, FOREARM_MASS, GRAVITY
from biceps.engine.errors import RefusedChange
from biceps.engine.hill import Equilibrium, HillParameters, equilibrate, stacked

if TYPE_CHECKING:
    from biceps.engine.arm import Arm

TORQUE_TOLERANCE = 1e-9
"""N m: how far the muscles' torque may miss the load's once solved."""

MOST_STEPS = 100
"""Sequential steps before the solver gives up (it needs fewer than ten)."""


@dataclass(frozen=True)
class Load:
    """What the muscles must hold at ``flexion`` degrees: torques in N m, positive flexing."""

    flexion: float
    mass: float  # kg in the hand
    hand: float  # N m: the mass's torque
    forearm: float  # N m: the forearm's own weight's

    @property
    def torque(self) -> float:
        return self.hand + self.forearm


def load_at(forearm: float, flexion: float, mass: float) -> Load:
    """The torque to hold ``mass`` kg at the end of a forearm ``forearm`` cm long, and the
    forearm's own weight, at ``flexion`` degrees (the upper arm hanging, so the lever is
    the forearm's horizontal reach)."""
    reach = math.sin(math.radians(flexion)) / 100.0  # m per cm along the forearm
    return Load(flexion, mass, mass * GRAVITY * forearm * reach,
                FOREARM_MASS * GRAVITY * FOREARM_CENTRE * reach)


@dataclass(frozen=True)
class Hold:
    """The least-effort activations and what they do: every muscle, and the load."""

    load: Load
    muscles: list[MuscleForce]
    multiplier: float  # lambda: the cost's rise per N m more of load

    @property
    def torque(self) -> float:
        """The muscles' net torque about the elbow (N m)."""
        return sum(muscle.torque for muscle in self.muscles)

    @property
    def cost(self) -> float:
        return sum(muscle.activation ** 2 for muscle in self.muscles)


def hold(names: Sequence[str], parameters: Sequence[HillParameters], lengths: np.ndarray,
         moment_arms: np.ndarray, load: Load) -> Hold:
    """The activations of the muscles ``names`` (with ``parameters``, musculotendon
    ``lengths`` and ``moment_arms`` (n,) cm at the load's flexion) that hold ``load`` with
    the least sum of squares; :class:`RefusedChange` naming the strongest torque the muscles
    can give there if none can."""
    low = np.array([p.minimum_activation for p in parameters])
    high = np.ones(len(parameters))
    together = stacked(parameters)
    _check_reach(together, lengths, moment_arms, load, low, high)
    activations, state = low.copy(), None
    for _ in range(MOST_STEPS):
        torques, slopes, state = _torques(together, lengths, moment_arms, activations, state)
        target = load.torque - torques.sum() + slopes @ activations
        multiplier = _multiplier(slopes, low, high, target)
        following = np.clip(multiplier * slopes / 2.0, low, high)
        moved = np.max(np.abs(following - activations))
        activations = following
        if moved <= 1e-12 and abs(torques.sum() - load.torque) <= TORQUE_TOLERANCE:
            break
    torques, _, _ = _torques(together, lengths, moment_arms, activations, state)
    if abs(torques.sum() - load.torque) > TORQUE_TOLERANCE:  # never seen: said if it happens
        raise RefusedChange(f"the activations that hold {load.mass:g} kg at {load.flexion:g} "
                            "degrees could not be found (the solver did not converge)")
    muscles = muscle_forces(names, parameters, lengths[None, :], moment_arms[None, :],
                            activations)[0]
    return Hold(load, muscles, multiplier)


def hold_arm(arm: Arm, parameters: Sequence[HillParameters], flexion: float,
             mass: float) -> Hold:
    """:func:`hold` for every muscle of ``arm`` (``parameters`` in the order of its names),
    ``mass`` kg at the end of its forearm, the elbow at ``flexion`` degrees."""
    lengths, moment_arms = musculotendon(arm, flexion)
    return hold(arm.names, parameters, lengths, moment_arms,
                load_at(arm.skeleton.forearm, flexion, mass))


def _torques(parameters: HillParameters, lengths, moment_arms, activations,
             near: Equilibrium | None = None) -> tuple[np.ndarray, np.ndarray, Equilibrium]:
    """Each muscle's torque (N m) at ``activations``, its slope per unit activation, and the
    equilibrium they come from (``parameters`` :func:`stacked`; ``near``, the last step's,
    to start from)."""
    state = equilibrate(parameters, lengths, activations, near)
    return (torque(state.tendon_force, moment_arms),
            torque(state.force_per_activation, moment_arms), state)


def _multiplier(slopes: np.ndarray, low: np.ndarray, high: np.ndarray, target: float) -> float:
    """The ``lambda`` at which ``sum(g_i clip(lambda g_i / 2, low_i, high_i)) = target``
    (``g_i`` the ``slopes``), or the nearest end where the sum cannot reach it."""
    moving = slopes != 0.0
    knots = np.unique(np.concatenate([2.0 * low[moving] / slopes[moving],
                                      2.0 * high[moving] / slopes[moving]]))
    if knots.size == 0:
        return 0.0
    sums = np.array([slopes @ np.clip(knot * slopes / 2.0, low, high) for knot in knots])
    if target <= sums[0]:
        return float(knots[0])
    if target >= sums[-1]:
        return float(knots[-1])
    # The sum is linear between neighbouring knots.
    right = int(np.searchsorted(sums, target))
    left = right - 1
    share = (target - sums[left]) / (sums[right] - sums[left])
    return float(knots[left] + share * (knots[right] - knots[left]))


def _check_reach(parameters, lengths, moment_arms, load: Load, low, high) -> None:
    """Refuse a load beyond the strongest torque the muscles give at its flexion, either way:
    every flexor (positive moment arm) at full activation and every extensor at its least,
    or the other way round."""
    flexing = np.asarray(moment_arms) > 0.0
    strongest, _, _ = _torques(parameters, lengths, moment_arms, np.where(flexing, high, low))
    weakest, _, _ = _torques(parameters, lengths, moment_arms, np.where(flexing, low, high))
    most, least = strongest.sum(), weakest.sum()
    needed = load.torque
    if least <= needed <= most:
        return
    what = (f"{load.mass:g} kg in the hand at {load.flexion:g} degrees of flexion needs "
            f"{needed:.2f} N m at the elbow ({load.hand:.2f} for the load, {load.forearm:.2f} "
            "for the forearm's own weight)")
    if needed > most:
        per_kg = load.hand / load.mass if load.mass > 0.0 else 0.0
        # Rounded down, so that the mass named can be held.
        heaviest = (f": at most {math.floor((most - load.forearm) / per_kg * 100) / 100:.2f} "
                    "kg there"
                    if per_kg > 0.0 and most > load.forearm else "")
        raise RefusedChange(f"{what}, but the strongest the muscles can hold there is "
                            f"{most:.2f} N m (every flexor fully active){heaviest}")
    raise RefusedChange(f"{what}, but the muscles' passive pull flexes it by {least:.2f} N m "
                        "even with every extensor fully active")


@dataclass(frozen=True)
class Effort:
    """What the muscles do at a pose when asked for an activation or to hold a mass: every
    muscle (its activation, forces, torque), the load when there is a mass, and why it
    cannot be held when it cannot (the muscles then at their strongest)."""

    muscles: list[MuscleForce]
    load: Load | None = None
    refusal: str | None = None

    @property
    def activations(self) -> tuple[float, ...]:
        return tuple(muscle.activation for muscle in self.muscles)

    @property
    def torque(self) -> float:
        """The muscles' net torque about the elbow (N m)."""
        return sum(muscle.torque for muscle in self.muscles)


def effort(arm: Arm, parameters: Sequence[HillParameters], activation: float,
           mass: float) -> Effort:
    """The muscles of ``arm`` at its flexion: each at ``activation``, or, with a ``mass``
    (kg, above 0) in the hand, at the least-effort activations that hold it."""
    flexion = arm.flexion
    lengths, moment_arms = musculotendon(arm, flexion)
    if mass <= 0.0:
        return Effort(muscle_forces(arm.names, parameters, lengths[None, :],
                                    moment_arms[None, :], activation)[0])
    load = load_at(arm.skeleton.forearm, flexion, mass)
    try:
        held = hold(arm.names, parameters, lengths, moment_arms, load)
    except RefusedChange as refusal:
        return Effort(muscle_forces(arm.names, parameters, lengths[None, :],
                                    moment_arms[None, :],
                                    strongest_activations(parameters, moment_arms))[0],
                      load, str(refusal))
    return Effort(held.muscles, load)


def strongest_activations(parameters: Sequence[HillParameters],
                          moment_arms: np.ndarray) -> np.ndarray:
    """The activations (same shape as ``moment_arms``, (n,) or (k, n) cm) that flex the
    elbow hardest: every flexor (a positive moment arm) fully active, every extensor at its
    least."""
    return np.where(moment_arms > 0.0, 1.0, [p.minimum_activation for p in parameters])


def strongest_torques(arm: Arm, parameters: Sequence[HillParameters],
                      flexions: Sequence[float]) -> np.ndarray:
    """The strongest torque (N m) the muscles of ``arm`` can flex the elbow with at each of
    ``flexions`` (k,) degrees: (k,)."""
    lengths, moment_arms = musculotendon_across(arm, flexions)
    state = equilibrate(stacked(parameters), lengths,
                        strongest_activations(parameters, moment_arms))
    return torque(state.tendon_force, moment_arms).sum(axis=1)
