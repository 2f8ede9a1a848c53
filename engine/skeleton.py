"""The arm skeleton: the upper arm and the forearm hinged at the elbow, and the points where
a muscle is fixed to them.

Frames (see ``engine/__init__``): the elbow's centre is the origin and its axis is ``z``.
The upper arm's frame is the world's: its axis ``+y`` runs up the humerus to the centre of
the humeral head, ``+x`` is the front of the arm (the flexor side) and ``+z`` its outside
(the lateral, thumb side). The forearm's frame turns with the elbow about ``z``: its axis
runs from the elbow towards the wrist, straight down (``-y``) at 0 degrees of flexion and
swinging towards ``+x`` as the elbow bends; its front is ``+x`` when straight, and its
outside stays ``+z``.

An :class:`Attachment` is a point fixed on one of the two in its frame: so far along the
bone's axis, so far in front of it, so far to its outside. The biceps' two are the
skeleton's ``origin`` (on the shoulder blade, which moves with the upper arm: the shoulder
does not move here) and ``insertion`` (on the radius).

The muscle runs straight from its origin to its insertion, so its length ``L`` is a side of
the triangle (elbow centre, origin, insertion) and the elbow follows from the law of cosines
(SPEC 2.3). With the attachments off the bones' axes the triangle lives in the plane of the
bend, with sides ``A`` and ``B`` (the attachments' distances from the elbow's axis) and, at
flexion ``f``, the angle ``psi = psi0 - f`` between them (``psi0`` at the straight arm, a
little under 180 degrees when the attachments sit in front of the axes); the attachments'
sideways separation ``dz`` adds in quadrature:

    L^2 = A^2 + B^2 - 2 A B cos(psi) + dz^2

The moment arm about the elbow, ``-dL/df``, is then ``A B sin(psi) / L``: with the insertion
in front of the forearm's axis the muscle pulls with a lever even with the arm straight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from biceps.engine.bounds import (ATTACHMENT_ALONG, ATTACHMENT_REACH, BONE, BONE_RATIO,
                                  COORDINATE, FLEXION_SPAN, OutOfBounds, exactly, finite)
from biceps.engine.arm26_frame import HEAD
from biceps.engine.errors import RefusedChange

Bone = Literal["upper_arm", "forearm"]
SkeletonModel = Literal["simple", "arm26"]
"""A skeleton's bones and hinge: "simple", the two bones sized by :class:`Skeleton`'s
lengths with the driver's attachments where its fields put them; "arm26", OpenSim's arm26
model's (``engine/arm26.py``), whose muscles' paths come with it."""


@dataclass(frozen=True)
class Attachment:
    """Where a muscle is fixed to a bone, in the bone's frame (cm).

    bone: "upper_arm" (the humerus and the shoulder blade) or "forearm" (radius and ulna).
    along: from the elbow's centre along the bone's axis (up the humerus, down the forearm).
    forward: in front of the axis (negative: behind); lateral: to its outside (negative:
    inside).
    """

    bone: Bone
    along: float
    forward: float = 0.0
    lateral: float = 0.0

    def in_frame(self) -> np.ndarray:
        """(3,) float64: the point in its bone's frame, as the straight arm holds it."""
        if self.bone == "upper_arm":
            return np.array([self.forward, self.along, self.lateral])
        return np.array([self.forward, -self.along, self.lateral])


@dataclass(frozen=True)
class ArmPose:
    """The skeleton at one flexion: key points (3,) float64 in world space (cm), and the
    forearm's frame."""

    flexion: float  # degrees
    shoulder: np.ndarray  # the centre of the humeral head
    origin: np.ndarray  # the muscle's attachment on the shoulder blade
    elbow: np.ndarray
    insertion: np.ndarray  # the muscle's attachment on the radius
    hand: np.ndarray  # the forearm's free end, at the wrist
    forearm_frame: np.ndarray  # (3, 3): columns along (to the wrist), forward, lateral

    def place(self, attachment: Attachment) -> np.ndarray:
        """(3,) float64: where ``attachment`` is in this pose, world space."""
        return place(attachment, self.forearm_frame)


def forearm_frame(flexion: float) -> np.ndarray:
    """(3, 3) float64: the forearm's axes as columns (along, forward, lateral) at ``flexion``
    degrees; so also the rotation taking the straight forearm to this pose."""
    bend = math.radians(flexion)
    c, s = math.cos(bend), math.sin(bend)
    return np.array([[s, c, 0.0], [-c, s, 0.0], [0.0, 0.0, 1.0]])


def place(attachment: Attachment, frame: np.ndarray) -> np.ndarray:
    """(3,) float64: ``attachment`` in world space, the forearm's axes being ``frame``."""
    if attachment.bone == "upper_arm":
        return attachment.in_frame()
    return frame @ np.array([attachment.along, attachment.forward, attachment.lateral])


