"""A 256-colour terminal: the picture mapped onto the palette, smooth and true to its
colours and hues, on the background's own colour (the acceptance figures are in
tests/cli/test_snapshot_colours.py)."""

from __future__ import annotations

import numpy as np
import pytest
import textual.constants
from rich._palettes import EIGHT_BIT_PALETTE
from rich.color import Color, ColorSystem, ColorType

from biceps.engine.config import rgb
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal.palette import COLOURS, FIRST, Palette256, colour, nearest, oklab
from biceps.tui.widgets.viewport import Viewport
from colours import blurred_difference, off_hue_share
from pictures import shown_cells
from test_app_encoder import Corners, OneViewport, _shown

BACKGROUND = (0x12, 0x16, 0x1C)  # the bundled model's


@pytest.fixture
def frame(config) -> np.ndarray:
    """The bundled model, large enough that its shading has room to be smooth."""
    scene = Scene.of(config).with_view(scale=2.0)
    return SceneRenderer().render(scene, 160, 120).copy()


def _block_error(picture: np.ndarray, frame: np.ndarray, block: int = 4) -> float:
    """The mean colour difference between the two on the arm, over blocks of block x block
    pixels: what the eye sees from a little way off, where dithering averages out and bands
    do not. (The background is left out: it is one flat colour, checked on its own.)"""
    h, w = (frame.shape[0] // block) * block, (frame.shape[1] // block) * block
    arm = ~np.all(frame == BACKGROUND, axis=2)[:h, :w]

    def means(image):
        image = np.where(arm[..., None], image[:h, :w], 0).astype(float)
        return image.reshape(h // block, block, w // block, block, 3).sum(axis=(1, 3))

    counts = arm.reshape(h // block, block, w // block, block).sum(axis=(1, 3))
    error = np.abs(means(picture) - means(frame)).sum(axis=2)
    return float(error[counts > 0].sum() / (3 * counts.sum()))


def _downgraded(frame: np.ndarray) -> np.ndarray:
    """The frame as Rich maps it on its own, pixel by pixel (what Textual does unasked)."""
    entries = {}
    out = np.empty_like(frame)
    for index in np.ndindex(frame.shape[:2]):
        key = tuple(int(v) for v in frame[index])
        if key not in entries:
            number = Color.from_rgb(*key).downgrade(ColorSystem.EIGHT_BIT).number
            entries[key] = EIGHT_BIT_PALETTE[number]
        out[index] = entries[key]
    return out


def test_the_frame_is_mapped_to_palette_colours_only(frame):
    mapped = Palette256().mapped(frame, BACKGROUND)
    palette = {tuple(c) for c in COLOURS.tolist()}
    assert {tuple(c) for c in mapped.reshape(-1, 3).tolist()} <= palette


def test_the_background_is_its_nearest_colour_all_over_not_black(frame):
    mapped = Palette256().mapped(frame, BACKGROUND)
    background = np.all(frame == BACKGROUND, axis=2)
    assert nearest(BACKGROUND) == 233  # #121212, where Rich makes it 16, pure black
    assert np.all(mapped[background] == COLOURS[233 - FIRST])


def test_dithering_keeps_the_shading_true_where_pixel_by_pixel_mapping_bands(frame):
    mapped = Palette256().mapped(frame, BACKGROUND)
    ours, rich = _block_error(mapped, frame), _block_error(_downgraded(frame), frame)
    assert ours < rich / 2  # measured 5.2, where Rich's is 12.2


def test_a_shaded_red_is_dithered_from_reds_only():
    # The muscle's colour from its shadow to its highlight, a row each.
    shades = np.linspace(0.45, 1.3, 40)[:, None, None]
    frame = np.clip(np.array([180, 72, 62]) * shades * np.ones((1, 16, 1)), 0, 255)
    frame = frame.astype(np.uint8)
    mapped = Palette256().mapped(frame, BACKGROUND)
    hue = lambda colours: np.degrees(np.arctan2(colours[..., 2], colours[..., 1]))
    true, shown = oklab(frame), oklab(mapped)
    assert np.hypot(shown[..., 1], shown[..., 2]).min() > 0.04  # no grey among them
    assert np.abs((hue(shown) - hue(true) + 180) % 360 - 180).max() < 25


def test_a_pixel_depends_on_its_own_colour_and_place_alone(frame):
    # Unlike error diffusion, a change in one corner leaves the rest of the picture as it was.
    changed = frame.copy()
    changed[:10, :10] = (200, 30, 30)
    before, after = (Palette256().mapped(picture, BACKGROUND) for picture in (frame, changed))
    assert np.array_equal(before[10:], after[10:]) and np.array_equal(before[:, 10:],
                                                                      after[:, 10:])


def test_a_grey_is_written_as_its_own_entry():
    # Rich would write 252 (208, 208, 208) as 251, and 59 (95, 95, 95) as 240.
    for number in (59, 252, FIRST, 255):
        r, g, b = COLOURS[number - FIRST].tolist()
        written = colour(r << 16 | g << 8 | b)
        assert (written.type, written.number) == (ColorType.EIGHT_BIT, number)


async def test_the_app_in_256_colours_shows_the_mapped_picture(biceps, monkeypatch, config):
    monkeypatch.setattr(textual.constants, "COLOR_SYSTEM", "256")
    async with biceps(size=(100, 30)) as session:
        viewport = session.app.screen.query_one(Viewport)
        width, height = viewport.size
        numbers = np.zeros((2 * height, width), dtype=int)
        for x, y, top, bottom in shown_cells(viewport):
            # The entries Textual writes: it downgrades whatever is not one already.
            numbers[2 * y: 2 * y + 2, x] = [colour.downgrade(ColorSystem.EIGHT_BIT).number
                                            for colour in (top, bottom)]
        shown = np.array(EIGHT_BIT_PALETTE._colors, dtype=np.uint8)[numbers]
        frame = SceneRenderer().render(Scene.of(config), width, 2 * height)
        assert np.all(numbers[np.all(frame == rgb(config.render.background), axis=2)] == 233)
        background, muscle = rgb(config.render.background), rgb(config.render.muscle_colour)
        assert blurred_difference(frame, shown, background) <= 0.025  # measured 0.0219
        assert off_hue_share(frame, shown, background, muscle) <= 0.02  # measured 0


async def test_real_pixels_are_not_mapped_onto_the_palette(monkeypatch, config):
    monkeypatch.setattr(textual.constants, "COLOR_SYSTEM", "256")

    class Frames(Corners):
        def encode(self, frame):
            self.frames = [*getattr(self, "frames", []), frame.copy()]
            return super().encode(frame)

    encoder = Frames()
    app = OneViewport(Scene.of(config).with_view(scale=2.0), encoder)
    async with app.run_test(size=(60, 20)) as pilot:
        await _shown(app, pilot)
    palette = {tuple(c) for c in COLOURS.tolist()}
    colours = {tuple(c) for c in encoder.frames[-1].reshape(-1, 3).tolist()}
    assert not colours <= palette  # an image carries every colour of the frame
