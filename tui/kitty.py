"""Frames as images in the kitty graphics protocol
(https://sw.kovidgoyal.net/kitty/graphics-protocol/), as kitty, WezTerm, Ghostty and Konsole
speak it.

Each frame is sent as raw RGB (``f=24``), deflated (``o=z``: zlib at its fastest level, a
few milliseconds for a 1200x800 frame, against three times that for a PNG, and about as
small), in base64 chunks of 4096 bytes as the protocol asks. (The encoder is in ``tui/pixels.py``;
this module, free of Textual, also serves ``biceps snapshot --kitty``.) Every frame reuses one image
id and one placement id, so each replaces the last in place, without flicker; ``C=1`` keeps
the cursor still, ``q=2`` keeps the terminal from answering (its answers would reach the
app as keys). ``c`` and ``r`` stretch the frame over the picture's cells, whatever its size
in pixels.
"""

from __future__ import annotations

import base64
import zlib

import numpy as np

CHUNK = 4096  # base64 bytes per escape sequence, as the protocol asks
PLACEMENT = 1


def command(keys: str, payload: bytes = b"") -> str:
    """One graphics command: ``ESC _ G keys ; payload ESC \\``."""
    data = ";" + payload.decode("ascii") if payload else ""
    return f"\x1b_G{keys}{data}\x1b\\"


def transmit(frame: np.ndarray, image_id: int, columns: int, rows: int) -> str:
    """Send ``frame`` ((h, w, 3) uint8) and place it over ``columns x rows`` cells from the
    cursor, replacing the image ``image_id`` and its placement, if there are any."""
    height, width = frame.shape[:2]
    data = base64.b64encode(zlib.compress(np.ascontiguousarray(frame).data, 1))
    chunks = [data[at:at + CHUNK] for at in range(0, len(data), CHUNK)] or [b""]
    first = (f"a=T,f=24,o=z,s={width},v={height},i={image_id},p={PLACEMENT},"
             f"c={columns},r={rows},C=1,q=2")
    parts = []
    for index, chunk in enumerate(chunks):
        more = int(index < len(chunks) - 1)
        keys = f"{first},m={more}" if index == 0 else f"m={more},q=2"
        parts.append(command(keys, chunk))
    return "".join(parts)


def delete(image_id: int) -> str:
    """Take the image ``image_id`` off the screen and out of the terminal's memory."""
    return command(f"a=d,d=I,i={image_id},q=2")
