"""The muscle clear of the bones: its cross-sections moved sideways, each within its plane.

The muscle's line runs straight from origin to insertion (its length is that line's, which
the elbow follows by the law of cosines), and on that line it would pass through the humeral
head, the humerus and the elbow. So each circular section is moved forward, to the flexor
side where the biceps lies (within the section's plane, away from the elbow's axis), just
far enough that its disc clears every bone: the muscle bulges to one side, over the bones,
as a real biceps lies on them. Moving sections within their planes leaves the volume as it
was (Cavalieri's principle; ``engine/mesh.py`` says why the mesh's does not change either),
so the volume law needs no change.

A bone is a row of spheres along its axis (``engine/bones.py``). A sphere cuts a section's
plane in a circle, and the section's disc, moved by ``s`` along the forward direction, must
keep its radius plus that circle's plus a small gap from the circle's centre: a quadratic
in ``s`` that rules out one interval. Each section takes the least ``s >= 0`` outside every
such interval, and the moves are then smoothed from above (no section moves less than it
needs) so the muscle leans no steeper than ``SLOPE``. The tendons' last centimetre at either
end, which is where they hold on to their bone, is left where it is.
"""

from __future__ import annotations

import numpy as np

RINGS_PER_SEGMENT = 4
"""Sections drawn per segment between two nodes, so the moves bend smoothly..."""
MOST_SECTIONS = 1024
"""...while that makes no more than this many: a muscle of thousands of nodes has sections
enough in its nodes alone, and one of 16,384 would otherwise have 65,533."""
_BLOCK = 4096  # sections tested against the spheres at a time: (block, spheres) arrays

GAP = 0.1  # cm kept between muscle and bone
SLOPE = 0.7  # the most a section moves per cm along the muscle
HOLD = 1.0  # cm at either end where the tendon holds on to its bone and does not move
_ROUNDS = 24  # passes over the intervals; each lifts a section past one more bone


