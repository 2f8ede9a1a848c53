"""What a model, a picture and an animation cost, checked against their bounds
(``engine/bounds.py``) before any work: a file, a dialog and the command line each say the
limit and the figure that passed it, rather than hanging or running out of memory."""

from __future__ import annotations

from typing import Sequence

from biceps.engine.bounds import (ANIMATION_BYTES, LAYING, MESH_VERTICES, MUSCLES, NODES,
                                  PICTURE_BYTES)
from biceps.engine.errors import BicepsError, RefusedChange

PICTURE_SAMPLE_BYTES = 3 + 4  # a colour and a depth per sample
PICTURE_PIXEL_BYTES = 3  # the picture averaged down, when it is supersampled
FRAME_BYTES = 3 + 4  # an animation's frame, kept, and its copy in the encoder (Pillow: RGBX)


def model_problem(nodes: Sequence[int], segments: int) -> tuple[str, str] | None:
    """Whether a model of muscles of ``nodes`` nodes each (the driver's first), drawn with
    ``segments`` round each, costs more than the bounds allow: what is over ("muscles",
    "nodes" or "segments") and a sentence with the limit and the figure; None if not.
    The nodes are bounded twice: all together, and times the muscles (what laying them
    round each other costs)."""
    if len(nodes) > MUSCLES:
        return "muscles", (f"{len(nodes):,} muscles; a model has at most {MUSCLES}, each laid "
                           "round the others at every pose")
    total = sum(nodes)
    if total > NODES:
        return "nodes", (f"{total:,} nodes; a model has at most {NODES:,}, all its muscles "
                         "together")
    if len(nodes) * total > LAYING:
        return "nodes", (f"{len(nodes)} muscles of {total:,} nodes together, each laid round "
                         f"the others: {len(nodes)} muscles may have at most "
                         f"{LAYING // len(nodes):,} nodes together")
    vertices = total * segments
    if vertices > MESH_VERTICES:
        return "segments", (f"{total:,} nodes at {segments:,} segments round each make "
                            f"{vertices:,} vertices; at most {MESH_VERTICES:,} are drawn: "
                            f"give at most {MESH_VERTICES // total:,} segments, or fewer nodes")
    return None


def check_model(nodes: Sequence[int], segments: int) -> None:
    """Raise :class:`RefusedChange` if :func:`model_problem` finds one."""
    problem = model_problem(nodes, segments)
    if problem is not None:
        raise RefusedChange(problem[1])


def picture_bytes(width: int, height: int, ssaa: int) -> int:
    """The memory a picture's buffers take, ``ssaa`` x ``ssaa`` samples a pixel."""
    averaged = PICTURE_PIXEL_BYTES if ssaa > 1 else 0
    return width * height * (ssaa * ssaa * PICTURE_SAMPLE_BYTES + averaged)


def check_picture(width: int, height: int, ssaa: int) -> None:
    """Raise :class:`BicepsError` if a picture this large would take more memory than
    :data:`PICTURE_BYTES`."""
    needed = picture_bytes(width, height, ssaa)
    if needed > PICTURE_BYTES:
        sampled = f" with {ssaa}x{ssaa} supersampling" if ssaa > 1 else ""
        raise BicepsError(f"a picture of {width}x{height}{sampled} needs {_gib(needed)} of "
                          f"memory, more than the {_gib(PICTURE_BYTES)} allowed: ask for a "
                          "smaller size or less supersampling")


def check_frames(frames: int, width: int, height: int) -> None:
    """Raise :class:`BicepsError` if ``frames`` different frames of this size would take
    more memory than :data:`ANIMATION_BYTES` as they are encoded."""
    needed = frames * width * height * FRAME_BYTES
    if needed > ANIMATION_BYTES:
        most = ANIMATION_BYTES // (width * height * FRAME_BYTES)
        raise BicepsError(f"{frames:,} different frames of {width}x{height} need "
                          f"{_gib(needed)} of memory to encode, more than the "
                          f"{_gib(ANIMATION_BYTES)} allowed: at this size at most {most:,} "
                          "different frames (a bounce shows each twice); ask for fewer "
                          "frames or a smaller size")


def _gib(count: int) -> str:
    return f"{count / (1 << 30):.2f} GiB"
