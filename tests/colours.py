"""How far a picture in few colours is from the 24-bit one, as the eye sees it: OKLab
differences after a blur that averages a dither out, and the share of a coloured area shown
in other hues (``terminal/palette.py``; ``benchmarks/palette.py`` prints both)."""

from __future__ import annotations

import numpy as np

from biceps.terminal.palette import oklab

BELLY_CHROMA = 0.08  # OKLab chroma from which a pixel of the muscle is clearly coloured
BELLY_HUE = 30.0  # degrees either side of the muscle colour's hue that are its shading's
OFF_HUE = 25.0  # degrees of hue away from the 24-bit pixel's that count as another hue


def drawn(frame: np.ndarray, background: tuple[int, int, int]) -> np.ndarray:
    """Where ``frame`` ((h, w, 3) uint8) shows the arm: (h, w) bool."""
    return ~np.all(frame == np.array(background, np.uint8), axis=2)


def blurred_difference(truecolour: np.ndarray, shown: np.ndarray,
                       background: tuple[int, int, int]) -> float:
    """The mean OKLab distance between the two pictures ((h, w, 3) uint8) after a 2 x 2 box
    blur of each (the mean of every 2 x 2 window of sRGB values), over the windows wholly
    on the arm."""
    def blurred(picture):
        p = picture.astype(float)
        return (p[:-1, :-1] + p[1:, :-1] + p[:-1, 1:] + p[1:, 1:]) / 4

    arm = drawn(truecolour, background)
    windows = arm[:-1, :-1] & arm[1:, :-1] & arm[:-1, 1:] & arm[1:, 1:]
    distance = np.linalg.norm(oklab(blurred(truecolour)) - oklab(blurred(shown)), axis=2)
    return float(distance[windows].mean())


def hue(lab: np.ndarray) -> np.ndarray:
    """OKLab colours' hue in degrees, -180 to 180."""
    return np.degrees(np.arctan2(lab[..., 2], lab[..., 1]))


def off_hue_share(truecolour: np.ndarray, shown: np.ndarray, background: tuple[int, int, int],
                  muscle: tuple[int, int, int]) -> float:
    """The share of the belly's pixels (the arm's pixels of the ``muscle`` colour's hue, give
    or take BELLY_HUE, and at least BELLY_CHROMA) whose hue in ``shown`` is more than
    OFF_HUE degrees from the 24-bit picture's (a grey has none, and counts as off)."""
    true, seen = oklab(truecolour), oklab(shown)
    chroma = np.hypot(true[..., 1], true[..., 2])
    muscle_hue = hue(oklab(np.array(muscle)))
    belly = (drawn(truecolour, background) & (chroma >= BELLY_CHROMA)
             & (np.abs((hue(true) - muscle_hue + 180) % 360 - 180) <= BELLY_HUE))
    away = np.abs((hue(seen) - hue(true) + 180) % 360 - 180)
    seen_chroma = np.hypot(seen[..., 1], seen[..., 2])
    off = (away > OFF_HUE) | (seen_chroma < 1e-3)
    return float(off[belly].mean())
