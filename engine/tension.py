"""An active muscle's shape: at the same length and the same volume, its belly thicker and
the ends of the belly thinner, as a tensed muscle bunches up (Scheepers, Parent, Carlson
and May 1997, "Anatomy-based modeling of the human musculature": a belly's tension moves
its cross-section from its ends to its middle, its volume kept).

With the growth coefficients ``m`` (what makes a node belly rather than tendon, SPEC 2) and
``g = m / max(m)``, the radii ``r`` of the muscle at its length become

    r' = r + alpha m g + beta m,

``alpha`` chosen by the activation (``TENSION`` of the largest radius at full activation,
where ``g`` is 1) and ``beta`` the step that gives the volume back: the volume law of the
length change (``engine/muscle.py``), solved exactly from ``r + alpha m g`` with the growth
``m`` at the same spacing. ``beta`` is negative, so the nodes that grow least lose radius
and the middle gains, the crossing where ``g = -beta / alpha``; tendon nodes (``m = 0``) are
left as they are.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Sequence

from biceps.engine.muscle import Muscle, volume_step

if TYPE_CHECKING:
    from biceps.engine.arm import Arm

TENSION = 0.6
"""``alpha`` at full activation, over the largest radius and growth: once the volume is
given back, the thickest node of a fully active belly is 8 to 10 % thicker and the ends of
the belly 15 to 25 % thinner (configs/elbow.toml's six at 0, 60 and 130 degrees), which
shows at a glance beside the thickening of a contraction over the elbow's range."""


def tensed(muscle: Muscle, activation: float) -> Muscle:
    """``muscle`` at the same length and volume with its belly tensed by ``activation`` (0
    to 1): its radii as above, every other property (its rest, its length) the same, so its
    volume, computed again from the new radii, is the one conserved."""
    if activation <= 0.0:
        return muscle
    growth = muscle.growth
    share = growth / growth.max()
    alpha = TENSION * min(activation, 1.0) * muscle.max_radius / growth.max()
    bulged = muscle.radii + alpha * growth * share
    beta = volume_step(bulged, growth, muscle.length, muscle.reference_volume,
                       muscle.volume_mode)
    if beta is None:  # the ends cannot give enough: no tension shown
        return muscle
    radii = bulged + beta * growth
    radii.flags.writeable = False
    return replace(muscle, radii=radii)


def tensed_arm(arm: Arm, activations: Sequence[float]) -> Arm:
    """``arm`` with each muscle (in the order of ``arm.names``) tensed by its activation."""
    if not activations:
        return arm
    companions = tuple(replace(companion, muscle=tensed(companion.muscle, activation))
                       for companion, activation in zip(arm.companions, activations[1:]))
    return replace(arm, muscle=tensed(arm.muscle, activations[0]), companions=companions)
