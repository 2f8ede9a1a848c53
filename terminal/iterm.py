"""Frames as iTerm2 inline images (https://iterm2.com/documentation-images.html), as iTerm2
and WezTerm show them.

The image is a PNG (Pillow's fastest compression: lossless, and what every terminal that
speaks the protocol decodes), stretched over the picture's cells (``width`` and ``height``
in cells, ``preserveAspectRatio=0``), so a frame of fewer pixels than the cells hold is
scaled up by the terminal. (The encoder is in ``tui/pixels.py``.)
"""

from __future__ import annotations

import base64
import io

import numpy as np
from PIL import Image


def png(frame: np.ndarray) -> bytes:
    """``frame`` ((h, w, 3) uint8) as a PNG file."""
    out = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(frame), "RGB").save(out, "PNG", compress_level=1)
    return out.getvalue()


def inline_image(data: bytes, columns: int, rows: int) -> str:
    """The OSC 1337 sequence showing the image file ``data`` over ``columns x rows`` cells."""
    arguments = (f"inline=1;size={len(data)};width={columns};height={rows};"
                 "preserveAspectRatio=0")
    return f"\x1b]1337;File={arguments}:{base64.b64encode(data).decode('ascii')}\x07"
