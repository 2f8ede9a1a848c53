"""Moving pictures out: GIF, APNG and WebP through Pillow, MP4 through PyAV, written atomically.

Every format is encoded in memory and the file replaced in one step, so a refusal or a
failure half way leaves no half-written file. MP4 needs PyAV, the optional extra
``biceps[video]``; the other formats need nothing beyond Pillow.
"""

from __future__ import annotations

import io
from fractions import Fraction
from pathlib import Path
from typing import Callable

import numpy as np
from PIL import Image, features

from biceps.engine.errors import BicepsError
from biceps.engine.export import PNG_COMPRESS_LEVEL, check_writable
from biceps.engine.files import write_atomically
from biceps.engine.names import printable

ANIMATION_FORMATS = (".gif", ".apng", ".webp", ".mp4")

FPS_RANGE = (1.0, 60.0)

GIF_MOST_FPS = 50.0
"""A GIF counts time in hundredths of a second, and browsers play a delay below 2 of them
as 10: faster than 50 frames a second a GIF plays slower, not faster."""

WEBP_QUALITY = 90  # lossy: the default cycle in 143 KB against the GIF's 198, and no palette
MP4_CODEC = "libx264"  # H.264, which every player plays
MP4_CRF = 18  # x264's constant quality: about what the eye cannot tell from the frames
BT709 = 1  # FFmpeg's number for ITU-R BT.709 colour (primaries, transfer and matrix alike)

VIDEO_EXTRA = "pip install 'biceps[video]' (installed with pipx: pipx inject biceps av)"

Progress = Callable[[int, int], None]
"""Told ``(done, total)`` after each step of a long job: a frame rendered or encoded."""


def check_animation(path: Path, width: int, height: int, fps: float,
                    read: Path | None = None) -> None:
    """Raise :class:`BicepsError` now, before any rendering, if ``path`` cannot be written
    at this size and frame rate, or is ``read``, the configuration it is made from."""
    check_writable(path, *ANIMATION_FORMATS, read=read)
    low, high = FPS_RANGE
    if not low <= fps <= high:
        raise BicepsError(f"the frame rate must be {low:g} to {high:g} a second, not {fps:g}")
    suffix = path.suffix.lower()
    if suffix == ".gif" and fps > GIF_MOST_FPS:
        raise BicepsError(
            f"{printable(path)}: a GIF plays at most {GIF_MOST_FPS:g} frames a second (browsers slow "
            f"down shorter delays), not {fps:g}; lower --fps, or write .apng, .webp or .mp4"
        )
    if suffix == ".webp" and not features.check("webp"):
        raise BicepsError(f"{printable(path)}: this Pillow was built without WebP; write .gif or .apng")
    if suffix == ".mp4":
        _check_mp4_encoder(path)
        if width % 2 or height % 2:
            raise BicepsError(
                f"{printable(path)}: MP4 video needs an even width and height, not {width}x{height}"
            )


def write_animation(path: Path, frames: list[np.ndarray], fps: float,
                    progress: Progress | None = None) -> None:
    """Write ``frames`` (each (h, w, 3) uint8, in playing order) to ``path`` at ``fps``
    frames a second, repeating for ever where the format can say so. The format follows the
    suffix; ``progress`` is told ``(done, total)`` frames encoded."""
    height, width = frames[0].shape[:2]
    check_animation(path, width, height, fps)
    tell = progress or (lambda done, total: None)
    suffix = path.suffix.lower()
    if suffix == ".mp4":
        data = _mp4(frames, fps, tell)
    else:
        data = _pillow(suffix, frames, fps, tell)
    write_atomically(path, data)


def durations(count: int, fps: float, unit_ms: int) -> list[int]:
    """Each frame's display time in ms, in whole ``unit_ms``: rounded where the frame ends,
    not frame by frame, so the cycle keeps its length (30 frames a second in a GIF's
    hundredths is 30, 40, 30 ms..., not 30 ms throughout, which would play 11 % fast)."""
    ends = [round((k + 1) * 1000 / fps / unit_ms) * unit_ms for k in range(count)]
    return [end - start for start, end in zip([0, *ends], ends)]


