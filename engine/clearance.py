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

A muscle laid over others (``engine/anatomy.py``) is moved the same way along a direction
turned round its axis, towards its own side of the arm (`best_lean`), the same all along
it, so that the elbow's muscles pack round the humerus instead of stacking in the plane of
the bend, and each bows out once, to one side, instead of winding round the bone. Where a
path bends round the elbow, its sections move only across the plane of the bend, which
keeps the volume there too (`path_offsets`).
"""

from __future__ import annotations

import numpy as np

from biceps.engine.stations import distances_along, section_radii, shares

RINGS_PER_SEGMENT = 4
"""Sections drawn per segment between two nodes, so the moves bend smoothly..."""
MOST_SECTIONS = 1024
"""...while that makes no more than this many: a muscle of thousands of nodes has sections
enough in its nodes alone, and one of 16,384 would otherwise have 65,533."""
_BLOCK = 4096  # sections tested against the spheres at a time: (block, spheres) arrays

GAP = 0.1  # cm kept between muscle and bone
SLOPE = 0.7  # the most a section moves per cm along the muscle
HOLD = 1.0  # cm at either end where the tendon holds on to its bone and does not move
LEANS = np.radians(np.arange(0.0, 80.5, 10.0))
"""The leans a muscle laid over others may take (see `best_lean`), straight first: up to 80
degrees round from straight away from the elbow, towards its side of the arm."""
TURN = 3.0  # cm before a bend over which a leaning muscle's moves turn across the bend
_ROUNDS = 24  # passes over the intervals; each lifts a section past one more bone


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
    share = shares(count)
    axis = (end - start) / np.linalg.norm(end - start)
    return path_offsets(start + np.outer(share, end - start), np.tile(axis, (count, 1)),
                        radii, centres, sphere_radii)


def path_offsets(points, axes, radii, centres, sphere_radii, lean: float = 0.0,
                 one_bulge: bool = False) -> np.ndarray:
    """The sideways moves (m, 3) of m sections centred at ``points`` (m, 3), equally spaced
    along a path (straight, or bent round the elbow), each in the plane across its unit
    ``axes`` (m, 3), that keep the muscle of node ``radii`` (n,) clear of the spheres; m - 1
    is a multiple of n - 1. ``lean`` (radians) turns the direction of the moves about each
    section's axis, from straight away from the elbow towards the arm's outside (``+z``;
    negative: its inside), the same all along the muscle, so that it bulges to one side
    and never winds round the bone.

    On a straight stretch the planes are parallel, so any move keeps the volume
    (Cavalieri). Where the path bends round the elbow, a section moved away from the bend
    or towards it would lengthen or shorten the tube there and change its volume (Pappus),
    so a bent section moves only along the bend's binormal, across the plane of the bend:
    the lean turns to a quarter within ``TURN`` cm of the bend, and what is left of the
    move in the bend's plane eases off towards it at ``SLOPE``.

    With ``one_bulge`` (a muscle laid over others) the moves rise to their largest and fall
    from it, never dipping between two humps, so that the muscle bows out once, in one
    direction, and never snakes (a dip between the humeral head and the belly would bend
    it in and out again).
    """
    along = distances_along(points)
    near = _from_bend(along, axes)
    leans = _bend_leans(near, len(points), lean)
    sides = _sides(points, axes)
    way = _leaning(sides, _turned(sides, axes), leans) if leans.any() else sides
    radius = section_radii(radii, len(points))
    shift = _least_shifts(points, radius, axes, way, centres, sphere_radii)
    return _smoothed(along, near, shift, np.abs(np.cos(leans)), one_bulge)[:, None] * way


def _from_bend(along: np.ndarray, axes: np.ndarray) -> np.ndarray | None:
    """(m,) each section's distance along the path from the nearest bent one (`_bends`),
    given their places ``along`` it (m,) and unit ``axes`` (m, 3); None for a straight
    path."""
    bent = np.flatnonzero(_bends(axes))
    if not bent.size:
        return None
    return np.min(np.abs(along[:, None] - along[bent][None, :]), axis=1)


def _bend_leans(near: np.ndarray | None, count: int, lean: float) -> np.ndarray:
    """(count,) each section's lean: the muscle's ``lean``, turned to a quarter (the bend's
    binormal, on the same side) over the last ``TURN`` cm before a bend (``near``: see
    `_from_bend`)."""
    leans = np.full(count, float(lean))
    if near is None or not lean:
        return leans
    share = np.clip(1.0 - near / TURN, 0.0, 1.0)
    return leans + (np.copysign(np.pi / 2, lean) - leans) * share


def _smoothed(along, near, shift, across, one_bulge: bool = False) -> np.ndarray:
    """(m,) how far the sections move, given their places ``along`` the path (m,), their
    distances from a bend (``near``, see `_from_bend`) and the least moves (m,) that clear
    them (see `path_offsets`); ``across`` (m,) is the share of each move that lies in the
    plane of a bend."""
    length = along[-1]
    shift = shift.copy()
    shift[(along < HOLD) | (along > length - HOLD)] = 0.0
    # The least smooth profile above the needs: each need spreads down both ways at SLOPE,
    # max_j (shift_j - SLOPE |a_i - a_j|), the larger of a running maximum from each end
    # (an m x m array of every pair would take 34 GB at 16,384 nodes).
    rising = np.maximum.accumulate(shift + SLOPE * along) - SLOPE * along
    falling = (np.maximum.accumulate((shift - SLOPE * along)[::-1]) + SLOPE * along[::-1])[::-1]
    smooth = np.maximum(rising, falling)
    if one_bulge:  # each valley filled up to the lower of the highest moves either side
        smooth = np.minimum(np.maximum.accumulate(smooth),
                            np.maximum.accumulate(smooth[::-1])[::-1])
    smooth[[0, -1]] = 0.0  # the attachments themselves stay on the bone
    if near is not None:
        with np.errstate(divide="ignore"):
            smooth = np.minimum(smooth, np.where(across > 1e-9, SLOPE * near / across, np.inf))
    return smooth


def lean_reaches(points, axes, radii, centres, sphere_radii) -> tuple[np.ndarray, np.ndarray]:
    """Each lean of :data:`LEANS` (radians, see `path_offsets`), turned towards the side of
    the arm the muscle's line lies on (the outside for a line whose sections lie outside
    the elbow's middle on the whole, ``z >= 0``), and how far the muscle would reach from
    the humerus's axis (the world's ``y``) above the elbow, so leaning (cm): (k,) each.
    The sections ``points`` and ``axes`` (m, 3) and the rest as in `path_offsets`."""
    # Judged on the nodes' sections alone (64 at most), which the spheres cut once for all
    # the leans.
    nodes = np.linspace(0, len(points) - 1, min(len(radii), 64)).round().astype(int)
    points, axes = points[nodes], axes[nodes]
    radii = section_radii(radii, len(nodes))
    sides = _sides(points, axes)
    turned = _turned(sides, axes)
    along = distances_along(points)
    near = _from_bend(along, axes)
    cuts = _cuts(points, radii, axes, centres, sphere_radii)
    leans = LEANS * (1.0 if points[:, 2].mean() >= 0.0 else -1.0)
    reaches = []
    for lean in leans:
        turns = _bend_leans(near, len(points), lean)
        way = _leaning(sides, turned, turns)
        shift = _smoothed(along, near, _shifts(*cuts, way, len(points)), np.abs(np.cos(turns)),
                          one_bulge=True)
        reaches.append(reach(points + shift[:, None] * way, radii))
    return leans, np.array(reaches)


def best_lean(leans: np.ndarray, reaches: np.ndarray, bound: float = 0.0) -> float:
    """Of ``leans`` (k,), the one whose ``reaches`` (k,) (see `lean_reaches`) is least, to
    a millimetre, counting none as less than ``bound`` (cm, how far the muscles laid before
    it reach already), the most turned of those that tie: so that the muscle keeps closest
    round the humerus, beside the muscles laid before it, and turns as far to its own side
    as it can without the arm reaching farther, leaving the middle to those laid over it."""
    return float(leans[np.lexsort((-np.abs(leans), np.round(np.maximum(reaches, bound), 1)))[0]])


def reach(centres: np.ndarray, radii: np.ndarray) -> float:
    """How far the sections (centres (m, 3), radii (m,)) reach from the humerus's axis (the
    world's ``y``) above the elbow (cm); 0 if none lies above it."""
    above = centres[:, 1] > 0.0
    return float(np.max(np.hypot(centres[above, 0], centres[above, 2]) + radii[above],
                        initial=0.0))


