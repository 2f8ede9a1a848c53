"""OpenSim's arm26 model's frames, and where world space puts them: apart from arm26's paths
(``engine/arm26.py``), which build on the skeleton (``engine/skeleton.py``), so that the
skeleton takes the humeral head's place from here with no import circle.

arm26's frames: the humerus's origin is the humeral head's centre, its x forward, y up, z
to the outside; the scapula ("base") holds the shoulder joint at ``SHOULDER`` and, with the
shoulder at its rest angle (as every pose here has it), does not turn against the humerus;
the forearm ("r_ulna_radius_hand") turns about ``ELBOW_AXIS`` through ``ELBOW``, by the
flexion in radians. World space (``engine/skeleton.py``) puts the elbow's centre at the
origin and its hinge on z, so the hinge is arm26's axis exactly: world x and y are turned
about it so that the humeral head lies straight up (+y), with the head 2.26 cm to the
outside of the elbow's centre (arm26's hinge is 85.5 degrees, not 90, to the humerus).
"""

from __future__ import annotations

import numpy as np

SHOULDER = (-0.017545, -0.007, 0.17)
"""The shoulder joint in the scapula's frame ("base"): its points less this are the humerus's."""
ELBOW = (0.0061, -0.2904, -0.0123)
"""The elbow's centre in the humerus's frame (r_elbow's parent offset)."""
ELBOW_AXIS = (0.04940001, 0.03660001, 0.99810825)
"""The hinge's direction in the humerus's frame, the same in the forearm's at any flexion."""


def _axes() -> np.ndarray:
    """(3, 3): world x, y, z as rows, in the humerus's frame (see the module's docstring)."""
    z = np.array(ELBOW_AXIS) / np.linalg.norm(ELBOW_AXIS)
    up = -np.array(ELBOW)  # from the elbow's centre to the head's
    y = up - (up @ z) * z
    y /= np.linalg.norm(y)
    return np.stack([np.cross(y, z), y, z])


WORLD = _axes()
"""Rows x, y, z of world space in the humerus's frame: a point ``p`` (m) of the humerus is
``100 WORLD (p - ELBOW)`` cm in world space."""


def world_point(body: str, location) -> np.ndarray:
    """(3,) cm: a point of arm26's ``body`` at ``location`` (m) in world space, the forearm
    held straight (0 degrees of flexion)."""
    location = np.asarray(location, dtype=np.float64)
    if body == "r_ulna_radius_hand":
        return 100.0 * WORLD @ location
    if body == "base":
        location = location - SHOULDER
    return 100.0 * WORLD @ (location - ELBOW)


HEAD = world_point("r_humerus", (0.0, 0.0, 0.0))
"""(3,) cm: the humeral head's centre (arm26's humerus origin) in world space."""
