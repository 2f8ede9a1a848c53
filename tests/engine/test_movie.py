"""Animations written and decoded again: Pillow for GIF, APNG and WebP, PyAV for MP4."""

import sys

import av
import numpy as np
import pytest
from PIL import Image, ImageSequence

from biceps.engine.errors import BicepsError
from biceps.engine.movie import durations, write_animation
from decode import decoded, off


def _frames(count: int, width: int = 64, height: int = 48) -> list[np.ndarray]:
    """A dark picture with a light square that moves right frame by frame, and a red bar."""
    frames = []
    for k in range(count):
        frame = np.full((height, width, 3), (18, 22, 28), np.uint8)
        frame[8:24, 4 + 6 * k : 20 + 6 * k] = (230, 220, 200)
        frame[30:40, :] = (180, 60, 50)
        frames.append(frame)
    return frames


@pytest.mark.parametrize("suffix", [".gif", ".apng", ".webp", ".mp4"])
def test_every_frame_comes_back_at_its_size_and_in_its_place(tmp_path, suffix):
    frames = _frames(6)
    path = tmp_path / f"moving{suffix}"
    write_animation(path, frames, 25.0)
    back = decoded(path)
    assert len(back) == 6
    assert back[0].shape == (48, 64, 3)
    for k, (written, read) in enumerate(zip(frames, back)):
        assert off(written, read, 40) < 0.02, k  # each frame looks like its own...
        if k:
            assert off(frames[k - 1], read, 40) > 0.05, k  # ...and not like the one before


def test_apng_is_exact(tmp_path):
    frames = _frames(4)
    write_animation(tmp_path / "exact.apng", frames, 25.0)
    assert all(np.array_equal(a, b) for a, b in zip(frames, decoded(tmp_path / "exact.apng")))


def test_a_gif_keeps_the_colours_within_a_shared_palette(tmp_path):
    frames = _frames(4)
    write_animation(tmp_path / "palette.gif", frames, 25.0)
    for written, read in zip(frames, decoded(tmp_path / "palette.gif")):
        assert np.abs(written.astype(int) - read).max() <= 8


def test_a_gif_at_30_frames_a_second_keeps_the_cycle_length_in_hundredths(tmp_path):
    write_animation(tmp_path / "timed.gif", _frames(6), 30.0)
    with Image.open(tmp_path / "timed.gif") as image:
        shown = [frame.info["duration"] for frame in ImageSequence.Iterator(image)]
        assert image.info["loop"] == 0  # for ever
    assert shown == [30, 40, 30, 30, 40, 30]
    assert durations(6, 30.0, 10) == shown


def test_an_mp4_has_the_asked_frame_rate(tmp_path):
    write_animation(tmp_path / "rate.mp4", _frames(6), 30.0)
    with av.open(str(tmp_path / "rate.mp4")) as container:
        assert container.streams.video[0].average_rate == 30


@pytest.mark.parametrize(("name", "fps", "size", "message"), [
    ("fast.gif", 55.0, (64, 48), "a GIF plays at most 50 frames a second"),
    ("odd.mp4", 25.0, (63, 48), "MP4 video needs an even width and height, not 63x48"),
    ("slow.webp", 0.5, (64, 48), "the frame rate must be 1 to 60 a second, not 0.5"),
    ("arm.avi", 25.0, (64, 48), "must end in .gif, .apng, .webp, .mp4"),
])
def test_what_cannot_be_written_is_refused_and_nothing_is_written(tmp_path, name, fps, size,
                                                                   message):
    width, height = size
    with pytest.raises(BicepsError, match=message):
        write_animation(tmp_path / name, _frames(2, width, height), fps)
    assert list(tmp_path.iterdir()) == []


def test_mp4_without_pyav_names_the_extra_to_install(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "av", None)  # as if it were not installed
    with pytest.raises(BicepsError, match=r"needs PyAV.*pip install 'biceps\[video\]'"):
        write_animation(tmp_path / "arm.mp4", _frames(2), 25.0)
    assert list(tmp_path.iterdir()) == []


def test_an_interrupted_encoding_leaves_the_old_file_as_it_was(tmp_path, monkeypatch):
    path = tmp_path / "cycle.gif"
    path.write_bytes(b"the old animation")

    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr("biceps.engine.movie._shared_palette", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_animation(path, _frames(4), 25.0)
    assert path.read_bytes() == b"the old animation"
    assert list(tmp_path.iterdir()) == [path]
