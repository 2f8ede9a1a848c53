"""Reading animations back for the tests: every frame decoded, and how far two pictures differ."""

from __future__ import annotations

from pathlib import Path

import av
import numpy as np
from PIL import Image, ImageSequence


def decoded(path: Path) -> list[np.ndarray]:
    """Every frame of a GIF, APNG, WebP (Pillow) or MP4 (PyAV) as (h, w, 3) uint8."""
    if path.suffix == ".mp4":
        with av.open(str(path)) as container:
            return [frame.to_ndarray(format="rgb24") for frame in container.decode(video=0)]
    with Image.open(path) as image:
        return [np.asarray(frame.convert("RGB")) for frame in ImageSequence.Iterator(image)]


def off(a: np.ndarray, b: np.ndarray, levels: int) -> float:
    """The share of pixels that differ by more than ``levels`` in some channel."""
    return float((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > levels).mean())