@dataclass(frozen=True)
class Skeleton:
    """Bone lengths, the muscle's attachments (cm) and the joint's range (degrees of flexion).

    The defaults are OpenSim's arm26 (Holzbaur, Murray and Delp 2005): the humerus from the
    elbow's centre to the humeral head's, 29.1 cm; the forearm to the wrist, 25.4 cm; the
    origin on the supraglenoid tubercle of the shoulder blade, 1.05 cm above the head's centre
    and 2.2 cm inside it (arm26's BIClong-P1); the insertion on the radial tuberosity, 2.18 cm
    to the outside (BIClong-P9) and 0.753 cm in front of the forearm's axis (P9: 0.751).

    A straight muscle cannot follow arm26's BIClong exactly: arm26 leads it over the humeral
    head and down the front of the humerus through via points, and from 11.6 cm above the
    elbow straight to the radius. The origin sits on the humerus's axis (arm26: 2.2 cm behind
    it) and the insertion 4.987 cm down the forearm (arm26: 4.84) so that the straight
    muscle's length change and moment arm stay closest to arm26's: within 1.98 mm and
    2.97 mm from 0 to 130 degrees (``benchmarks/arm26_reference.py``).
    """

    upper_arm: float = 29.1
    origin_to_elbow: float = 30.15
    origin_forward: float = 0.0
    origin_lateral: float = -2.2
    elbow_to_insertion: float = 4.987
    insertion_forward: float = 0.753
    insertion_lateral: float = 2.18
    forearm: float = 25.4
    min_flexion: float = 0.0
    max_flexion: float = 130.0
    model: SkeletonModel = "simple"

    @property
    def shoulder(self) -> np.ndarray:
        """(3,) the humeral head's centre in world space: up the humerus's axis, or where
        arm26 has it (2.26 cm to the outside: its hinge is not square to the humerus)."""
        if self.model == "arm26":
            return HEAD.copy()
        return np.array([0.0, self.upper_arm, 0.0])

    @property
    def origin(self) -> Attachment:
        return Attachment("upper_arm", self.origin_to_elbow, self.origin_forward,
                          self.origin_lateral)

    @property
    def insertion(self) -> Attachment:
        return Attachment("forearm", self.elbow_to_insertion, self.insertion_forward,
                          self.insertion_lateral)

    def _triangle(self) -> tuple[float, float, float, float]:
        """A, B (the attachments' distances from the elbow's axis), dz^2 (their sideways
        separation, squared) and psi0 (radians, the angle between them at the straight arm)."""
        origin, insertion = self.origin.in_frame(), self.insertion.in_frame()
        a = math.hypot(origin[0], origin[1])
        b = math.hypot(insertion[0], insertion[1])
        psi0 = math.atan2(origin[1], origin[0]) - math.atan2(insertion[1], insertion[0])
        return a, b, (origin[2] - insertion[2]) ** 2, psi0 % (2.0 * math.pi)

    def interior_angle(self, length: float) -> float:
        """The angle psi (radians) at the elbow between the attachments, in the plane of the
        bend, when the muscle is ``length`` cm long."""
        a, b, dz2, _ = self._triangle()
        cosine = (a * a + b * b + dz2 - length * length) / (2.0 * a * b)
        # Clamped: at the ends of the range rounding can push the cosine a hair past 1.
        return float(np.arccos(np.clip(cosine, -1.0, 1.0)))

    def flexion(self, length: float) -> float:
        """Elbow flexion in degrees: 0 with the arm straight."""
        return math.degrees(self._triangle()[3] - self.interior_angle(length))

    def length_at(self, flexion: float) -> float:
        """The muscle length (cm) that puts the elbow at ``flexion`` degrees."""
        a, b, dz2, psi0 = self._triangle()
        psi = psi0 - math.radians(flexion)
        return math.sqrt(max(a * a + b * b - 2.0 * a * b * math.cos(psi) + dz2, 0.0))

    def moment_arm(self, flexion: float) -> float:
        """The muscle's moment arm about the elbow (cm) at ``flexion`` degrees: how much
        shorter it gets per radian of flexion."""
        a, b, _, psi0 = self._triangle()
        return a * b * math.sin(psi0 - math.radians(flexion)) / self.length_at(flexion)

    def length_range(self) -> tuple[float, float]:
        """The shortest and longest muscle (cm) the joint's range allows.

        The length grows with psi, which shrinks as the elbow bends, so the most flexed
        pose gives the shortest muscle (`check_skeleton` makes sure psi stays within 0 to
        180 degrees over the range, where that holds).
        """
        return self.length_at(self.max_flexion), self.length_at(self.min_flexion)

    def pose(self, length: float) -> ArmPose:
        """The skeleton's key points when the muscle is ``length`` cm long."""
        flexion = self.flexion(length)
        frame = forearm_frame(flexion)
        return ArmPose(
            flexion=flexion,
            shoulder=self.shoulder,
            origin=place(self.origin, frame),
            elbow=np.zeros(3),
            insertion=place(self.insertion, frame),
            hand=self.forearm * frame[:, 0],
            forearm_frame=frame,
        )


LENGTHS = ("upper_arm", "origin_to_elbow", "elbow_to_insertion", "forearm")
OFFSETS = ("origin_forward", "origin_lateral", "insertion_forward", "insertion_lateral")