def forward(start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """(3,) the unit direction, perpendicular to the muscle's line and to the elbow's axis
    (``z``), on the side away from the elbow (the origin of world space): the flexor side."""
    axis = (end - start) / np.linalg.norm(end - start)
    return _sides(start[None, :], axis[None, :])[0]


def _sides(points: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """(m, 3) for each section (centre and unit axis (m, 3) each) the unit direction across
    its axis and the elbow's, on the side away from the elbow. Sections of one straight line
    all take the same side: the centre's component along it is that of the line's nearest
    point to the elbow."""
    side = np.column_stack([-axes[:, 1], axes[:, 0], np.zeros(len(axes))])  # z x axis
    side /= np.linalg.norm(side, axis=1, keepdims=True)
    return np.where(np.einsum("mc,mc->m", points, side)[:, None] >= 0.0, side, -side)


def section_offsets(start, end, radii, centres, sphere_radii,
                    per_segment: int = RINGS_PER_SEGMENT) -> np.ndarray:
    """The sideways moves (m, 3) of the muscle's m = (n - 1) per_segment + 1 sections,
    equally spaced from ``start`` to ``end`` ((3,) each), that keep it clear of the bones.

    radii: (n,) the node radii. centres: (k, 3) and sphere_radii: (k,): the bones' spheres.
    """
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    count = (len(radii) - 1) * per_segment + 1
    share = np.linspace(0.0, 1.0, count)
    axis = (end - start) / np.linalg.norm(end - start)
    return path_offsets(start + np.outer(share, end - start), np.tile(axis, (count, 1)),
                        radii, centres, sphere_radii)


def path_offsets(points, axes, radii, centres, sphere_radii) -> np.ndarray:
    """The sideways moves (m, 3) of m sections centred at ``points`` (m, 3), equally spaced
    along a path (straight, or bent round the elbow), each in the plane across its unit
    ``axes`` (m, 3), that keep the muscle of node ``radii`` (n,) clear of the spheres; m - 1
    is a multiple of n - 1.

    Only sections on a straight stretch move: there the planes are parallel, so the volume
    does not change (Cavalieri). Where the path bends, moving a section away from the bend
    would lengthen the tube and grow its volume (Pappus), so the sections whose plane is
    not parallel to a neighbour's stay, and the moves ease off towards them at ``SLOPE``.
    """
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    length = along[-1]
    radius = np.interp(np.linspace(0.0, 1.0, len(points)), np.linspace(0.0, 1.0, len(radii)),
                       radii)
    side = _sides(points, axes)
    shift = _least_shifts(points, radius, axes, side, centres, sphere_radii)
    shift[(along < HOLD) | (along > length - HOLD)] = 0.0
    # The least smooth profile above the needs: each need spreads down both ways at SLOPE,
    # max_j (shift_j - SLOPE |a_i - a_j|), the larger of a running maximum from each end
    # (an m x m array of every pair would take 34 GB at 16,384 nodes).
    rising = np.maximum.accumulate(shift + SLOPE * along) - SLOPE * along
    falling = (np.maximum.accumulate((shift - SLOPE * along)[::-1]) + SLOPE * along[::-1])[::-1]
    smooth = np.maximum(rising, falling)
    smooth[[0, -1]] = 0.0  # the attachments themselves stay on the bone
    bent = np.flatnonzero(_bends(axes))
    if bent.size:
        nearest = np.min(np.abs(along[:, None] - along[bent][None, :]), axis=1)
        smooth = np.minimum(smooth, SLOPE * nearest)
    return smooth[:, None] * side


def _bends(axes: np.ndarray) -> np.ndarray:
    """(m,) bool: the sections whose unit axis (of ``axes`` (m, 3)) is not that of a
    neighbour, to a rounding error."""
    turns = np.any(np.abs(axes[1:] - axes[:-1]) > 1e-12, axis=1)
    bends = np.zeros(len(axes), dtype=bool)
    bends[1:] |= turns
    bends[:-1] |= turns
    return bends


def sections_per_segment(nodes: int) -> int:
    """:data:`RINGS_PER_SEGMENT`, or fewer (one at least) for a muscle of many nodes, so
    that it has at most :data:`MOST_SECTIONS` sections if it can."""
    return max(1, min(RINGS_PER_SEGMENT, (MOST_SECTIONS - 1) // max(nodes - 1, 1)))


def _least_shifts(points, radius, axes, sides, centres, sphere_radii) -> np.ndarray:
    """For each section (points (m, 3), radius (m,), unit axis and side (m, 3)), the least
    move s >= 0 along its side that clears every sphere's circle in its plane: (m,)."""
    return np.concatenate([
        _block_shifts(*(values[first:first + _BLOCK] for values in (points, radius, axes, sides)),
                      centres, sphere_radii)
        for first in range(0, len(points), _BLOCK)
    ])


def _block_shifts(points, radius, axes, sides, centres, sphere_radii) -> np.ndarray:
    # Each sphere's centre above each section's plane. Only the pairs where the sphere cuts
    # the section's plane can block; with several muscles laid few do, and of those fewer
    # reach the disc: the work below is on those pairs alone, as flat arrays.
    height = np.einsum("kc,mc->mk", centres, axes) - np.einsum("mc,mc->m", points, axes)[:, None]
    section, sphere = np.nonzero(np.abs(height) < sphere_radii[None, :])
    height = height[section, sphere]
    axis = axes[section]
    in_plane = centres[sphere] - points[section] - height[:, None] * axis
    ahead = np.einsum("pc,pc->p", in_plane, sides[section])
    reach = radius[section] + np.sqrt(np.maximum(sphere_radii[sphere] ** 2 - height**2, 0.0)) + GAP
    spread = ahead**2 - np.einsum("pc,pc->p", in_plane, in_plane) + reach**2
    blocked = spread > 0.0
    section, ahead, root = section[blocked], ahead[blocked], np.sqrt(spread[blocked])
    low, high = ahead - root, ahead + root
    shift = np.zeros(len(points))
    for _ in range(_ROUNDS):
        inside = (low < shift[section]) & (shift[section] < high)
        if not inside.any():
            break
        np.maximum.at(shift, section[inside], high[inside])
    return shift
