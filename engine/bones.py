"""The bones: the shoulder blade's glenoid, the humerus, the radius and the ulna, built from
profiles revolved about axes (no copied meshes).

Each bone is a few closed parts (the humerus: its shaft, head, tubercles and the spool of
its condyles), each a profile of radii along an axis placed in the bone's frame (see
``engine/skeleton.py``): the upper arm's parts stay put, the forearm's turn with the elbow.
The parts of one bone overlap where they join, as a bone's processes grow out of it; the
picture's depth test and the meshes' volumes do not mind.

Proportions are an adult's, from the OpenSim arm26 model's geometry (its humerus 29.1 cm
from the elbow's centre to the head's, its forearm 25.4 cm; its humeral head of radius about
2.2 cm, after the wrapping ellipsoid BIClonghh), scaled with the skeleton's bone lengths.
The knobs on which the muscle's tendons end (the supraglenoid tubercle, the radial
tuberosity) are built to reach the skeleton's attachments wherever they are, so a tendon
always ends on bone.

A part also gives its profile as spheres (centres and radii, world space), the cheap shape
with which the muscle keeps clear of it (``engine/clearance.py``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from biceps.engine.arm26_frame import HEAD, world_point
from biceps.engine.mesh import Mesh, revolved_mesh
from biceps.engine.skeleton import ArmPose, Skeleton

ARM26_UPPER_ARM = 29.1
ARM26_FOREARM = 25.4
HEAD_RADIUS = 2.2  # arm26's BIClonghh wrapping ellipsoid: 2.5 by 2 by 2 cm
STEP = 0.6  # cm between the profile's samples along a part's axis
MOST_SAMPLES = 32
"""Samples between two knots at most: an adult's bones take up to 17 at STEP; a bone scaled
to kilometres takes no more (at 0.6 cm each, a humerus of 1e6 cm took millions, 5 GB)."""


@dataclass(frozen=True, eq=False)
class Part:
    """One closed piece of a bone: a profile (k, 2) of rows (distance along the axis,
    radius), pole to pole, revolved about the line from ``start`` (3,) along the unit
    ``axis`` (3,), in its bone's frame."""

    start: np.ndarray
    axis: np.ndarray
    profile: np.ndarray

    def mesh(self, segments: int) -> Mesh:
        return revolved_mesh(self.profile, self.start, self.axis, segments)

    def spheres(self) -> tuple[np.ndarray, np.ndarray]:
        """Centres (k, 3) and radii (k,) of spheres along the axis, one per profile point."""
        x, r = self.profile[1:-1].T
        return self.start + np.outer(x, self.axis), r


def profile(knots, ends: tuple[float, float], step: float = STEP) -> np.ndarray:
    """A smooth profile (k, 2), pole to pole, through ``knots`` (j, 2) rows (distance along
    the axis, radius), j >= 2, increasing distances.

    Between knots the radius follows a Catmull-Rom spline, sampled every ``step`` cm or
    closer (but :data:`MOST_SAMPLES` times at most); each end closes with a quarter ellipse
    as long as that end's entry of ``ends`` (the end's radius: a hemisphere; less: a flatter
    end).
    """
    knots = np.asarray(knots, dtype=np.float64)
    x, r = knots.T
    slopes = np.gradient(r, x)  # Catmull-Rom's tangents, for knots unevenly spaced
    samples = [knots[:1]]
    for i in range(len(knots) - 1):
        count = min(max(1, int(np.ceil((x[i + 1] - x[i]) / step))), MOST_SAMPLES)
        t = np.linspace(0.0, 1.0, count + 1)[1:]
        h = x[i + 1] - x[i]
        radius = ((2 * t**3 - 3 * t**2 + 1) * r[i] + (t**3 - 2 * t**2 + t) * h * slopes[i]
                  + (-2 * t**3 + 3 * t**2) * r[i + 1] + (t**3 - t**2) * h * slopes[i + 1])
        # The spline between knots of very different radii (the ulna's, sized with both
        # bones, when one is five times the other) can dip below zero: a part is never
        # thinner than half its thinnest knot (an adult's bones never come near).
        samples.append(np.column_stack([x[i] + t * h, np.maximum(radius, 0.5 * r.min())]))
    body = np.concatenate(samples)
    arcs = np.linspace(0.0, np.pi / 2, 5)[:-1]  # elevations from the pole, the ring excluded
    before = np.column_stack([x[0] - ends[0] * np.cos(arcs), r[0] * np.sin(arcs)])
    after = np.column_stack([x[-1] + ends[1] * np.cos(arcs), r[-1] * np.sin(arcs)])[::-1]
    return np.concatenate([before, body, after])


