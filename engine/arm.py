"""The arm: the muscle on its skeleton, changing length within what both allow, and the
other muscles of the elbow, which follow it.

The muscle (the driver, the biceps) sets the elbow's angle by its length: straight between
the skeleton's attachments, by the law of cosines (:class:`Skeleton`); on a path of its own
(``driver_path``, arm26's), as the flexion at which that path has its length
(:class:`PathDrive`). Its companions (``engine/companion.py``) take the length their paths
have at that angle. A single-muscle arm is the case with no companions.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from biceps.engine.bounds import cm
from biceps.engine.companion import Companion, check_reach
from biceps.engine.errors import RefusedChange
from biceps.engine.muscle import Muscle
from biceps.engine.packing import Leans, chosen_leans
from biceps.engine.path import MusclePath, PathDrive, ViaPath
from biceps.engine.skeleton import ArmPose, Skeleton, forearm_frame

HINGE_AXIS = np.array([0.0, 0.0, 1.0])
"""The elbow's axis in world space: flexion turns the forearm about ``+z``, from ``-y``
towards ``+x`` (see ``engine/skeleton.py``)."""


@dataclass(frozen=True)
class Arm:
    """A muscle, the skeleton it spans, optional limits (cm) on its length, its name and the
    muscles that follow the elbow with it.

    Immutable like :class:`Muscle`: a change returns a new arm or raises
    :class:`RefusedChange` and leaves this one as it was.
    """

    muscle: Muscle
    skeleton: Skeleton
    min_length: float | None = None
    max_length: float | None = None
    name: str = "muscle"
    companions: tuple[Companion, ...] = ()
    driver_path: ViaPath | None = None
    leans: Leans | None = field(default=None, repr=False, compare=False)
    """How far each muscle turns round the humerus (``engine/packing.py``), which its mesh
    reads: chosen when the arm is made with muscles of new shapes, and kept by its poses."""

    def __post_init__(self) -> None:
        # A pose (at_length, tensed_arm) keeps the shapes, and the leans come with them;
        # any other change is checked, so that no leans of other shapes are kept.
        if self.leans is None or not self.leans.fit(self):
            object.__setattr__(self, "leans", chosen_leans(self))

    @property
    def drive(self) -> Skeleton | PathDrive:
        """How the driver's length sets the elbow: the skeleton's law of cosines, or the
        flexion at which its own path has that length."""
        if self.driver_path is None:
            return self.skeleton
        return PathDrive(self.driver_path, self.skeleton.min_flexion, self.skeleton.max_flexion)

    @property
    def names(self) -> tuple[str, ...]:
        """Every muscle's name, the driver's first."""
        return (self.name, *(companion.name for companion in self.companions))

    @property
    def muscles(self) -> tuple[Muscle, ...]:
        """Every muscle, the driver first, in the order of :attr:`names`."""
        return (self.muscle, *(companion.muscle for companion in self.companions))

    @property
    def paths(self) -> tuple[MusclePath, ...]:
        """Every muscle's path, the driver's (its own, or straight between the skeleton's
        attachments) first."""
        driver = self.driver_path or MusclePath(self.skeleton.origin, self.skeleton.insertion)
        return (driver, *(companion.path for companion in self.companions))

    @property
    def length(self) -> float:
        return self.muscle.length

    @property
    def lengths(self) -> tuple[float, ...]:
        """Every muscle's length (cm), in the order of :attr:`names`: each is its path's
        length at the elbow's flexion (the driver's sets the flexion)."""
        return tuple(muscle.length for muscle in self.muscles)

    @property
    def moment_arms(self) -> tuple[float, ...]:
        """Every muscle's moment arm about the elbow (cm) at the elbow's flexion, in the
        order of :attr:`names`: ``-dL/dtheta`` of its path, the length it loses per radian
        of flexion, so positive for a flexor and negative for an extensor."""
        flexion = self.flexion
        return tuple(path.moment_arm_at(flexion) for path in self.paths)

    @property
    def flexion(self) -> float:
        """Elbow flexion in degrees: 0 with the arm straight."""
        return self.drive.flexion(self.length)

    @property
    def pose(self) -> ArmPose:
        if self.driver_path is None:
            return self.skeleton.pose(self.length)
        flexion = self.flexion
        frame = forearm_frame(flexion)
        origin, insertion = self.driver_path.ends(flexion)
        return ArmPose(flexion, self.skeleton.shoulder, origin, np.zeros(3), insertion,
                       self.skeleton.forearm * frame[:, 0], frame)

    @property
    def moment_arm(self) -> float:
        """The muscle's moment arm about the elbow (cm), positive for a flexor.

        The moment about the hinge of a unit pull along the muscle's line of action, the
        straight line from insertion to origin: the perpendicular distance from the elbow's
        centre to that line. For a straight muscle this equals ``-dL/dtheta``, the length
        lost per radian of flexion (the tendon-excursion method; An et al. 1984), which is
        what OpenSim reports for a muscle with no wrapping. Worked out from the pose's
        points, so it follows wherever the skeleton puts the attachments. On a path of its
        own, ``-dL/dtheta`` of that path.
        """
        if self.driver_path is not None:
            return self.driver_path.moment_arm_at(self.flexion)
        pose = self.pose
        line = pose.origin - pose.insertion
        pull = line / np.linalg.norm(line)
        return float(np.cross(pose.insertion - pose.elbow, pull) @ HINGE_AXIS)

    def length_range(self) -> tuple[float, float]:
        """The shortest and longest length (cm): the joint's range, the config's limits and
        the muscle's own (stretched too far, a node thins to nothing)."""
        low, high = self._set_range()
        return low, min(high, self.muscle.longest_length)

    def _set_range(self) -> tuple[float, float]:
        """The joint's range and the config's limits, without the muscle's own."""
        low, high = self.drive.length_range()
        if self.min_length is not None:
            low = max(low, self.min_length)
        if self.max_length is not None:
            high = min(high, self.max_length)
        return low, high

    def at_length(self, length: float) -> Arm:
        """The arm with the muscle at ``length`` cm, or :class:`RefusedChange` if outside."""
        low, high = self.length_range()
        if not low <= length <= high:
            raise RefusedChange(
                f"length {cm(length)} cm is outside what this arm allows: "
                f"{low:.2f} to {high:.2f} cm (elbow flexion "
                # round(), an int: the straight arm's -1e-14 degrees is 0, not "-0"
                f"{round(self.drive.flexion(high))} to {round(self.drive.flexion(low))} "
                "degrees)"
                + self._muscle_limit_note(high)
            )
        muscle = self.muscle.at_length(length)
        flexion = self.drive.flexion(length)
        return replace(self, muscle=muscle, companions=tuple(
            companion.at_flexion(flexion) for companion in self.companions))

    def at_flexion(self, flexion: float) -> Arm:
        """The arm with the elbow at ``flexion`` degrees."""
        low, high = self.skeleton.min_flexion, self.skeleton.max_flexion
        if not low <= flexion <= high:
            raise RefusedChange(
                f"flexion {flexion:g} degrees is outside the joint's range, {low:g} to {high:g}"
            )
        return self.at_length(self.drive.length_at(flexion))

    def stepped(self, change: float) -> tuple[Arm, str | None]:
        """The muscle lengthened by ``change`` cm (shortened if negative), stopping at a limit.

        Returns the new arm and, when it stopped at a limit, a sentence saying which.
        """
        return self.towards(self.length + change)

    def towards(self, length: float) -> tuple[Arm, str | None]:
        """The muscle at ``length`` cm, or at the limit on the way there, and then a sentence
        saying which limit stopped it."""
        low, high = self.length_range()
        if length < low:
            return self.at_length(low), self._limit_note(low, "shortest")
        if length > high:
            return self.at_length(high), self._limit_note(high, "longest")
        return self.at_length(length), None

    def _limit_note(self, length: float, which: str) -> str:
        flexion = self.drive.flexion(length)
        if which == "longest" and length < self._set_range()[1]:
            return (
                f"the muscle is at its longest, {length:.2f} cm: stretched further, "
                f"{self.muscle.thinnest_note()}"
            )
        if which == "longest" and flexion < 0.05:
            return f"the arm is straight: the muscle is at its longest, {length:.2f} cm"
        return (
            f"the muscle is at its {which}, {length:.2f} cm "
            f"(elbow flexion {flexion:.0f} degrees)"
        )

    def _muscle_limit_note(self, high: float) -> str:
        if high < self._set_range()[1]:
            return f"; stretched further, {self.muscle.thinnest_note()}"
        return ""

    def with_muscle(self, muscle: Muscle) -> Arm:
        """The arm with an edited muscle (same length, so the skeleton does not move)."""
        return replace(self, muscle=muscle)

    def with_muscle_at(self, index: int, muscle: Muscle) -> Arm:
        """The arm with muscle ``index`` of :attr:`muscles` edited (0: the driver); a
        companion that could then no longer follow the elbow over its range is refused."""
        if index == 0:
            return self.with_muscle(muscle)
        companions = list(self.companions)
        companions[index - 1] = companions[index - 1].with_muscle(muscle)
        check_reach(companions[index - 1], self.skeleton.min_flexion, self.skeleton.max_flexion)
        return replace(self, companions=tuple(companions))
