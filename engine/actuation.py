"""The elbow's muscles as actuators: at a pose and an activation, each muscle's forces and its
torque about the elbow.

Every musculotendon length and moment arm comes from one call, :func:`musculotendon`: the
length of each muscle's path at that flexion and its moment arm, ``-dL/dtheta`` of that path
(the tendon-excursion method, which is what OpenSim reports), both from the arm's paths
(``engine/path.py``; arm26's via points and wrapping surfaces on ``configs/elbow.toml``), as
:attr:`Arm.lengths` and :attr:`Arm.moment_arms` give them at the arm's own pose, so that a
better path changes every number here and nothing else. The forces are the Hill-type
model's at rest (``engine/hill.py``).

Units: lengths and moment arms in cm, forces in N, torques in N m, positive where they
flex the elbow.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from biceps.engine.hill import HillParameters, equilibrate, stacked

if TYPE_CHECKING:
    from biceps.engine.arm import Arm


def musculotendon(arm: Arm, flexion: float) -> tuple[np.ndarray, np.ndarray]:
    """Each muscle's musculotendon length and moment arm about the elbow (both (n,) cm, in
    the order of ``arm.names``) with the elbow at ``flexion`` degrees."""
    paths = arm.paths
    return (np.array([path.length_at(flexion) for path in paths]),
            np.array([path.moment_arm_at(flexion) for path in paths]))


def musculotendon_across(arm: Arm, flexions: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`musculotendon` at each of ``flexions`` (k,) degrees: lengths and moment arms,
    both (k, n) cm."""
    geometry = [musculotendon(arm, flexion) for flexion in flexions]
    count = len(arm.names)
    return (np.array([length for length, _ in geometry]).reshape(len(flexions), count),
            np.array([arms for _, arms in geometry]).reshape(len(flexions), count))


@dataclass(frozen=True)
class MuscleForce:
    """One muscle at rest at one pose and activation."""

    name: str
    length: float  # cm, the whole musculotendon path
    moment_arm: float  # cm
    activation: float  # as it acts (raised to the muscle's minimum)
    fibre_length: float  # cm
    normalised_fibre_length: float
    pennation: float  # degrees
    active_force: float  # N, along the fibre
    passive_force: float  # N, along the fibre
    tendon_force: float  # N
    torque: float  # N m about the elbow, positive flexing

    def record(self) -> dict[str, Any]:
        """The muscle's numbers as plain data, named with their units (:data:`RECORD`)."""
        return {key: getattr(self, field) for field, key in RECORD}


RECORD = (("name", "name"), ("activation", "activation"),
          ("length", "musculotendon_length_cm"), ("moment_arm", "moment_arm_cm"),
          ("fibre_length", "fibre_length_cm"),
          ("normalised_fibre_length", "normalised_fibre_length"), ("pennation", "pennation_deg"),
          ("active_force", "active_force_n"), ("passive_force", "passive_force_n"),
          ("tendon_force", "tendon_force_n"), ("torque", "torque_nm"))
"""Each field of :class:`MuscleForce` and its name in ``sweep`` and ``hold``'s output, in
their order there."""


def torque(tendon_force, moment_arm):
    """N m from a force in N and a moment arm in cm."""
    return tendon_force * moment_arm / 100.0


def muscle_forces(names: Sequence[str], parameters: Sequence[HillParameters],
                  lengths: np.ndarray, moment_arms: np.ndarray,
                  activations) -> list[list[MuscleForce]]:
    """Every muscle at every pose: ``lengths`` and ``moment_arms`` (k, n) cm for k poses of
    n muscles (``names``, ``parameters``), ``activations`` one for all, (n,) or (k, n); a
    list of k poses, each a list of n muscles."""
    state = equilibrate(stacked(parameters), lengths, activations)
    torques = torque(state.tendon_force, moment_arms)
    pennation = np.degrees(state.pennation)
    return [[MuscleForce(name, *(float(each[k, i]) for each in (
        lengths, moment_arms, state.activation, state.fibre_length,
        state.normalised_fibre_length, pennation, state.active_force, state.passive_force,
        state.tendon_force, torques))) for i, name in enumerate(names)]
        for k in range(lengths.shape[0])]


def forces_across(arm: Arm, parameters: Sequence[HillParameters], flexions: Sequence[float],
                  activation: float) -> list[list[MuscleForce]]:
    """Every muscle of ``arm`` at each of ``flexions`` (degrees), all at ``activation``."""
    lengths, moment_arms = musculotendon_across(arm, flexions)
    return muscle_forces(arm.names, parameters, lengths, moment_arms, activation)