def _rod(start, end, radius: float) -> Part:
    """A rod of ``radius`` from ``start`` to ``end`` (3,), rounded at both ends."""
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    length = float(np.linalg.norm(end - start))
    axis = (end - start) / length if length > 0 else np.array([0.0, 1.0, 0.0])
    return Part(start, axis, profile([[0.0, radius], [length, radius]], (radius, radius)))


def _knob(base, tip, radius: float) -> Part:
    """A rounded knob of ``radius`` growing from ``base`` towards ``tip`` (3,) and ending
    exactly there: a tubercle under a tendon's end."""
    base, tip = np.asarray(base, dtype=np.float64), np.asarray(tip, dtype=np.float64)
    reach = float(np.linalg.norm(tip - base))
    direction = (tip - base) / reach if reach > 0 else np.array([0.0, 1.0, 0.0])
    return _rod(base, tip - direction * radius if reach > radius else base, radius)


def _along(start, end, knots, ends) -> Part:
    """A part whose profile runs from ``start`` towards ``end`` (3,); ``knots`` as in
    `profile`, distances as fractions of the way from start to end."""
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    length = float(np.linalg.norm(end - start))
    knots = np.asarray(knots, dtype=np.float64) * [length, 1.0]
    return Part(start, (end - start) / length, profile(knots, ends))


@lru_cache(maxsize=16)
def bone_parts(skeleton: Skeleton) -> dict[str, tuple[bool, tuple[Part, ...]]]:
    """Each bone's parts, by name ("scapula", "humerus", "radius", "ulna"), in its frame, and
    whether it turns with the forearm. Cached: the bones change only with the skeleton."""
    if skeleton.model == "arm26":
        return _arm26_bones()
    up = skeleton.upper_arm / ARM26_UPPER_ARM  # each side's scale
    fore = skeleton.forearm / ARM26_FOREARM
    return {"scapula": (False, _scapula(skeleton, up)), "humerus": (False, _humerus(skeleton, up)),
            "radius": (True, _radius(skeleton, fore)), "ulna": (True, _ulna(skeleton, up, fore))}


def _humerus(skeleton: Skeleton, up: float) -> tuple[Part, ...]:
    top = skeleton.upper_arm
    return (
        # The shaft, from inside the condyles to inside the head: flared above the elbow,
        # slender in the middle, widening to the surgical neck.
        Part(np.zeros(3), np.array([0.0, 1.0, 0.0]), profile(
            np.array([[0.6, 1.35], [1.6, 1.4], [3.0, 1.22], [5.5, 1.0], [9.0, 0.9],
                      [15.0, 0.86], [21.0, 0.95], [24.5, 1.2], [26.5, 1.55], [27.6, 1.8]]) * up,
            (1.0 * up, 1.0 * up))),
        Part(np.array([0.0, top, 0.0]), np.array([0.0, 1.0, 0.0]),
             _sphere_profile(HEAD_RADIUS * up)),
        # The greater tubercle, a bulge on the outside of the neck, and the lesser, in front;
        # the biceps' tendon runs in the groove between them.
        _rod(np.array([0.5, top - 0.9 * up, 1.0 * up]), np.array([0.6, top - 2.0 * up, 0.9 * up]),
             1.25 * up),
        _rod(np.array([1.0, top - 1.1 * up, -0.5 * up]), np.array([0.9, top - 1.8 * up, -0.5 * up]),
             0.75 * up),
        # The condyles, a spool about the elbow's axis: the trochlea inside, under the ulna,
        # the capitulum outside, under the radius, the epicondyles at either end.
        Part(np.array([0.0, 0.0, -3.2 * up]), np.array([0.0, 0.0, 1.0]), profile(
            np.array([[0.0, 0.55], [0.5, 0.8], [1.1, 1.12], [2.0, 0.95], [2.8, 1.12],
                      [3.2, 0.98], [3.6, 1.05], [4.5, 1.05], [5.1, 0.8], [5.6, 0.55]]) * up,
            (0.4 * up, 0.4 * up))),
    )


def _scapula(skeleton: Skeleton, up: float) -> tuple[Part, ...]:
    glenoid = np.array([0.0, skeleton.upper_arm, -(HEAD_RADIUS + 0.1) * up])
    return (
        # The glenoid's face against the head, the neck, and the start of the blade.
        _along(glenoid, glenoid + [0.0, 0.0, -3.5 * up],
               [[0.0, 1.2 * up], [0.12, 1.3 * up], [0.45, 0.95 * up], [1.0, 1.35 * up]],
               (0.15 * up, 0.9 * up)),
        # The supraglenoid tubercle, under the origin.
        _knob(glenoid + [0.0, 0.8 * up, -0.4 * up], skeleton.origin.in_frame(), 0.45 * up),
    )


