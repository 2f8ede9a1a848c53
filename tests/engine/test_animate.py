"""The flex cycle's frames: which poses, in which order, each rendered once."""

import numpy as np
import pytest

from biceps.engine.animate import FlexCycle, check_cycle, render_cycle
from biceps.engine.config import BUNDLED, DEFAULT_CONFIG, load_config, rgb
from biceps.engine.errors import BicepsError
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer

SCENE = Scene.of(load_config(DEFAULT_CONFIG))


def test_a_loop_goes_from_the_first_angle_to_the_last_in_even_steps():
    cycle = FlexCycle(0.0, 100.0, 5, bounce=False)
    assert cycle.flexions().tolist() == [0.0, 25.0, 50.0, 75.0, 100.0]


def test_a_bounce_goes_out_and_back_through_the_same_poses():
    cycle = FlexCycle(0.0, 90.0, 6, bounce=True)
    assert cycle.poses().tolist() == [0.0, 30.0, 60.0, 90.0]
    assert cycle.flexions().tolist() == [0.0, 30.0, 60.0, 90.0, 60.0, 30.0]


@pytest.mark.parametrize(("cycle", "message"), [
    (dict(start=0.0, end=90.0, frames=7, bounce=True), "needs an even number of frames, not 7"),
    (dict(start=0.0, end=90.0, frames=1, bounce=False), "at least 2 frames"),
    (dict(start=45.0, end=45.0, frames=10, bounce=False), "nothing would move"),
])
def test_a_cycle_that_cannot_be_played_is_refused(cycle, message):
    with pytest.raises(BicepsError, match=message):
        FlexCycle(**cycle)


def test_each_pose_is_rendered_once_and_a_bounce_reuses_the_pictures(monkeypatch):
    rendered = []

    class Counting(SceneRenderer):
        def render(self, scene, width, height, framed=None):
            rendered.append(scene.arm.flexion)
            return super().render(scene, width, height, framed)

    monkeypatch.setattr("biceps.engine.animate.SceneRenderer", Counting)
    steps = []
    frames = render_cycle(SCENE, FlexCycle(0.0, 90.0, 6), 32, 18,
                          progress=lambda done, total: steps.append((done, total)))
    assert rendered == pytest.approx([0.0, 30.0, 60.0, 90.0])
    assert steps == [(1, 4), (2, 4), (3, 4), (4, 4)]
    assert frames[1] is frames[5] and frames[2] is frames[4]
    assert len({id(frame) for frame in frames}) == 4
    assert not np.array_equal(frames[0], frames[3])  # the arm moved
    assert frames[0].shape == (18, 32, 3) and frames[0].dtype == np.uint8


def test_a_cycle_past_the_joint_is_refused_before_anything_is_rendered(monkeypatch):
    monkeypatch.setattr("biceps.engine.animate.SceneRenderer", None)  # would fail if used
    with pytest.raises(BicepsError, match="outside the joint's range"):
        render_cycle(SCENE, FlexCycle(0.0, 150.0, 4), 32, 18)


def test_a_cycle_too_big_for_memory_is_refused():
    with pytest.raises(BicepsError, match="ask for fewer frames or a smaller size"):
        check_cycle(SCENE, FlexCycle(0.0, 90.0, 2000, bounce=False), 8192, 8192)


@pytest.mark.parametrize("model", ["biceps", "elbow"])
def test_the_whole_cycle_is_seen_from_one_camera_with_the_whole_arm_in_every_frame(model):
    # Framed pose by pose, the shoulder drifted and the arm grew and shrank: the top 15 %
    # of the straight and the bent arm's frames differed by 9.9 levels on average.
    config = load_config(BUNDLED / f"{model}.toml")
    frames = render_cycle(Scene.of(config), FlexCycle(0.0, 130.0, 60), 320, 180)
    straight, bent = frames[0].astype(int), frames[30].astype(int)
    top = round(0.15 * 180)
    assert np.abs(straight[:top] - bent[:top]).mean() <= 2.0
    background = np.array(rgb(config.render.background))
    for frame in frames:
        drawn = np.any(frame != background, axis=2)
        assert drawn.any()
        assert not (drawn[0].any() or drawn[-1].any() or drawn[:, 0].any() or drawn[:, -1].any())
