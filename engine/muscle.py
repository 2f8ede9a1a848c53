"""The muscle: a chain of frusta whose volume stays exactly constant as its length changes.

A muscle is ``n >= 2`` nodes equally spaced along its axis, node ``i`` with a radius
``r_i > 0`` and a growth coefficient ``m_i >= 0``. Changing the length from ``L`` to ``L'``
moves every radius by one step ``d`` scaled by its growth, ``r_i' = r_i + m_i d``, where
``d`` keeps the volume (SPEC 2.2). The volume is a cubic in ``d`` (a quadratic without the
end caps), strictly increasing where every radius is positive, so the root is unique.

The state is a function of the length alone: every length is solved from the reference
(rest) shape, never from the previous step, so no sequence of changes can drift. Editing a
node makes the edited current shape the new reference. A :class:`Muscle` is immutable;
every change returns a new one or raises :class:`RefusedChange` and leaves this one as is.

Node numbers in messages are 1-based, as a person counts them in the node table.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from biceps.engine.bounds import (GROWING, GROWTH, NODES, RADIUS, Limits, OutOfBounds, cm,
                                  finite)
from biceps.engine.errors import RefusedChange

VolumeMode = Literal["closed", "frusta"]
VOLUME_MODES: tuple[VolumeMode, ...] = ("closed", "frusta")

_NEWTON_MAX_STEPS = 200

VOLUME_TOLERANCE = 1e-12
"""The largest relative volume error a length change may leave (SPEC 2.2)."""


def frusta_sum(radii: np.ndarray) -> float:
    """``Q(R) = sum (r_i^2 + r_i r_{i+1} + r_{i+1}^2) / 3``: the frusta volume over ``pi dx``.

    radii: (n,) float64.
    """
    left, right = radii[:-1], radii[1:]
    return float(np.sum(left * left + left * right + right * right)) / 3.0


def volume(radii: np.ndarray, length: float, mode: VolumeMode = "closed") -> float:
    """The volume (cm^3) of the solid of revolution of the profile ``radii`` over ``length``.

    ``frusta`` is the stack of truncated cones alone (the seed's definition); ``closed``
    adds the two hemispherical end caps, which is what is drawn.
    """
    dx = length / (len(radii) - 1)
    over_pi = dx * frusta_sum(radii)
    if mode == "closed":
        over_pi += 2.0 / 3.0 * (radii[0] ** 3 + radii[-1] ** 3)
    return float(np.pi * over_pi)


def _read_only(values: np.ndarray) -> np.ndarray:
    values = np.array(values, dtype=np.float64)
    values.flags.writeable = False
    return values


@dataclass(frozen=True)
class _VolumeLaw:
    """The volume over ``pi`` as a polynomial in the step ``d``, for a given spacing ``dx``.

    ``V(d) / pi = dx (a d^2 + b d + c) + caps(d)``, with ``caps(d) = 2/3 ((r_1 + m_1 d)^3 +
    (r_n + m_n d)^3)`` in the closed mode and zero otherwise. The coefficients depend only on
    the reference shape, so a length change costs O(1) plus the O(n) update of the radii.
    """

    a: float
    b: float
    c: float
    ends: tuple[tuple[float, float], ...]  # (radius, growth) of each capped end; none if frusta
    lowest_step: float  # the step at which the first radius with growth reaches zero
    thinnest_step: float  # the step at which the first radius with growth thins to the bound
    first_to_thin: int  # the index of that node

    @classmethod
    def of(cls, radii: np.ndarray, growth: np.ndarray, closed: bool) -> _VolumeLaw:
        r0, r1 = radii[:-1], radii[1:]
        m0, m1 = growth[:-1], growth[1:]
        # Expanding (r_i + m_i d)^2 + (r_i + m_i d)(r_j + m_j d) + (r_j + m_j d)^2, the
        # frustum formula with the stepped radii (SPEC 2.2; the seed's A and B are wrong).
        a = float(np.sum(m0 * m0 + m0 * m1 + m1 * m1)) / 3.0
        b = float(np.sum(2 * r0 * m0 + r0 * m1 + r1 * m0 + 2 * r1 * m1)) / 3.0
        c = frusta_sum(radii)
        growing = growth > 0

        def reaching(radius: float) -> np.ndarray:
            # The step at which each growing node's radius is ``radius``. A vanishingly
            # small growth overflows to -inf: that node never gets there.
            steps = np.full(len(radii), -np.inf)
            with np.errstate(over="ignore"):
                steps[growing] = (radius - radii[growing]) / growth[growing]
            return steps

        # A stretch stops where a node thins to the smallest radius the model takes (the
        # bound a file and a dialog give a radius), a hair above it, so that rounding in the
        # solve cannot take it below.
        limits, thinnest = reaching(0.0), reaching(RADIUS.low * (1.0 + 1e-6))
        thin = int(np.argmax(thinnest))
        # Plain floats: the solver evaluates these a few times per change, and numpy's
        # per-call overhead on two-element arrays would dominate it.
        ends = ((float(radii[0]), float(growth[0])), (float(radii[-1]), float(growth[-1])))
        return cls(a, b, c, ends if closed else (), float(limits.max()),
                   min(float(thinnest[thin]), 0.0), thin)

    def over_pi(self, step: float, dx: float) -> float:
        return dx * ((self.a * step + self.b) * step + self.c) + self.caps(step)

    def slope(self, step: float, dx: float) -> float:
        """The derivative of :meth:`over_pi` with respect to the step."""
        caps = sum(2.0 * m * (r + m * step) ** 2 for r, m in self.ends)
        return dx * (2.0 * self.a * step + self.b) + caps

    def caps(self, step: float) -> float:
        return 2.0 / 3.0 * sum((r + m * step) ** 3 for r, m in self.ends)

    def solve(self, target: float, dx: float) -> float | None:
        """The step ``d`` with ``over_pi(d, dx) == target`` and every radius positive.

        ``None`` when there is none (the muscle would have to thin past zero). In terms of
        ``t = d - lowest_step`` every stepped radius is a linear function with non-negative
        coefficients, so ``over_pi`` is increasing and convex on the feasible interval; Newton's
        method started right of the root then falls monotonically onto it and cannot overshoot.
        """
        if self.over_pi(self.lowest_step, dx) >= target:
            return None
        step = 0.0
        excess = self.over_pi(step, dx) - target
        if excess < 0:
            # b, c and the caps only grow for d >= 0, so dx a d^2 >= -excess is enough.
            step = float(np.sqrt(-excess / (dx * self.a)))
            excess = self.over_pi(step, dx) - target
        for _ in range(_NEWTON_MAX_STEPS):
            if excess <= 0:
                break
            next_step = step - excess / self.slope(step, dx)
            if not next_step < step:  # converged to the last representable point
                break
            step = next_step
            excess = self.over_pi(step, dx) - target
        return step

    def length_at(self, step: float, target: float, segments: int) -> float:
        """The length at which ``step`` keeps the volume (``inf`` if none does)."""
        if not np.isfinite(step):
            return float("inf")
        spaced = (self.a * step + self.b) * step + self.c
        room = target - self.caps(step)
        if spaced <= 0 or room <= 0:
            return float("inf")
        return segments * room / spaced


def volume_step(radii: np.ndarray, growth: np.ndarray, length: float, target: float,
                mode: VolumeMode = "closed") -> float | None:
    """The step ``d`` at which ``radii + d growth`` (both (n,)) over ``length`` cm has the
    volume ``target`` cm^3, every radius positive; None if there is none. The length
    change's own solve (SPEC 2.2), for a shape other than a rest."""
    law = _VolumeLaw.of(radii, growth, mode == "closed")
    return law.solve(target / np.pi, length / (len(radii) - 1))


@dataclass(frozen=True, eq=False)
class _Rest:
    """The reference shape a muscle is solved from. Every length of one muscle shares it,
    so what depends on it alone (the volume law, the conserved volume) is worked out once,
    not at every length change."""

    radii: np.ndarray  # (n,) float64, read-only
    growth: np.ndarray  # (n,) float64, read-only
    length: float
    volume_mode: VolumeMode

    @cached_property
    def volume(self) -> float:
        return volume(self.radii, self.length, self.volume_mode)

    @cached_property
    def law(self) -> _VolumeLaw:
        return _VolumeLaw.of(self.radii, self.growth, self.volume_mode == "closed")

    @cached_property
    def longest_length(self) -> float:
        return self.law.length_at(self.law.thinnest_step, self.volume / np.pi,
                                  len(self.radii) - 1)


@dataclass(frozen=True, eq=False)
class Muscle:
    """A muscle at some length, together with the reference shape it is solved from.

    Build one with :meth:`Muscle.of`. ``radii`` are the current radii (cm), ``length`` the
    current length (cm); the reference (rest) shape is the one whose volume is conserved.
    """

    rest: _Rest
    length: float
    radii: np.ndarray  # (n,) float64, read-only
    step: float  # the d of SPEC 2.2 that takes the reference to this length

    @classmethod
    def of(
        cls,
        radii: np.ndarray | list[float],
        growth: np.ndarray | list[float],
        length: float,
        volume_mode: VolumeMode = "closed",
    ) -> Muscle:
        """A muscle at rest with this profile; raises :class:`RefusedChange` if invalid."""
        radii = _read_only(radii)
        growth = _read_only(growth)
        _check_profile(radii, growth, length, volume_mode)
        return cls(_Rest(radii, growth, float(length), volume_mode), float(length), radii, 0.0)

    @property
    def reference_radii(self) -> np.ndarray:
        return self.rest.radii

    @property
    def growth(self) -> np.ndarray:
        """(n,) float64: each node's growth coefficient."""
        return self.rest.growth

    @property
    def reference_length(self) -> float:
        return self.rest.length

    @property
    def volume_mode(self) -> VolumeMode:
        return self.rest.volume_mode

    @property
    def node_count(self) -> int:
        return len(self.radii)

    @property
    def positions(self) -> np.ndarray:
        """(n,) float64: each node's distance (cm) from the muscle's origin."""
        return np.linspace(0.0, self.length, self.node_count)

    @cached_property
    def volume(self) -> float:
        """The volume (cm^3) of the current shape, computed directly from its radii."""
        return volume(self.radii, self.length, self.volume_mode)

    @property
    def reference_volume(self) -> float:
        """The volume (cm^3) every length change conserves."""
        return self.rest.volume

    @property
    def volume_error(self) -> float:
        """Relative difference between the current and the conserved volume."""
        return abs(self.volume - self.reference_volume) / self.reference_volume

    @property
    def max_radius(self) -> float:
        return float(self.radii.max())

    @property
    def girth(self) -> float:
        """The circumference (cm) at the thickest node."""
        return 2.0 * np.pi * self.max_radius

    @property
    def longest_length(self) -> float:
        """The longest this muscle can be (cm): where its first growing node thins to the
        smallest radius the model takes; ``inf`` if none ever does."""
        return self.rest.longest_length

    def at_length(self, length: float) -> Muscle:
        """This muscle contracted or stretched to ``length`` (cm) at the same volume."""
        length = float(length)
        if not np.isfinite(length) or length <= 0:
            raise RefusedChange(f"length must be a positive number of cm, got {length}")
        if length == self.length:
            return self
        if length > self.longest_length:
            raise RefusedChange(self._too_long_message(length))
        if length == self.reference_length:  # exactly the rest shape, not a 1e-17 step off it
            return Muscle(self.rest, length, self.reference_radii, 0.0)
        dx = length / (self.node_count - 1)
        step = self.rest.law.solve(self.reference_volume / np.pi, dx)
        if step is None:
            raise RefusedChange(self._too_long_message(length))
        radii = self.reference_radii + step * self.growth
        if not np.isfinite(step) or not np.all(np.isfinite(radii)):
            raise RefusedChange(
                f"cannot reach {cm(length)} cm: the growth coefficients are too small to keep "
                "the volume"
            )
        if radii.min() <= 0:
            raise RefusedChange(self._too_long_message(length))
        radii.flags.writeable = False
        muscle = Muscle(self.rest, length, radii, step)
        if not muscle.volume_error <= VOLUME_TOLERANCE:
            # Near the length at which a radius vanishes, the step is the difference of
            # nearly equal terms and loses digits: say so rather than show a wrong volume.
            raise RefusedChange(
                f"cannot reach {cm(length)} cm at constant volume: so close to node "
                f"{self.rest.law.first_to_thin + 1}'s vanishing the volume cannot be kept "
                f"to {VOLUME_TOLERANCE:g} (it would be off by {muscle.volume_error:.1e})"
            )
        return muscle

    def _too_long_message(self, length: float) -> str:
        return (
            f"cannot stretch to {cm(length)} cm: {self.thinnest_note()} at "
            f"{self.longest_length:.2f} cm, the longest this muscle can be"
        )

    def thinnest_note(self) -> str:
        """Which node stops a stretch, in words: ``node 1's radius would fall to zero``."""
        return f"node {self.rest.law.first_to_thin + 1}'s radius would fall to zero"

    def with_radius(self, index: int, radius: float) -> Muscle:
        """The current shape with node ``index`` (0-based) at ``radius`` cm, as a new rest."""
        self._check_index(index)
        radii = self.radii.copy()
        radii[index] = radius
        return self._redefined(radii, self.growth)

    def with_growth(self, index: int, growth: float) -> Muscle:
        """The current shape with node ``index`` (0-based) growing by ``growth``, as a new rest."""
        self._check_index(index)
        coefficients = self.growth.copy()
        coefficients[index] = growth
        return self._redefined(self.radii, coefficients)

    def with_node_inserted(self, index: int) -> Muscle:
        """A new node between ``index`` and ``index + 1`` with their mean radius and growth.

        The nodes stay equally spaced over the same length, so the profile and the volume
        change: the result is a new rest shape.
        """
        if not 0 <= index < self.node_count - 1:
            raise RefusedChange(
                f"a node goes between two neighbours: pick node 1 to {self.node_count - 1}, "
                f"not {index + 1}"
            )
        _check_count(self.node_count + 1, "another node")
        radii = np.insert(self.radii, index + 1, self.radii[index : index + 2].mean())
        growth = np.insert(self.growth, index + 1, self.growth[index : index + 2].mean())
        return self._redefined(radii, growth)

    def without_node(self, index: int) -> Muscle:
        """The muscle with node ``index`` removed (the rest stay equally spaced)."""
        self._check_index(index)
        if self.node_count <= 2:
            raise RefusedChange("a muscle needs at least 2 nodes; this one has 2")
        return self._redefined(np.delete(self.radii, index), np.delete(self.growth, index))

    def subdivided(self) -> Muscle:
        """A node at the middle of every segment, with the mean of its neighbours.

        The profile is a straight segment between nodes, so the midpoint lies on it: the
        shape and the volume are unchanged.
        """
        count = 2 * self.node_count - 1
        _check_count(count, "subdividing")
        radii = np.empty(count)
        growth = np.empty(count)
        radii[0::2], growth[0::2] = self.radii, self.growth
        radii[1::2] = (self.radii[:-1] + self.radii[1:]) / 2
        growth[1::2] = (self.growth[:-1] + self.growth[1:]) / 2
        return self._redefined(radii, growth)

    def with_volume_mode(self, mode: VolumeMode) -> Muscle:
        """The current shape as a new rest, conserving the ``closed`` or ``frusta`` volume."""
        return Muscle.of(self.radii, self.growth, self.length, mode)

    def _redefined(self, radii: np.ndarray, growth: np.ndarray) -> Muscle:
        return Muscle.of(radii, growth, self.length, self.volume_mode)

    def _check_index(self, index: int) -> None:
        if not 0 <= index < self.node_count:
            raise RefusedChange(f"there is no node {index + 1}: nodes are 1 to {self.node_count}")


def _check_count(count: int, doing: str) -> None:
    if count > NODES:
        raise RefusedChange(
            f"{doing} would make {count:,} nodes; a muscle has at most {NODES:,}, more than a "
            "picture can show apart, each a ring of its mesh"
        )


def _check_profile(
    radii: np.ndarray, growth: np.ndarray, length: float, volume_mode: str
) -> None:
    if radii.ndim != 1 or len(radii) < 2:
        raise RefusedChange(f"a muscle needs at least 2 nodes, got {radii.size}")
    if len(radii) > NODES:
        raise RefusedChange(f"a muscle has at most {NODES:,} nodes, not {len(radii):,}")
    if growth.shape != radii.shape:
        raise RefusedChange(
            f"every node needs a radius and a growth: {len(radii)} radii, {growth.size} growths"
        )
    for name, values, limits in (("radius", radii, RADIUS), ("growth", growth, GROWTH)):
        bad = _outside(values, limits)
        if bad is not None:
            try:
                finite(float(values[bad]), limits)
            except OutOfBounds as error:
                raise RefusedChange(f"node {bad + 1}: {name} {error}") from None
    if not growth.max() >= GROWING:
        raise RefusedChange(
            f"at least one node needs a growth of {GROWING:g} or more, or the muscle cannot "
            f"change length at constant volume (the largest here is {growth.max():g})"
        )
    if not np.isfinite(length) or length <= 0:
        raise RefusedChange(f"length must be above 0 cm, got {length}")
    if volume_mode not in VOLUME_MODES:
        raise RefusedChange(f"volume mode must be 'closed' or 'frusta', got {volume_mode!r}")


def _outside(values: np.ndarray, limits: Limits) -> int | None:
    """The index of the first of ``values`` that ``limits`` refuses (NaN among them), if any."""
    with np.errstate(invalid="ignore"):
        inside = (values >= limits.low) & (values <= limits.high)
    bad = np.flatnonzero(~inside)
    return int(bad[0]) if bad.size else None