# The forearm's parts are placed as the straight arm holds them: along is -y, forward +x,
# lateral +z (see `Attachment.in_frame`).


def _radius(skeleton: Skeleton, fore: float) -> tuple[Part, ...]:
    top = np.array([0.0, -1.15 * fore, 1.45 * fore])  # under the capitulum
    end = np.array([0.2 * fore, -skeleton.forearm, 2.0 * fore])
    insertion = skeleton.insertion.in_frame()
    level = (top[1] - insertion[1]) / (top[1] - end[1])  # how far down the radius it sits
    return (
        _along(top, end,
               [[0.0, 1.05 * fore], [0.04, 1.05 * fore], [0.07, 0.7 * fore], [0.15, 0.62 * fore],
                [0.45, 0.68 * fore], [0.75, 0.82 * fore], [0.92, 1.05 * fore],
                [1.0, 1.35 * fore]], (0.2 * fore, 0.4 * fore)),
        # The radial tuberosity, under the insertion.
        _knob(top + np.clip(level, 0.0, 1.0) * (end - top), insertion, 0.5 * fore),
    )


def _ulna(skeleton: Skeleton, up: float, fore: float) -> tuple[Part, ...]:
    # From the olecranon's tip, behind and above the elbow (so sized with the humerus), to
    # the ulna's head at the wrist; the trochlear notch wraps the trochlea.
    return (
        _along([-1.55 * up, 2.3 * up, -1.0 * up], [-0.3 * fore, -skeleton.forearm, -1.3 * fore],
               [[0.0, 0.95 * up], [0.06, 1.3 * up], [0.13, 1.2 * up], [0.2, 1.0 * fore],
                [0.35, 0.78 * fore], [0.7, 0.6 * fore], [0.95, 0.55 * fore],
                [1.0, 0.75 * fore]], (0.8 * up, 0.6 * fore)),
    )


def _arm26_bones() -> dict[str, tuple[bool, tuple[Part, ...]]]:
    """arm26's bones: built round its landmarks (``engine/arm26.py``, world space, the
    forearm's as the straight arm holds them), each muscle's origin and insertion on a knob
    of the bone arm26 names for it, ending exactly at the attachment."""
    from biceps.engine import arm26  # whose paths build on this package's skeleton

    parts = {"scapula": list(_arm26_scapula()), "humerus": list(_arm26_humerus()),
             "radius": list(_arm26_radius()), "ulna": list(_arm26_ulna())}
    axes = {"scapula": None, "humerus": (np.zeros(3), HEAD),
            "radius": (RADIUS_TOP, RADIUS_END), "ulna": (ULNA_TOP, ULNA_END)}
    for name in arm26.MUSCLES:
        path = arm26.path(name)
        for bone, point in zip(arm26.BONES[name], (path.origin, path.insertion)):
            if bone == "scapula":
                continue  # its tubercles and the coracoid are built to their tendons
            tip = point.in_frame()
            start, end = axes[bone]
            base = _nearest_on(start, end, tip)
            if not _inside(parts[bone], tip):
                parts[bone].append(_knob(base, tip, 0.45))
    return {name: (name in ("radius", "ulna"), tuple(bone)) for name, bone in parts.items()}


ARM26_HEAD_RADIUS = 2.2
"""cm: the humeral head, as far inside arm26's wrapping ellipsoid (BIClonghh, 2.5 by 2 by 2
cm) as BIClong's tendon needs over it (its path stays 2.67 cm from the head's centre)."""
RADIUS_TOP = np.array([0.0, -1.15, 1.55])  # the radial head, under the capitulum
RADIUS_END = np.array([-0.6, -23.0, 6.8])  # beside arm26's radial styloid (-1.1, -23.9, 8.5)
ULNA_TOP = np.array([-1.63, 0.83, -0.15])  # under the olecranon's tip (arm26's TRI*-P5)
ULNA_END = np.array([-0.9, -23.0, 3.0])  # the ulna's head, inside the radius's at the wrist


