"""The arm in one pose, as meshes: the muscles lying clear of the bones, and the bones.

The parts, world space, in centimetres: one per muscle, by its name (the driver first; a
single-muscle arm's is "muscle"), then "scapula", "humerus", "radius", "ulna". Also where a
muscle is tendon: its nodes that do not grow are its tendons (SPEC 2), drawn in the
tendon's colour, which blends into the belly's over the nodes that grow a little.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from biceps.engine.bones import bone_meshes, bone_spheres
from biceps.engine.lies import Lie
from biceps.engine.mesh import Mesh, bent_muscle_mesh, muscle_mesh
from biceps.engine.muscle import Muscle
from biceps.engine.packing import centreline, laid_offsets, laying_order
from biceps.engine.path import MusclePath, ViaPath
from biceps.engine.stations import section_radii

if TYPE_CHECKING:
    from biceps.engine.arm import Arm
    from biceps.engine.layers import Humerus

BONES = ("scapula", "humerus", "radius", "ulna")
PARTS = ("muscle", *BONES)
"""A single-muscle arm's parts."""


def arm_parts(arm: Arm, segments: int, hidden: frozenset[str] = frozenset(),
              companion_segments: int | None = None) -> dict[str, Mesh]:
    """The arm in its current pose, by part: each muscle not ``hidden`` by its name (see
    :attr:`Arm.names`), then the bones (``BONES``), world space; ``segments`` round each,
    or ``companion_segments`` round the companions (the driver's, if None).

    The muscles are laid on the bones one at a time, deepest first: the companions in their
    order, then the driver over them; each keeps clear of the bones and of those laid
    before it (hidden or not, so hiding one moves no other). On arm26's skeleton each lies
    in layers round the humerus (``engine/layers.py``); on the simple one, one laid over
    others turns to its own side of them, round the humerus (:attr:`Arm.leans`).
    """
    if arm.skeleton.model == "arm26":
        return _layered_parts(arm, segments, hidden, companion_segments)
    return _simple_parts(arm, segments, hidden, companion_segments)


def _layered_parts(arm: Arm, segments: int, hidden: frozenset[str],
                   companion_segments: int | None):
    from biceps.engine.arm26 import BONES, LIES  # arm26's paths build on this package
    # The layers' kernels are numba's: imported only here, so that the simple skeleton's
    # mesh (export-mesh of the single biceps) imports no numba.
    from biceps.engine.layers import Ground, Humerus, lay
    from biceps.engine.layers import muscle_mesh as layered_mesh

    pose, skeleton = arm.pose, arm.skeleton
    ground = Ground(Humerus(skeleton.shoulder), *bone_spheres(skeleton, pose), len(arm.names))
    names, muscles, paths = arm.names, arm.muscles, arm.paths
    parts = {}
    for index in laying_order(arm):
        name, muscle, path = names[index], muscles[index], paths[index]
        around = segments if index == 0 or companion_segments is None else companion_segments
        route = path.route(pose.flexion).points if isinstance(path, ViaPath) else \
            path.centreline(pose.flexion, 64)[0]
        lie = LIES.get(name) or _lie_of(route, ground.humerus)
        held = BONES.get(name, ("humerus", "humerus"))
        laid = lay(name, muscle, route, lie, ground, around,
                   (held[0] != "humerus", held[1] != "humerus"))
        if name not in hidden:
            parts[name] = layered_mesh(laid, muscle.volume_mode == "closed")
    parts = {name: parts[name] for name in names if name in parts}
    return {**parts, **bone_meshes(skeleton, pose, segments)}


def _lie_of(route: np.ndarray, humerus: Humerus) -> Lie:
    """How a muscle with no lie of its own lies: on the side of the humerus its path runs
    down, round its middle."""
    heights, _, angles = humerus.polar(route)
    side = math.degrees(float(np.angle(np.mean(np.exp(1j * angles)))))
    return Lie(side=(side, side))


def _simple_parts(arm: Arm, segments: int, hidden: frozenset[str],
                  companion_segments: int | None) -> dict[str, Mesh]:
    pose, skeleton = arm.pose, arm.skeleton
    spheres = bone_spheres(skeleton, pose)
    names, muscles, paths = arm.names, arm.muscles, arm.paths  # properties: built per read
    laid = {}
    for index, lean in zip(laying_order(arm), arm.leans.each):
        centres, radii = spheres
        around = segments if index == 0 or companion_segments is None else companion_segments
        mesh, (more_centres, more_radii) = muscle_part(
            muscles[index], paths[index], pose.flexion, spheres, around, lean)
        laid[names[index]] = mesh
        spheres = np.concatenate([centres, more_centres]), np.concatenate([radii, more_radii])
    parts = {name: laid[name] for name in names if name not in hidden}
    return {**parts, **bone_meshes(skeleton, pose, segments)}


def muscle_part(muscle: Muscle, path: MusclePath, flexion: float,
                spheres: tuple[np.ndarray, np.ndarray], segments: int,
                lean: float | None = None) -> tuple[Mesh, tuple[np.ndarray, np.ndarray]]:
    """One muscle on its path at ``flexion`` degrees, its sections moved clear of
    ``spheres`` (centres (k, 3), radii (k,)); if it lies beside other muscles, turned by
    ``lean`` (radians, :attr:`Arm.leans`) to its side of them and bowed out once (None: it lies
    on bare bone). Also its sections as spheres, which the muscles laid after it keep
    clear of. A straight path's sections stay parallel, so the mesh keeps the muscle's
    volume exactly (``engine/mesh.py``)."""
    points, axes = centreline(muscle, path, flexion)
    offsets = laid_offsets(muscle, points, axes, spheres, lean)
    if path.wraps(flexion):
        mesh = bent_muscle_mesh(muscle.radii, points + offsets, axes, segments)
    else:
        mesh = muscle_mesh(muscle.radii, muscle.length, points[0], points[-1], segments,
                           offsets=offsets)
    return mesh, (points + offsets, section_radii(muscle.radii, len(points)))


def tendon_share(muscle: Muscle, path: MusclePath, flexion: float, mesh: Mesh) -> np.ndarray:
    """How much each vertex of ``mesh`` (the muscle's part, see `muscle_part`) is tendon:
    (n,) float32 in [0, 1], 1 on the nodes that do not grow, 0 where a node grows at least
    half as much as the most growing one, linear between nodes."""
    growth = muscle.growth
    share = 1.0 - np.clip(growth / (0.5 * growth.max()), 0.0, 1.0)
    places = node_places(muscle, path, flexion, mesh.vertices)
    return np.interp(places, np.arange(len(growth)), share).astype(np.float32)


def node_places(muscle: Muscle, path: MusclePath | ViaPath, flexion: float,
                vertices: np.ndarray) -> np.ndarray:
    """Each of ``vertices`` (n, 3) (of the muscle's part) placed along the muscle, in
    nodes: (n,) float64, 0 at the first node, ``node_count - 1`` at the last (the caps reach
    a little past them)."""
    if isinstance(path, ViaPath):  # laid in layers, its sections the same shares of it
        from biceps.engine.layers import ring_places

        return ring_places(muscle, len(vertices))
    start, end = path.ends(flexion)
    chord = float(np.linalg.norm(end - start))
    return (vertices - start) @ ((end - start) / chord) / chord * (muscle.node_count - 1)
