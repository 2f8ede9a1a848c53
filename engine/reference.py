"""OpenSim's arm26 biceps (its long head, BIClong): the curves the model's are compared with.

The numbers are OpenSim's own, computed once by ``benchmarks/arm26_reference.py --write``
(arm26.osim, the shoulder at 0) and shipped as ``engine/data/arm26_biclong.json``, so that
neither the app nor the tests need opensim.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cache
from importlib.resources import files

import numpy as np


@dataclass(frozen=True)
class Curve:
    """A muscle's length and moment arm about the elbow against the elbow's flexion."""

    name: str  # as the plots label it
    source: str  # where the numbers come from
    flexion: np.ndarray  # (k,) float64, degrees, increasing
    length: np.ndarray  # (k,) float64, cm
    moment_arm: np.ndarray  # (k,) float64, cm

    def length_change(self, flexions: np.ndarray, start: float) -> np.ndarray:
        """The length at each of ``flexions`` (k,) less that at ``start`` degrees, cm,
        interpolated linearly between the stored angles."""
        return (np.interp(flexions, self.flexion, self.length)
                - np.interp(start, self.flexion, self.length))


@cache
def arm26_biclong() -> Curve:
    """arm26's BIClong every 10 degrees from 0 to 130."""
    data = json.loads(files("biceps.engine").joinpath("data/arm26_biclong.json").read_text())
    return Curve("arm26 BIClong", data["source"], np.array(data["flexion_deg"], float),
                 np.array(data["length_mm"]) / 10.0, np.array(data["moment_arm_mm"]) / 10.0)