def _arm26_humerus() -> tuple[Part, ...]:
    up = HEAD / np.linalg.norm(HEAD)
    return (
        # The shaft, from inside the condyles to inside the head (arm26's humerus leans
        # 4.5 degrees out from square to its hinge).
        Part(np.zeros(3), up, profile(
            np.array([[0.6, 1.35], [1.6, 1.4], [3.0, 1.22], [5.5, 1.0], [9.0, 0.9],
                      [15.0, 0.86], [21.0, 0.95], [24.5, 1.2], [26.5, 1.55], [27.6, 1.8]]),
            (1.0, 1.0))),
        Part(HEAD, up, _sphere_profile(ARM26_HEAD_RADIUS)),
        # The greater tubercle outside and the lesser in front, either side of the groove
        # that BIClong's tendon runs down (arm26's BIClong-P3 and P4).
        _rod(HEAD + [0.5, -0.6, 1.6], HEAD + [0.6, -2.0, 1.7], 1.1),
        _rod(HEAD + [1.0, -1.0, -0.4], HEAD + [0.9, -1.8, -0.4], 0.7),
        # The condyles, a spool along the hinge: the medial epicondyle, the trochlea under
        # the ulna, the capitulum under the radius, the lateral epicondyle (arm26's marker
        # r_humerus_epicondyle is 4.2 cm outside the hinge's centre). Its axis is that of
        # arm26's wrapping cylinder "TRI", 4 mm behind the hinge, so that the tendons
        # wrapped round that (1.6 cm) pass clear of it.
        Part(np.array([-0.36, -0.16, -3.0]), np.array([0.0, 0.0, 1.0]), profile(
            np.array([[0.0, 0.55], [0.5, 0.85], [1.0, 1.1], [1.9, 0.95], [2.8, 1.1],
                      [3.3, 0.95], [3.6, 1.05], [4.8, 1.05], [5.6, 0.8], [6.8, 0.55]]),
            (0.4, 0.4))),
    )


def _arm26_scapula() -> tuple[Part, ...]:
    from biceps.engine.arm26 import POINTS

    supraglenoid = world_point(*POINTS["BIClong"][0])
    infraglenoid = world_point(*POINTS["TRIlong"][0])
    coracoid = world_point(*POINTS["BICshort"][0])
    acromion = world_point("base", (-0.01256, 0.04, 0.17))  # arm26's marker r_acromion
    # The glenoid faces the head between its two tubercles, a hair off the head's surface.
    middle = 0.5 * (supraglenoid + infraglenoid)
    facing = (HEAD - middle) / np.linalg.norm(HEAD - middle)
    glenoid = HEAD - (ARM26_HEAD_RADIUS + 0.1) * facing
    neck = glenoid - 2.5 * facing
    blade = neck + np.array([-2.5, -2.0, -2.5])  # the body, behind and inside the chest wall
    spine = neck + np.array([-1.5, 3.0, -1.0])  # the spine's root, behind and above the neck
    return (
        # The glenoid's shallow face against the head, and the neck behind it.
        _along(glenoid, neck, [[0.0, 1.3], [0.15, 1.4], [0.55, 1.0], [1.0, 1.3]], (0.15, 0.9)),
        # The blade, a flat disc turned to lie against the ribs.
        Part(blade, np.array([0.7, 0.0, -0.7]) / np.sqrt(0.98),
             profile([[0.0, 4.0], [0.5, 4.0]], (0.25, 0.25))),
        _rod(neck, blade, 1.1),
        # The supraglenoid and infraglenoid tubercles, under the biceps' and the triceps'
        # long heads.
        _knob(neck + 0.6 * (supraglenoid - neck), supraglenoid, 0.45),
        _knob(neck + 0.5 * (infraglenoid - neck), infraglenoid, 0.5),
        # The coracoid: up from the neck, then hooked forward to its tip, under the short
        # head.
        _rod(neck, neck + np.array([0.6, 1.6, 0.2]), 0.7),
        _knob(neck + np.array([0.6, 1.6, 0.2]), coracoid, 0.55),
        # The spine and a short acromion, arching over the head to arm26's marker.
        _rod(neck, spine, 0.8),
        _knob(spine, acromion, 0.8),
    )


def _arm26_radius() -> tuple[Part, ...]:
    from biceps.engine.arm26 import POINTS

    return (_along(RADIUS_TOP, RADIUS_END,
                   [[0.0, 1.05], [0.04, 1.05], [0.07, 0.7], [0.15, 0.62], [0.45, 0.68],
                    [0.75, 0.82], [0.92, 1.05], [1.0, 1.35]], (0.2, 0.4)),
            # The radial tuberosity, as wide across as the biceps' two tendons side by side.
            _ridge(world_point(*POINTS["BIClong"][-1]), RADIUS_TOP, RADIUS_END, 0.5, 0.55))


