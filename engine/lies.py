"""How a muscle lies round the humerus (`Lie`), apart from the layers that use it
(``engine/layers.py``), so that a model's table of them (``engine/arm26.py``) is read without
compiling anything: ``info`` and ``sweep`` import no numba."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Lie:
    """Where a muscle lies round the humerus: the angle of its side (``side``, degrees
    round from the front towards the outside, at the top of its stretch down the upper arm
    and at its bottom), how flat its slices are (``aspect``, width over thickness) and how
    far round either way they may spread from their middle (``spread``, degrees).
    ``beside``: a muscle laid before it that it lies against, on the side of it that
    ``side`` is on (its slices then start at that muscle's edge, wherever it has one).
    Below ``merge_below`` (cm above the elbow's centre) two such muscles make one belly:
    each slice is then thickest at its ``wall`` edge (+1 its edge round towards the outside,
    -1 towards the inside), where the two meet, so that together they make one round
    slice; a muscle with a wall has it at ``side`` there. ``lane``: how far along the
    hinge (cm, towards the outside) its tendon keeps from its path towards its insertion,
    beside the others that end on the same point. ``lowest``: the least height (cm above
    the elbow's centre) its slices go down to; below, it keeps to its path. ``band``: the
    part it forms of one flat tendon that heads sharing an insertion make together, towards
    it (None: its tendon is round): -1 or 1 a side part (towards the inside or the
    outside along the hinge), its inner edge ``seam`` cm from the path; 0 the middle part,
    ``seam`` cm wide either side of the path."""

    side: tuple[float, float]
    aspect: float = 1.6
    spread: float = 60.0
    beside: str | None = None
    wall: int = 0
    merge_below: float = -math.inf
    lane: float = 0.0
    lowest: float = 0.0
    band: int | None = None
    seam: float = 0.0