def _turned(sides: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """(m, 3) the unit ``sides`` (m, 3) turned a quarter about the unit ``axes``, towards
    the arm's outside (``+z``)."""
    # np.cross's own formula, written out (the same bits): its checks and axis moves cost
    # more than the arithmetic on a muscle's few dozen sections.
    (ax, ay, az), (sx, sy, sz) = axes.T, sides.T
    turned = np.column_stack([ay * sz - az * sy, az * sx - ax * sz, ax * sy - ay * sx])
    return turned * np.where(turned[:, 2:] < 0.0, -1.0, 1.0)


def _leaning(sides: np.ndarray, turned: np.ndarray, lean) -> np.ndarray:
    """(m, 3) the unit ``sides`` (m, 3) turned about their sections' axes by ``lean``
    radians, one for all or (m,) one each, towards ``turned`` (`_turned`) for a positive
    lean."""
    lean = np.asarray(lean, dtype=np.float64)
    if not lean.any():
        return sides
    lean = np.broadcast_to(lean, len(sides))[:, None]
    return np.cos(lean) * sides + np.sin(lean) * turned


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
    return _shifts(*_cuts(points, radius, axes, centres, sphere_radii), sides, len(points))


def _cuts(points, radius, axes, centres, sphere_radii):
    """The pairs (section, sphere) where the sphere cuts the section's plane: the section's
    index (p,), the sphere's circle's centre from the section's (p, 3) and how far apart
    the two must keep (p,)."""
    # Each sphere's centre above each section's plane. Only the pairs where the sphere cuts
    # the section's plane can block; with several muscles laid few do, and of those fewer
    # reach the disc: the work below is on those pairs alone, as flat arrays.
    # The spheres' heights along each distinct axis, once: the sections of a straight
    # stretch share theirs, so a path has one or two runs of them but for a bend's arc;
    # (m, k) products over every section would be a good part of a muscle's clearance.
    # The same einsum on fewer rows gives the same bits.
    first = np.ones(len(axes), dtype=bool)
    first[1:] = np.any(axes[1:] != axes[:-1], axis=1)
    height = (np.einsum("kc,uc->uk", centres, axes[first])[np.cumsum(first) - 1]
              - np.einsum("mc,mc->m", points, axes)[:, None])
    # The pairs as flat indices and rows gathered by np.take: the same values as np.nonzero
    # on the (m, k) mask and fancy indexing, which cost several times as much.
    pairs = np.flatnonzero(np.abs(height) < sphere_radii)
    section, sphere = np.divmod(pairs, len(centres))
    height = height.ravel()[pairs]
    in_plane = (np.take(centres, sphere, axis=0) - np.take(points, section, axis=0)
                - height[:, None] * np.take(axes, section, axis=0))
    reach = radius[section] + np.sqrt(np.maximum(sphere_radii[sphere] ** 2 - height**2, 0.0)) + GAP
    return section, in_plane, reach


def _shifts(section, in_plane, reach, sides, count: int) -> np.ndarray:
    """(count,) each section's least move s >= 0 along its unit side (``sides`` (count, 3))
    that keeps it clear of every circle (`_cuts`): each rules out one interval of s."""
    ahead = np.einsum("pc,pc->p", in_plane, np.take(sides, section, axis=0))
    spread = ahead**2 - np.einsum("pc,pc->p", in_plane, in_plane) + reach**2
    blocked = spread > 0.0
    section, ahead, root = section[blocked], ahead[blocked], np.sqrt(spread[blocked])
    low, high = ahead - root, ahead + root
    shift = np.zeros(count)
    for _ in range(_ROUNDS):
        inside = (low < shift[section]) & (shift[section] < high)
        if not inside.any():
            break
        np.maximum.at(shift, section[inside], high[inside])
    return shift