ARM26_RANGE = (0.0, 130.0)
"""The flexions arm26's elbow takes (its coordinate's range), degrees."""


def skeleton_problem(skeleton: Skeleton) -> tuple[str, str] | None:
    """What is wrong with ``skeleton``, if anything: the field to blame (a key of the
    configuration's ``[skeleton]`` table) and a sentence saying why; None if it makes sense."""
    if skeleton.model == "arm26":
        low, high = skeleton.min_flexion, skeleton.max_flexion
        if not ARM26_RANGE[0] <= low < high <= ARM26_RANGE[1]:
            return "flexion_range", (
                f"arm26's elbow bends from {ARM26_RANGE[0]:g} to {ARM26_RANGE[1]:g} degrees: "
                f"the range must lie within that, its start below its end, got {low:g} to "
                f"{high:g}")
        return None
    for names, limits in ((LENGTHS, BONE), (OFFSETS, COORDINATE)):
        for name in names:
            try:
                finite(getattr(skeleton, name), limits)
            except OutOfBounds as error:
                return name, str(error)
    upper, fore = skeleton.upper_arm, skeleton.forearm
    if max(upper, fore) > BONE_RATIO * min(upper, fore):
        longer = "upper_arm" if upper > fore else "forearm"
        return longer, (f"{max(upper, fore):g} cm is more than {BONE_RATIO:g} times the "
                        f"{'forearm' if longer == 'upper_arm' else 'upper arm'}'s "
                        f"{min(upper, fore):g} cm: no arm is so out of proportion")
    if skeleton.elbow_to_insertion > skeleton.forearm:
        return "elbow_to_insertion", (
            f"must be at most the forearm's length, {skeleton.forearm:g} cm, not "
            f"{skeleton.elbow_to_insertion:g}: the muscle inserts on the forearm")
    for end, keys in (("origin", ("origin_to_elbow", "origin_forward", "origin_lateral")),
                      ("insertion", ("elbow_to_insertion", "insertion_forward",
                                     "insertion_lateral"))):
        attachment = getattr(skeleton, end)
        problem = attachment_problem(attachment, skeleton)
        if problem is not None:
            across = 1 if abs(attachment.forward) >= abs(attachment.lateral) else 2
            return keys[0 if problem[0] == "along" else across], problem[1]
    low, high = skeleton.min_flexion, skeleton.max_flexion
    if not 0.0 <= low < high <= 180.0:
        return "flexion_range", (f"flexion range must satisfy 0 <= min_flexion < max_flexion "
                                 f"<= 180 degrees, got {low} to {high}")
    if high - low < FLEXION_SPAN:
        return "flexion_range", (f"{exactly(low)} to {exactly(high)} degrees is "
                                 f"{high - low:.3g} degrees wide; the elbow needs at least "
                                 f"{FLEXION_SPAN:g} to move")
    # The law of cosines gives one length per flexion only while psi stays within 0 and
    # 180 degrees: the muscle's line must pass in front of the elbow's axis all the way.
    psi0 = math.degrees(skeleton._triangle()[3])
    if psi0 > 180.0 + low:
        return "insertion_forward", (
            f"the attachments put the muscle behind the elbow's axis at {low:g} degrees of "
            f"flexion: move the insertion or the origin forward")
    if psi0 - high <= 0.0:
        return "flexion_range", (
            f"at {high:g} degrees the forearm would fold past the muscle's origin: lower the "
            f"range's end below {psi0:.1f} degrees")
    return None


def attachment_problem(attachment: Attachment, skeleton: Skeleton) -> tuple[str, str] | None:
    """Whether ``attachment`` is off its bone of ``skeleton``: "along" (too far along it)
    or "across" (too far from its axis, ``ATTACHMENT_ALONG``, ``ATTACHMENT_REACH``), and
    why in words; None if it is on it."""
    length = skeleton.upper_arm if attachment.bone == "upper_arm" else skeleton.forearm
    bone = "the upper arm" if attachment.bone == "upper_arm" else "the forearm"
    low, high = ATTACHMENT_ALONG
    if attachment.bone == "forearm":
        high = 1.0  # no hand past the wrist to hold on to
    if not low * length <= attachment.along <= high * length:
        return "along", (f"{attachment.along:g} cm along {bone} is off the bone, {length:g} cm "
                         f"long: an attachment lies from {low * length:g} to "
                         f"{high * length:g} cm along it")
    reach = math.hypot(attachment.forward, attachment.lateral)
    if reach > ATTACHMENT_REACH * length:
        return "across", (f"{reach:g} cm from {bone}'s axis is off the bone, {length:g} cm "
                          f"long: an attachment lies within {ATTACHMENT_REACH * length:g} cm "
                          "of its axis")
    return None


def check_skeleton(skeleton: Skeleton) -> None:
    """Raise :class:`RefusedChange` unless every distance and the joint's range make sense."""
    problem = skeleton_problem(skeleton)
    if problem is not None:
        field, reason = problem
        raise RefusedChange(f"skeleton {field} {reason}" if reason.startswith("must")
                            else f"skeleton {field}: {reason}")
