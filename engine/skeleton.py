"""The arm skeleton: two rods hinged at the elbow, with the muscle's attachments on them.

The muscle runs straight from its origin on the upper arm (``a`` cm from the elbow) to its
insertion on the forearm (``b`` cm from the elbow), so its length ``L`` is the third side of
a triangle and the elbow's interior angle follows from the law of cosines (SPEC 2.3):
``theta = arccos((a^2 + b^2 - L^2) / (2 a b))``. Flexion is ``180 - theta`` degrees: 0 with
the arm straight, growing as the muscle shortens.

Placement in world space (see ``engine/__init__``): the elbow at the origin, the upper arm
along ``+y``, the forearm swinging from ``-y`` (straight) towards ``+x`` as the elbow bends.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from biceps.engine.errors import RefusedChange


@dataclass(frozen=True)
class ArmPose:
    """The skeleton's key points at one length, each (3,) float64 in world space (cm)."""

    shoulder: np.ndarray  # the upper arm's free end
    origin: np.ndarray  # the muscle's attachment on the upper arm
    elbow: np.ndarray
    insertion: np.ndarray  # the muscle's attachment on the forearm
    hand: np.ndarray  # the forearm's free end


@dataclass(frozen=True)
class Skeleton:
    """Bone lengths and attachment distances (cm), and the joint's range (degrees of flexion).

    The seed's four distances are ``upper_arm - origin_to_elbow`` (free end of the upper arm
    to the origin; negative when the origin sits above the bone, on the shoulder blade, as
    the biceps' long head does), ``origin_to_elbow``, ``elbow_to_insertion`` and ``forearm -
    elbow_to_insertion``.
    """

    upper_arm: float = 29.1
    origin_to_elbow: float = 30.2
    elbow_to_insertion: float = 5.4
    forearm: float = 25.4
    min_flexion: float = 0.0
    max_flexion: float = 130.0

    def interior_angle(self, length: float) -> float:
        """The elbow's interior angle (radians) when the muscle is ``length`` cm long."""
        a, b = self.origin_to_elbow, self.elbow_to_insertion
        cosine = (a * a + b * b - length * length) / (2.0 * a * b)
        # Clamped: at a straight arm rounding can push the cosine a hair past -1.
        return float(np.arccos(np.clip(cosine, -1.0, 1.0)))

    def flexion(self, length: float) -> float:
        """Elbow flexion in degrees: 0 with the arm straight."""
        return 180.0 - float(np.degrees(self.interior_angle(length)))

    def length_at(self, flexion: float) -> float:
        """The muscle length (cm) that puts the elbow at ``flexion`` degrees."""
        a, b = self.origin_to_elbow, self.elbow_to_insertion
        theta = np.radians(180.0 - flexion)
        return float(np.sqrt(max(a * a + b * b - 2.0 * a * b * np.cos(theta), 0.0)))

    def length_range(self) -> tuple[float, float]:
        """The shortest and longest muscle (cm) the joint's range allows.

        The law of cosines makes the length grow with the interior angle, so the most
        flexed pose gives the shortest muscle. Every length of the joint's range lies within
        the triangle's ``|a - b| <= L <= a + b``.
        """
        return self.length_at(self.max_flexion), self.length_at(self.min_flexion)

    def pose(self, length: float) -> ArmPose:
        """The skeleton's key points when the muscle is ``length`` cm long."""
        theta = self.interior_angle(length)
        up = np.array([0.0, 1.0, 0.0])
        forearm = np.array([np.sin(theta), np.cos(theta), 0.0])
        return ArmPose(
            shoulder=self.upper_arm * up,
            origin=self.origin_to_elbow * up,
            elbow=np.zeros(3),
            insertion=self.elbow_to_insertion * forearm,
            hand=self.forearm * forearm,
        )


def check_skeleton(skeleton: Skeleton) -> None:
    """Raise :class:`RefusedChange` unless every distance and the joint's range make sense."""
    for name in ("upper_arm", "origin_to_elbow", "elbow_to_insertion", "forearm"):
        value = getattr(skeleton, name)
        if not np.isfinite(value) or value <= 0:
            raise RefusedChange(f"skeleton {name} must be above 0 cm, got {value}")
    low, high = skeleton.min_flexion, skeleton.max_flexion
    if not 0.0 <= low < high <= 180.0:
        raise RefusedChange(
            f"flexion range must satisfy 0 <= min_flexion < max_flexion <= 180 degrees, "
            f"got {low} to {high}"
        )
