"""OpenSim's arm26 model, as much of it as the elbow's six muscles need: their path points,
the wrapping surfaces they pass, and the elbow's hinge, moved into this program's frames.

arm26 is the upper extremity of Holzbaur, Murray and Delp (2005, "A model of the upper
extremity for simulating musculoskeletal surgery and analyzing neuromuscular control",
Annals of Biomedical Engineering 33, 829-840), adapted by the OpenSim Development Team
(``Models/Arm26/arm26.osim`` of opensim-models), and licensed under Creative Commons
Attribution 3.0. The numbers below are that file's, in its units (metres, radians) and
frames, so each can be checked against it; `path` moves them into world space
(``engine/arm26_frame.py``).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from biceps.engine.arm26_frame import WORLD, world_point
from biceps.engine.lies import Lie
from biceps.engine.path import PathWrap, ViaPath
from biceps.engine.skeleton import Attachment
from biceps.engine.wrapping import Cylinder, Ellipsoid, Surface

MUSCLES = ("BIClong", "BICshort", "BRA", "TRIlong", "TRIlat", "TRImed")

POINTS: dict[str, tuple[tuple[str, tuple[float, float, float]], ...]] = {
    "TRIlong": (("base", (-0.05365, -0.01373, 0.14723)),
                ("r_humerus", (-0.02714, -0.11441, -0.00664)),
                ("r_humerus", (-0.03184, -0.22637, -0.01217)),
                ("r_humerus", (-0.01743, -0.26757, -0.01208)),
                ("r_ulna_radius_hand", (-0.0219, 0.01046, -0.00078))),
    "TRIlat": (("r_humerus", (-0.00599, -0.12646, 0.00428)),
               ("r_humerus", (-0.02344, -0.14528, 0.00928)),
               ("r_humerus", (-0.03184, -0.22637, -0.01217)),
               ("r_humerus", (-0.01743, -0.26757, -0.01208)),
               ("r_ulna_radius_hand", (-0.0219, 0.01046, -0.00078))),
    "TRImed": (("r_humerus", (-0.00838, -0.13695, -0.00906)),
               ("r_humerus", (-0.02601, -0.15139, -0.0108)),
               ("r_humerus", (-0.03184, -0.22637, -0.01217)),
               ("r_humerus", (-0.01743, -0.26757, -0.01208)),
               ("r_ulna_radius_hand", (-0.0219, 0.01046, -0.00078))),
    "BIClong": (("base", (-0.039235, 0.00347, 0.14795)),
                ("base", (-0.028945, 0.01391, 0.15639)),
                ("r_humerus", (0.02131, 0.01793, 0.01028)),
                ("r_humerus", (0.02378, -0.00511, 0.01201)),
                ("r_humerus", (0.01345, -0.02827, 0.00136)),
                ("r_humerus", (0.01068, -0.07736, -0.00165)),
                ("r_humerus", (0.01703, -0.12125, 0.00024)),
                ("r_humerus", (0.0228, -0.1754, -0.0063)),
                ("r_ulna_radius_hand", (0.00751, -0.04839, 0.02179))),
    "BICshort": (("base", (0.004675, -0.01231, 0.13475)),
                 ("base", (-0.007075, -0.04004, 0.14507)),
                 ("r_humerus", (0.01117, -0.07576, -0.01101)),
                 ("r_humerus", (0.01703, -0.12125, -0.01079)),
                 ("r_humerus", (0.0228, -0.1754, -0.0063)),
                 ("r_ulna_radius_hand", (0.00751, -0.04839, 0.02179))),
    "BRA": (("r_humerus", (0.0068, -0.1739, -0.0036)),
            ("r_ulna_radius_hand", (-0.0032, -0.0239, 0.0009))),
}
"""Each muscle's path points, origin to insertion: the body each is fixed to, and where."""

# Each wrap object: its kind, body, xyz_body_rotation, translation, quadrant and size (a
# cylinder's radius and length, an ellipsoid's three semi-axes).
SURFACES = {
    "TRIlongglen": ("cylinder", "base", (1.37532, -0.294612, 2.43596),
                    (-0.043905, -0.0039, 0.1478), "x", (0.003, 0.03)),
    "TRI": ("cylinder", "r_humerus", (-0.14015, -0.00628319, 0.154985),
            (0.0028, -0.2919, -0.0069), "all", (0.016, 0.05)),
    "TRIlonghh": ("ellipsoid", "r_humerus", (3.00162, -0.853466, 2.57419),
                  (-0.0078, -0.0041, -0.0014), "z", (0.035, 0.02, 0.02)),
    "BIClonghh": ("ellipsoid", "r_humerus", (-2.00434, -1.00164, 0.975465),
                  (0.0033, 0.0073, 0.0003), "-y", (0.025, 0.02, 0.02)),
}

