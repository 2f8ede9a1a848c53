"""How the elbow's muscles pack round the humerus: the order they are laid on the bones,
deepest first, and how far each turns round the bone to its own side of those laid before.

Each muscle is laid clear of the bones and of the muscles laid before it
(``engine/clearance.py``); one laid over others moves along a direction turned round its
axis by its lean, towards its own side of the arm. The leans are chosen once for an arm's
muscles (their rest shapes, paths and skeleton) over the whole of the elbow's range, never
pose by pose: so no muscle jumps to another side as the elbow bends, and a pose costs no
search. An arm made with muscles of new shapes chooses them (``engine/arm.py``), and its
poses carry them on; ``engine/anatomy.py`` lays the muscles so at each pose, posing
nothing again.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from biceps.engine.bones import bone_spheres
from biceps.engine.clearance import (best_lean, lean_reaches, path_offsets, reach,
                                     sections_per_segment)
from biceps.engine.muscle import Muscle
from biceps.engine.path import MusclePath
from biceps.engine.stations import section_radii

if TYPE_CHECKING:
    from biceps.engine.arm import Arm


def laying_order(arm: Arm) -> list[int]:
    """The muscles' indices (in :attr:`Arm.names`) in the order they are laid on the bones:
    the companions in their order, deepest first, then the driver."""
    return [*range(1, len(arm.names)), 0]


JUDGED_POSES = 3
"""The poses a lean is judged at: the two ends of the elbow's range and its middle."""


@dataclass(frozen=True, eq=False)
class Leans:
    """Each muscle's lean (radians, see ``clearance.path_offsets``) in `laying_order`, and
    the shapes they were chosen for (`shapes_of`). An arm carries them from pose to pose."""

    shapes: tuple
    each: tuple[float | None, ...]  # None: on bare bone, or laid in layers (arm26)

    def fit(self, arm: Arm) -> bool:
        """Whether these are ``arm``'s leans: it has the shapes they were chosen for."""
        return self.shapes == shapes_of(arm)


def shapes_of(arm: Arm) -> tuple:
    """What an arm's leans depend on: its muscles' rest shapes (each shared by every
    length of its muscle, so compared by identity), their paths, the skeleton and the
    limits on the driver's length; not its pose."""
    return (arm.skeleton, arm.driver_path, arm.min_length, arm.max_length, arm.muscle.rest,
            tuple((companion.path, companion.muscle.rest) for companion in arm.companions))


def chosen_leans(arm: Arm) -> Leans:
    """``arm``'s leans, chosen once for its muscles' shapes and paths over the whole range
    of the elbow (the muscle reaching least far at the worst of its two ends and its
    middle), not at each pose: so no muscle jumps from one side to another as the elbow
    moves, and a pose costs no search. None for the first muscle, which lies on bare
    bone, for a single muscle, for arm26's, which lie in layers (``engine/layers.py``), and
    for an arm with no length to take (which loading refuses)."""
    unlaid = Leans(shapes_of(arm), (None,) * len(arm.names))
    if not arm.companions or arm.skeleton.model == "arm26":
        return unlaid
    low, high = arm.length_range()
    if low > high:
        return unlaid
    return Leans(unlaid.shapes, _leans_over_the_range(arm, low, high))


def _leans_over_the_range(arm: Arm, low: float, high: float) -> tuple[float | None, ...]:
    """Each muscle in `laying_order` laid at each judged pose over those before it, with
    the lean whose worst reach there is least (`best_lean`, bounded by how far the muscles
    before it reach already)."""
    poses = [_judged_pose(arm, length) for length in np.linspace(low, high, JUDGED_POSES)]
    spheres = [pose.spheres for pose in poses]
    paths = arm.paths
    leans, bound = [], 0.0
    for index in laying_order(arm):
        lean = None
        if leans:
            reaches = []
            for pose, (centres, radii) in zip(poses, spheres):
                muscle = pose.muscles[index]
                points, axes = centreline(muscle, paths[index], pose.flexion)
                turns, far = lean_reaches(points, axes, muscle.radii, centres, radii)
                reaches.append(far)
            lean = best_lean(turns, np.max(reaches, axis=0), bound)
        leans.append(lean)
        for at, (pose, (centres, radii)) in enumerate(zip(poses, spheres)):
            more_centres, more_radii = _laid_sections(pose.muscles[index], paths[index],
                                                     pose.flexion, (centres, radii), lean)
            bound = max(bound, reach(more_centres, more_radii))
            spheres[at] = (np.concatenate([centres, more_centres]),
                           np.concatenate([radii, more_radii]))
    return tuple(leans)


@dataclass(frozen=True)
class _JudgedPose:
    flexion: float  # degrees
    muscles: tuple[Muscle, ...]  # in the order of Arm.names
    spheres: tuple[np.ndarray, np.ndarray]  # the bones' (centres (k, 3), radii (k,))


def _judged_pose(arm: Arm, length: float) -> _JudgedPose:
    """The muscles and bones of the simple skeleton's arm with its driver at ``length``
    cm, as `Arm.at_length` poses them, without making an arm (which would choose leans)."""
    flexion = arm.drive.flexion(length)
    muscles = (arm.muscle.at_length(length),
               *(companion.at_flexion(flexion).muscle for companion in arm.companions))
    return _JudgedPose(flexion, muscles, bone_spheres(arm.skeleton, arm.skeleton.pose(length)))


def centreline(muscle: Muscle, path: MusclePath, flexion: float):
    """The muscle's section centres and unit axes (m, 3) on its path, before any move."""
    count = (muscle.node_count - 1) * sections_per_segment(muscle.node_count) + 1
    return path.centreline(flexion, count)


def _laid_sections(muscle: Muscle, path: MusclePath, flexion: float,
                  spheres: tuple[np.ndarray, np.ndarray],
                  lean: float | None) -> tuple[np.ndarray, np.ndarray]:
    """The muscle's sections as spheres (centres (m, 3), radii (m,)) when it is laid at
    ``flexion`` clear of ``spheres``, leaning by ``lean`` (see `laid_offsets`)."""
    points, axes = centreline(muscle, path, flexion)
    offsets = laid_offsets(muscle, points, axes, spheres, lean)
    return points + offsets, section_radii(muscle.radii, len(points))


def laid_offsets(muscle: Muscle, points, axes, spheres, lean: float | None) -> np.ndarray:
    """The moves (m, 3) of the muscle's sections (``points``, ``axes`` (m, 3), from
    `centreline`) that lay it clear of ``spheres`` (centres (k, 3), radii (k,)): turned by
    ``lean`` and bowed out once if it lies over other muscles, straight out if None."""
    return path_offsets(points, axes, muscle.radii, *spheres, lean=lean or 0.0,
                        one_bulge=lean is not None)
