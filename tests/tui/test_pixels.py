"""The encoders of real pixels, decoded back: kitty and iTerm2 payloads give the frame
exactly; sixel, decoded by libsixel's sixel2png, gives the frame in the palette's colours."""

from __future__ import annotations

import base64
import io
import os
import re
import shutil
import subprocess
import unicodedata
import zlib

import numpy as np
import pytest
from PIL import Image
from rich.style import Style
from textual.geometry import Size

from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal import kitty
from biceps.tui.pixels import ItermImages, KittyGraphics, KittyPlaceholders, Sixel
from biceps.terminal.sixel import quantised, sixel_image
from colours import blurred_difference

CELL = Size(10, 20)


@pytest.fixture(scope="module")
def frame() -> np.ndarray:
    """The bundled model at 24 x 9 cells of 10 x 20 pixels."""
    return SceneRenderer().render(Scene.of(load_config(DEFAULT_CONFIG)), 240, 180).copy()


def test_kitty_payload_decodes_to_the_frame_exactly(frame):
    picture = KittyGraphics(CELL, image_id=7).encode(frame)
    commands = re.findall(r"\x1b_G([^;\x1b]*);?([^\x1b]*)\x1b\\", picture.image)
    keys = dict(item.split("=") for item in commands[0][0].split(","))
    assert keys | {"m": "1"} == keys | {"a": "T", "f": "24", "o": "z", "s": "240", "v": "180",
                                        "i": "7", "c": "24", "r": "9", "C": "1", "q": "2",
                                        "m": "1"}
    assert [c[0].split(",")[0] for c in commands[1:]] == ["m=1"] * (len(commands) - 2) + ["m=0"]
    assert all(len(payload) <= 4096 for _, payload in commands)
    data = zlib.decompress(base64.b64decode("".join(payload for _, payload in commands)))
    np.testing.assert_array_equal(np.frombuffer(data, np.uint8).reshape(frame.shape), frame)


def test_the_placeholder_diacritics_follow_kittys_rule():
    # Combining class 230, no decomposition, in no composition; the Unicode 6.0 ones (the
    # list's age is not in unicodedata: its length and last character pin it).
    composing = {int(part, 16) for code in range(0x110000)
                 if (mapping := unicodedata.decomposition(chr(code)))
                 and not mapping.startswith("<") for part in mapping.split()}
    for mark in kitty.DIACRITICS:
        assert unicodedata.combining(mark) == 230 and unicodedata.decomposition(mark) == ""
        assert ord(mark) not in composing
    assert len(kitty.DIACRITICS) == 297 and kitty.DIACRITICS[-1] == "\U0001d244"
    assert kitty.DIACRITICS == sorted(kitty.DIACRITICS)


def test_through_tmux_the_placeholders_are_the_lines_and_the_image_is_passed_through(frame):
    encoder = KittyPlaceholders(CELL, image_id=42)
    picture = encoder.encode(frame)
    assert all(strip.cell_length == 24 for strip in picture.strips)
    cells = [(segment.text, segment.style.color.number) for segment in picture.strips[3]
             if segment.text.strip()]
    assert cells == [("".join("\U0010eeee" + kitty.DIACRITICS[3] + kitty.DIACRITICS[column]
                              for column in range(24)), 42)]
    # Each command in its own passthrough, escapes doubled; unwrapped, a virtual placement.
    assert picture.image.startswith("\x1bPtmux;") and picture.image.endswith("\x1b\\")
    wrapped = [piece.removesuffix("\x1b\\") for piece in picture.image.split("\x1bPtmux;")[1:]]
    assert all(piece.count("\x1b") == 2 * piece.count("\x1b\x1b") for piece in wrapped)
    commands = [piece.replace("\x1b\x1b", "\x1b") for piece in wrapped]
    assert commands[0].startswith("\x1b_Ga=T,f=24,o=z,s=240,v=180,i=42,U=1,c=24,r=9,q=2,m=")
    payload = "".join(command.split(";", 1)[1][:-2] for command in commands)
    data = zlib.decompress(base64.b64decode(payload))
    np.testing.assert_array_equal(np.frombuffer(data, np.uint8).reshape(frame.shape), frame)
    assert encoder.clear() == "\x1bPtmux;\x1b\x1b_Ga=d,d=I,i=42,q=2\x1b\x1b\\\x1b\\"


def test_kitty_clearing_deletes_its_own_image():
    assert KittyGraphics(CELL, image_id=7).clear() == "\x1b_Ga=d,d=I,i=7,q=2\x1b\\"


def test_iterm_payload_decodes_to_the_frame_exactly(frame):
    image = ItermImages(CELL).encode(frame).image
    match = re.fullmatch(r"\x1b\]1337;File=([^:]*):([A-Za-z0-9+/=]*)\x07", image)
    arguments = dict(item.split("=") for item in match[1].split(";"))
    assert arguments == {"inline": "1", "size": str(len(base64.b64decode(match[2]))),
                         "width": "24", "height": "9", "preserveAspectRatio": "0"}
    decoded = np.asarray(Image.open(io.BytesIO(base64.b64decode(match[2]))).convert("RGB"))
    np.testing.assert_array_equal(decoded, frame)