def _pillow(suffix: str, frames: list[np.ndarray], fps: float, tell: Progress) -> bytes:
    if suffix == ".gif":
        pictures = _shared_palette(frames, tell)
        options = {"format": "GIF", "duration": durations(len(frames), fps, 10)}
    else:
        pictures = _pictures(frames)
        options = {"format": "PNG", "compress_level": PNG_COMPRESS_LEVEL} if suffix == ".apng" \
            else {"format": "WEBP", "quality": WEBP_QUALITY}
        options["duration"] = durations(len(frames), fps, 1)
    buffer = io.BytesIO()
    pictures[0].save(buffer, save_all=True, append_images=pictures[1:], loop=0, **options)
    tell(len(frames), len(frames))
    return buffer.getvalue()


def _pictures(frames: list[np.ndarray]) -> list[Image.Image]:
    """The frames as pictures, one for each different frame however often it is shown (a
    bounce shows each twice): Pillow keeps an RGB picture in 4 bytes a pixel."""
    made: dict[int, Image.Image] = {}
    for frame in frames:
        if id(frame) not in made:
            made[id(frame)] = Image.fromarray(frame, "RGB")
    return [made[id(frame)] for frame in frames]


def _shared_palette(frames: list[np.ndarray], tell: Progress) -> list[Image.Image]:
    """The frames in one 256-colour palette, made from all of them (median cut), without
    dithering: the same colour stays the same index from frame to frame, so the still
    background and bones do not shimmer, and each frame stores only what moved."""
    distinct = list({id(frame): frame for frame in frames}.values())
    sample = np.concatenate([frame[::4, ::4] for frame in distinct])
    palette = Image.fromarray(sample, "RGB").quantize(256, method=Image.Quantize.MEDIANCUT)
    quantized: dict[int, Image.Image] = {}
    pictures = []
    for done, frame in enumerate(frames, 1):
        if id(frame) not in quantized:
            quantized[id(frame)] = Image.fromarray(frame, "RGB").quantize(
                palette=palette, dither=Image.Dither.NONE)
        pictures.append(quantized[id(frame)])
        tell(done - 1, len(frames))  # the last counts once the whole file is encoded
    return pictures


def _check_mp4_encoder(path: Path) -> None:
    try:
        import av
    except ImportError:
        raise BicepsError(
            f"{printable(path)}: writing MP4 needs PyAV, which is not installed; it comes with the "
            f"optional extra 'video': {VIDEO_EXTRA}"
        ) from None
    try:
        av.Codec(MP4_CODEC, "w")
    except ValueError:  # an FFmpeg built without it
        raise BicepsError(f"{printable(path)}: this PyAV's FFmpeg has no {MP4_CODEC} (H.264) encoder; "
                          "write .gif, .apng or .webp") from None


def _mp4(frames: list[np.ndarray], fps: float, tell: Progress) -> bytes:
    """H.264 in 4:2:0, converted from RGB with the BT.709 matrix and tagged so, which is
    what players assume of HD video (untagged, many take BT.601 and shift the reds)."""
    import av

    height, width = frames[0].shape[:2]
    buffer = io.BytesIO()
    with av.open(buffer, mode="w", format="mp4") as container:
        stream = container.add_stream(MP4_CODEC, rate=Fraction(fps).limit_denominator(1001))
        stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
        stream.options = {"crf": str(MP4_CRF)}
        context = stream.codec_context
        context.colorspace = context.color_primaries = context.color_trc = BT709
        context.color_range = 1  # limited ("MPEG") range, as players expect
        for done, frame in enumerate(frames, 1):
            picture = av.VideoFrame.from_ndarray(frame, format="rgb24")
            container.mux(stream.encode(picture.reformat(format="yuv420p",
                                                         dst_colorspace="itu709")))
            tell(done, len(frames))
        container.mux(stream.encode())  # what the encoder still holds
    return buffer.getvalue()