WRAPS: dict[str, tuple[tuple[str, tuple[int, int] | None], ...]] = {
    "TRIlong": (("TRI", None), ("TRIlonghh", None), ("TRIlongglen", None)),
    "TRIlat": (("TRI", None),),
    "TRImed": (("TRI", None),),
    "BIClong": (("BIClonghh", (2, 3)),),
    "BICshort": (),
    "BRA": (("TRI", None),),
}
"""Each muscle's wraps, in order: the surface and the range of its path points (1-based,
both ends included, as arm26's ``range``; None for ``-1 -1``, the whole path)."""

BONES: dict[str, tuple[str, str]] = {
    "BIClong": ("scapula", "radius"),  # the supraglenoid tubercle; the radial tuberosity
    "BICshort": ("scapula", "radius"),  # the coracoid process's tip
    "BRA": ("humerus", "ulna"),  # the front of the humerus's lower half; the coronoid
    "TRIlong": ("scapula", "ulna"),  # the infraglenoid tubercle; the olecranon
    "TRIlat": ("humerus", "ulna"),  # the back of the humerus above the radial groove
    "TRImed": ("humerus", "ulna"),  # and below it
}
"""The bones each muscle's origin and insertion hold on to, by their anatomical names."""


LIES: dict[str, Lie] = {
    # The brachialis broad and flat on the front of the humerus's lower half.
    "BRA": Lie(side=(0.0, 0.0), aspect=4.0, spread=100.0, lowest=-5.0),
    # The biceps over it: the short head from inside the front, the long head beside it
    # from outside; from 20 cm above the elbow down they make one belly, split in front.
    "BICshort": Lie(side=(-40.0, 0.0), aspect=1.5, spread=45.0, wall=1, merge_below=20.0,
                    lane=-0.3, band=-1),
    # The triceps' medial head deep on the back of the humerus, the lateral head over its
    # outer side, the long head over its inner side.
    # Towards the elbow the biceps' two tendons make one, flat, on the radial tuberosity; the
    # triceps' three one broad tendon on the olecranon, the medial head's in the middle.
    "TRImed": Lie(side=(180.0, 180.0), aspect=3.0, spread=90.0, band=0, seam=0.45),
    "TRIlat": Lie(side=(125.0, 150.0), aspect=1.8, spread=50.0, lane=0.85, band=1,
                  seam=0.45),
    "TRIlong": Lie(side=(-145.0, -160.0), aspect=3.0, spread=55.0, beside="TRIlat",
                   lane=-0.85, band=-1, seam=0.45),
    "BIClong": Lie(side=(40.0, 15.0), aspect=1.5, spread=45.0, beside="BICshort", wall=-1,
                   merge_below=20.0, lane=0.3, band=1),
}
"""Where each of the six lies round the humerus (``engine/layers.py``), as anatomy atlases
draw a mid-arm section: the biceps and brachialis in front, the triceps behind."""


def attachment(body: str, location) -> Attachment:
    """The point of arm26's ``body`` at ``location`` (m) as an attachment (see
    `Attachment.in_frame`): on the forearm if it is fixed to the forearm, else on the upper
    arm (the scapula does not move against the humerus here)."""
    x, y, z = world_point(body, location)
    if body == "r_ulna_radius_hand":
        return Attachment("forearm", -y, x, z)
    return Attachment("upper_arm", y, x, z)


def _rotation(angles) -> np.ndarray:
    """(3, 3) Simbody's body-fixed x-y-z rotation by ``angles`` (radians): Rx Ry Rz."""
    (cx, cy, cz), (sx, sy, sz) = np.cos(angles), np.sin(angles)
    about_x = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    about_y = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    about_z = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    return about_x @ about_y @ about_z


def _quadrant(name: str) -> tuple[int, int] | None:
    if name == "all":
        return None
    return "xyz".index(name[-1]), -1 if name.startswith("-") else 1


@lru_cache(maxsize=None)
def surface(name: str) -> Surface:
    """arm26's wrap object ``name`` in world space (cm)."""
    kind, body, angles, translation, quadrant, size = SURFACES[name]
    placed = dict(centre=world_point(body, translation),
                  rotation=WORLD @ _rotation(angles), quadrant=_quadrant(quadrant))
    if kind == "cylinder":
        return Cylinder(radius=100.0 * size[0], length=100.0 * size[1], **placed)
    return Ellipsoid(radii=100.0 * np.array(size), **placed)


@lru_cache(maxsize=None)
def path(name: str) -> ViaPath:
    """arm26's path of the muscle ``name`` (one of :data:`MUSCLES`), world space, cm."""
    points = tuple(attachment(body, location) for body, location in POINTS[name])
    wraps = []
    for surface_name, span in WRAPS[name]:
        first, last = (span[0] - 1, span[1] - 1) if span else (0, len(points) - 1)
        wraps.append(PathWrap(surface(surface_name), first, last))
    return ViaPath(points, tuple(wraps))