def _ridge(point: np.ndarray, start: np.ndarray, end: np.ndarray, radius: float,
           reach: float) -> Part:
    """A rod of ``radius`` along the hinge (z) whose surface passes through ``point`` (3,)
    on its side towards the bone's axis (from ``start`` to ``end``), ``reach`` cm either
    side of it: a bone's edge that tendons end on side by side."""
    inward = _nearest_on(start, end, point) - point
    inward[2] = 0.0
    centre = point + radius * inward / np.linalg.norm(inward)
    across = np.array([0.0, 0.0, reach])
    return _rod(centre - across, centre + across, radius)


def _arm26_ulna() -> tuple[Part, ...]:
    from biceps.engine.arm26 import POINTS

    coronoid = world_point(*POINTS["BRA"][-1])
    return (
        # From the olecranon's tip down to the ulna's head; the trochlear notch leaves the
        # trochlea room.
        _along(ULNA_TOP, ULNA_END,
               [[0.0, 0.6], [0.05, 0.75], [0.12, 0.7], [0.2, 0.75], [0.35, 0.7], [0.7, 0.55],
                [0.95, 0.5], [1.0, 0.75]], (0.6, 0.6)),
        # The coronoid process, forward under the trochlea, where the brachialis ends.
        _knob(ULNA_TOP + 0.15 * (ULNA_END - ULNA_TOP), coronoid, 0.5),
        # The olecranon, as wide across as the triceps' three tendons side by side.
        _ridge(world_point(*POINTS["TRIlat"][-1]), np.zeros(3), ULNA_TOP, 0.55, 1.2),
    )


def _nearest_on(start: np.ndarray, end: np.ndarray, point: np.ndarray) -> np.ndarray:
    """(3,) the point of the segment from ``start`` to ``end`` nearest ``point``."""
    along = end - start
    share = np.clip((point - start) @ along / (along @ along), 0.0, 1.0)
    return start + share * along


def _inside(parts, point: np.ndarray) -> bool:
    """Whether ``point`` (3,) lies inside any of the ``parts`` (by their spheres)."""
    for part in parts:
        centres, radii = part.spheres()
        if np.any(np.linalg.norm(centres - point, axis=1) < radii):
            return True
    return False


def _sphere_profile(radius: float, bands: int = 16) -> np.ndarray:
    """A sphere's profile (bands + 1, 2) about its centre, pole to pole."""
    elevations = np.linspace(-np.pi / 2, np.pi / 2, bands + 1)
    rows = np.column_stack([radius * np.sin(elevations), radius * np.cos(elevations)])
    rows[[0, -1], 1] = 0.0
    return rows


@lru_cache(maxsize=16)
def _bone_meshes(skeleton: Skeleton, segments: int) -> dict[str, tuple[bool, Mesh]]:
    return {name: (turns, Mesh.concatenate(part.mesh(segments) for part in parts))
            for name, (turns, parts) in bone_parts(skeleton).items()}


def bone_meshes(skeleton: Skeleton, pose: ArmPose, segments: int) -> dict[str, Mesh]:
    """Each bone as one mesh (of closed parts) in world space, in ``pose``."""
    return {name: _posed(mesh, pose) if turns else mesh
            for name, (turns, mesh) in _bone_meshes(skeleton, segments).items()}


def bone_spheres(skeleton: Skeleton, pose: ArmPose) -> tuple[np.ndarray, np.ndarray]:
    """Every bone part's spheres in world space, in ``pose``: centres (k, 3), radii (k,)."""
    centres, radii = [], []
    for turns, parts in bone_parts(skeleton).values():
        for part in parts:
            centre, radius = part.spheres()
            centres.append(_turned(centre, pose) if turns else centre)
            radii.append(radius)
    return np.concatenate(centres), np.concatenate(radii)


def _turned(points: np.ndarray, pose: ArmPose) -> np.ndarray:
    """Points (k, 3) of the straight forearm, turned with the elbow into ``pose``."""
    return points @ _straight_to(pose).T


def _straight_to(pose: ArmPose) -> np.ndarray:
    """(3, 3): the rotation about the elbow's axis from the straight arm to ``pose``. The
    forearm frame at 0 degrees has columns (0, -1, 0), (1, 0, 0), (0, 0, 1)."""
    straight = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    return pose.forearm_frame @ straight.T


def _posed(mesh: Mesh, pose: ArmPose) -> Mesh:
    rotation = _straight_to(pose)
    return Mesh(mesh.vertices @ rotation.T, mesh.normals @ rotation.T, mesh.triangles)
