"""A muscle's sections: equally spaced along it from origin to insertion, each with the
radius the node profile gives it, each so far along its (straight or bent) path.

Clearance (``engine/clearance.py``), packing (``engine/packing.py``), the paths
(``engine/path.py``) and the bent mesh (``engine/mesh.py``) all place sections so; here it
is done once, and the equal steps of a count are worked out once a process (a pose of the
elbow's six asked for them some 40 times: numpy's ``linspace`` costs 3 microseconds a call
whatever the count).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np


@lru_cache(maxsize=64)
def shares(count: int) -> np.ndarray:
    """(count,) float64, read-only: ``count`` equal steps from 0 to 1, both ends included
    (``np.linspace(0.0, 1.0, count)``)."""
    steps = np.linspace(0.0, 1.0, count)
    steps.flags.writeable = False
    return steps


def section_radii(radii: np.ndarray, count: int) -> np.ndarray:
    """(count,) the radii of ``count`` sections equally spaced along a muscle of node
    ``radii`` (n,): the nodes' profile, linear between nodes."""
    return np.interp(shares(count), shares(len(radii)), radii)


def distances_along(points: np.ndarray) -> np.ndarray:
    """(m,) each point's distance along the path through ``points`` (m, 3) from the first."""
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
