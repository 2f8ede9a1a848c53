"""The arm in one pose, as meshes: the muscle lying clear of the bones, and the bones.

The parts, world space, in centimetres: "muscle", "scapula", "humerus", "radius", "ulna".
Also where the muscle is tendon: its nodes that do not grow are its tendons (SPEC 2), drawn
in the tendon's colour, which blends into the belly's over the nodes that grow a little.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from biceps.engine.bones import bone_meshes, bone_spheres
from biceps.engine.clearance import section_offsets, sections_per_segment
from biceps.engine.mesh import Mesh, muscle_mesh

if TYPE_CHECKING:
    from biceps.engine.arm import Arm

PARTS = ("muscle", "scapula", "humerus", "radius", "ulna")


def arm_parts(arm: Arm, segments: int) -> dict[str, Mesh]:
    """The arm in its current pose, by part (see ``PARTS``), world space."""
    pose, skeleton, muscle = arm.pose, arm.skeleton, arm.muscle
    centres, radii = bone_spheres(skeleton, pose)
    offsets = section_offsets(pose.origin, pose.insertion, muscle.radii, centres, radii,
                              sections_per_segment(muscle.node_count))
    body = muscle_mesh(muscle.radii, arm.length, pose.origin, pose.insertion, segments,
                       offsets=offsets)
    return {"muscle": body, **bone_meshes(skeleton, pose, segments)}


def tendon_share(arm: Arm, muscle: Mesh) -> np.ndarray:
    """How much each vertex of ``muscle`` (the mesh of `arm_parts`) is tendon: (n,) float32
    in [0, 1], 1 on the nodes that do not grow, 0 where a node grows at least half as
    much as the most growing one, linear between nodes."""
    growth = arm.muscle.growth
    pose = arm.pose
    axis = (pose.insertion - pose.origin) / arm.length
    # Each vertex's place along the muscle, in nodes (the caps count as their end node).
    place = (muscle.vertices - pose.origin) @ axis / arm.length * (len(growth) - 1)
    share = 1.0 - np.clip(growth / (0.5 * growth.max()), 0.0, 1.0)
    return np.interp(place, np.arange(len(growth)), share).astype(np.float32)
