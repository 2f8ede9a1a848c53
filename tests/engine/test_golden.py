"""Golden images: the default model at three poses, compared as decoded pixels.

Regenerate after an intended change of the picture, then look at every image:
    BICEPS_UPDATE_GOLDEN=1 .venv/bin/pytest tests/engine/test_golden.py
"""

import os
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from biceps.engine.config import load_config, rgb
from biceps.engine.export import write_png
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.engine.config import DEFAULT_CONFIG
from pictures import pieces

GOLDEN = Path(__file__).resolve().parent / "golden"
SIZE = (320, 180)


def default_view(scene: Scene) -> Scene:
    return scene


def flexed_phong(scene: Scene) -> Scene:
    return (scene.with_arm(scene.arm.at_flexion(120.0)).with_view(yaw=60.0, pitch=15.0)
            .with_render(shading="phong", ssaa=2))


def straight_from_the_left(scene: Scene) -> Scene:
    return (scene.with_arm(scene.arm.at_flexion(0.0)).with_view(yaw=-70.0, pitch=-20.0, scale=1.3)
            .with_light(position=(-80.0, 40.0, 60.0)))


POSES = [default_view, flexed_phong, straight_from_the_left]


@pytest.mark.parametrize("pose", POSES, ids=lambda pose: pose.__name__)
def test_picture_matches_its_golden_image(pose):
    scene = pose(Scene.of(load_config(DEFAULT_CONFIG)))
    picture = SceneRenderer().render(scene, *SIZE)
    path = GOLDEN / f"{pose.__name__}.png"
    if os.environ.get("BICEPS_UPDATE_GOLDEN"):
        write_png(path, picture)
    with Image.open(path) as golden:
        expected = np.asarray(golden.convert("RGB"))
    difference = np.abs(picture.astype(np.int16) - expected.astype(np.int16)).max(axis=2)
    # Floating point may round a few edge pixels or shades differently on another CPU; a
    # changed picture moves far more than this.
    assert difference.mean() < 0.5
    assert np.mean(difference > 24) < 0.002


@pytest.mark.parametrize(("size", "scale"), [((62, 36), 1.0), ((78, 44), 0.7), ((46, 44), 0.5),
                                           ((100, 56), 0.7)])
def test_a_small_picture_keeps_the_thin_bones_whole(size, scale):
    # 78x44 and 46x44 are the picture at 80x24 without the side panel and with it; a
    # scale below 1 is the arm zoomed out, its bones thinner still. Once a pixel, these
    # fall into 2 to 6 pieces.
    config = load_config(DEFAULT_CONFIG)
    picture = SceneRenderer().render(Scene.of(config).with_view(scale=scale), *size)
    assert pieces(picture, rgb(config.render.background)) == 1
