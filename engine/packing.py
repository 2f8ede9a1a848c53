"""How the elbow's muscles pack round the humerus: the order they are laid on the bones,
deepest first, and how far each turns round the bone to its own side of those laid before.

Each muscle is laid clear of the bones and of the muscles laid before it
(``engine/clearance.py``); one laid over others moves along a direction turned round its
axis by its lean, towards its own side of the arm. The leans are chosen once for an arm's
muscles (their rest shapes, paths and skeleton) over the whole of the elbow's range, never
pose by pose: so no muscle jumps to another side as the elbow bends, and a pose costs no
search. ``engine/anatomy.py`` lays them so at each pose.
"""

from __future__ import annotations

from functools import lru_cache
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


def arm_leans(arm: Arm) -> tuple[float | None, ...]:
    """Each muscle's lean (radians, see ``clearance.path_offsets``), in `laying_order`: None for the
    first, which lies on bare bone, and for a single muscle.

    A lean is chosen once for the muscles' shapes and paths, over the whole range of the
    elbow (the muscle reaching least far at the worst of its two ends and its middle), not
    at each pose: so no muscle jumps from one side to another as the elbow moves, and a
    pose costs no search.
    """
    if not arm.companions:
        return (None,)
    return _chosen_leans(_Shapes(arm))


JUDGED_POSES = 3
"""The poses a lean is judged at: the two ends of the elbow's range and its middle."""


class _Shapes:
    """An arm, hashed and compared by what its leans depend on: its muscles' rest shapes,
    their paths and the skeleton, not its pose."""

    def __init__(self, arm: Arm):
        self.arm = arm
        self.key = (arm.names, arm.skeleton, arm.paths, arm.min_length, arm.max_length,
                    tuple((m.reference_length, m.volume_mode, m.reference_radii.tobytes(),
                           m.growth.tobytes()) for m in arm.muscles))

    def __hash__(self) -> int:
        return hash(self.key)

    def __eq__(self, other) -> bool:
        return isinstance(other, _Shapes) and self.key == other.key


@lru_cache(maxsize=16)
def _chosen_leans(shapes: _Shapes) -> tuple[float | None, ...]:
    """`arm_leans` for an arm's shapes: each muscle in `laying_order` laid at each judged
    pose over those before it, with the lean whose worst reach there is least (`best_lean`,
    bounded by how far the muscles before it reach already)."""
    arm = shapes.arm
    poses = [arm.at_length(length) for length in np.linspace(*arm.length_range(), JUDGED_POSES)]
    spheres = [bone_spheres(pose.skeleton, pose.pose) for pose in poses]
    leans, bound = [], 0.0
    for index in laying_order(arm):
        lean = None
        if leans:
            reaches = []
            for pose, (centres, radii) in zip(poses, spheres):
                muscle = pose.muscles[index]
                points, axes = centreline(muscle, pose.paths[index], pose.flexion)
                turns, far = lean_reaches(points, axes, muscle.radii, centres, radii)
                reaches.append(far)
            lean = best_lean(turns, np.max(reaches, axis=0), bound)
        leans.append(lean)
        for at, (pose, (centres, radii)) in enumerate(zip(poses, spheres)):
            more_centres, more_radii = _laid_sections(pose.muscles[index], pose.paths[index],
                                                     pose.flexion, (centres, radii), lean)
            bound = max(bound, reach(more_centres, more_radii))
            spheres[at] = (np.concatenate([centres, more_centres]),
                           np.concatenate([radii, more_radii]))
    return tuple(leans)


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