def _sixel2png(image: str, tmp_path) -> np.ndarray:
    if shutil.which("sixel2png") is None:
        if os.environ.get("CI"):
            pytest.fail("sixel2png is missing: .ci/run installs Debian's libsixel-bin")
        pytest.skip("sixel2png (Debian's libsixel-bin) is not installed")
    source, target = tmp_path / "frame.six", tmp_path / "frame.png"
    source.write_text(image)
    subprocess.run(["sixel2png", "-i", str(source), "-o", str(target)], check=True)
    return np.asarray(Image.open(target).convert("RGB")).astype(int)


def test_sixel_decodes_to_the_frame_in_its_palette(frame, tmp_path):
    indices, palette = quantised(frame, 256)
    decoded = _sixel2png(Sixel(CELL).encode(frame).image, tmp_path)
    assert decoded.shape == frame.shape
    # Exactly the palette's colours, up to sixel's colours in whole percent (255 / 100 / 2).
    assert np.abs(decoded - palette[indices]).max() <= 2
    # And the palette is close to the frame: the fast octree's error, measured for this
    # frame as a mean of 0.4 and at most 9 in a channel, within a margin.
    error = np.abs(decoded - frame)
    assert error.mean() < 1.0 and error.max() <= 16


@pytest.mark.parametrize("height", [1, 5, 6, 7, 13])
def test_sixel_bands_end_with_the_image(height, tmp_path):
    # Heights that are not a multiple of a band's six pixels, and a band of one row.
    rng = np.random.default_rng(height)
    palette = np.array([[0, 0, 0], [255, 0, 0], [0, 255, 0], [0, 0, 255]], np.uint8)
    indices = rng.integers(0, 4, (height, 9)).astype(np.uint8)
    decoded = _sixel2png(sixel_image(indices, palette), tmp_path)
    np.testing.assert_array_equal(decoded, palette[indices])


def test_sixel_runs_and_a_full_buffer():
    # One colour across a wide image: a run per band, "!width~"; and a palette image big
    # enough to outgrow the first buffer (the encoder grows it and starts again).
    flat = sixel_image(np.zeros((12, 500), np.uint8), np.array([[255, 255, 255]], np.uint8))
    assert flat.endswith("#0!500~-#0!500~\x1b\\")
    noisy = np.random.default_rng(1).integers(0, 256, (300, 600)).astype(np.uint8)
    palette = np.random.default_rng(2).integers(0, 256, (256, 3)).astype(np.uint8)
    assert len(sixel_image(noisy, palette)) > (1 << 16)


@pytest.mark.parametrize("encoder", [KittyGraphics(CELL, 7), Sixel(CELL), ItermImages(CELL)],
                         ids=["kitty", "sixel", "iterm"])
def test_the_lines_under_an_image_are_sent_only_when_its_size_changes(encoder, frame):
    first = encoder.encode(frame)
    assert first.changed == [(0, 9)] and len(first.strips) == 9
    assert all(strip.cell_length == 24 for strip in first.strips)
    assert encoder.encode(frame).changed == []
    assert encoder.encode(frame[:160, :200]).changed == [(0, 8)]
    encoder.reset()
    assert encoder.encode(frame[:160, :200]).changed == [(0, 8)]


def test_sixel_larger_than_the_terminal_takes_is_scaled_into_the_middle(frame, tmp_path):
    # xterm draws no sixel image larger than its maxGraphicSize (1000x1000 by default, as
    # it answers XTSMGRAPHICS): a smaller one, in the middle of the picture's cells.
    image = Sixel(CELL, limit=(120, 90)).encode(frame).image  # a frame of 240x180 pixels
    moved = re.match(r"(?:\x1b\[(\d+)B)?(?:\x1b\[(\d+)C)?\x1bP", image)
    decoded = _sixel2png(image[moved.end() - 2:], tmp_path)
    assert decoded.shape == (90, 120, 3)  # half the size: the limit's, at the frame's shape
    # 12 x 5 cells of 24 x 9: moved down (9 - 5) // 2 rows and (24 - 12) // 2 columns.
    assert (moved[1], moved[2]) == ("2", "6")
    scaled = np.asarray(Image.fromarray(frame).resize((120, 90), Image.Resampling.BOX))
    assert np.abs(decoded - scaled).mean() < 1.5  # (its 256-colour palette)


def test_sixel_with_few_colour_registers_is_dithered_onto_them(frame, tmp_path):
    dithered = _sixel2png(Sixel(CELL, colours=16).encode(frame).image, tmp_path)
    assert len(np.unique(dithered.reshape(-1, 3), axis=0)) <= 16
    octree = Image.fromarray(frame).quantize(16, method=Image.Quantize.FASTOCTREE,
                                             dither=Image.Dither.NONE)
    palette = np.asarray(octree.getpalette()[:48], np.uint8).reshape(16, 3)
    posterised = _sixel2png(sixel_image(np.asarray(octree), palette), tmp_path)
    # Seen from a little way off, the dithered picture is the nearer (OKLab, after a 2 x 2
    # blur): measured 0.014 against the octree's bands, 0.019.
    background = tuple(frame[0, 0].tolist())
    assert (blurred_difference(frame, dithered, background)
            < blurred_difference(frame, posterised, background))


def test_the_lines_under_an_image_are_on_the_pictures_background(frame):
    encoder = KittyGraphics(CELL, 7)
    encoder.background = Style(bgcolor="#12161c")
    strip = encoder.encode(frame).strips[0]
    assert [segment.style.bgcolor.triplet.hex for segment in strip] == ["#12161c"]
