"""In the app the arm fills the picture too, at any terminal size, and zoom keeps its middle."""

import numpy as np
import pytest

from biceps.engine.config import rgb
from biceps.tui.widgets.viewport import Viewport
from framing import assert_fills_the_view, box, strips_mask


def picture(session) -> np.ndarray:
    """The arm's pixels in the picture on screen: (2 rows, columns) bool."""
    viewport = session.app.screen.query_one(Viewport)
    background = rgb(session.app.scene.render.background)
    return strips_mask([viewport.render_line(y) for y in range(viewport.size.height)],
                       background)


@pytest.mark.parametrize("size", [(80, 24), (120, 36)])
@pytest.mark.parametrize("flexion", [0.0, 60.0, 130.0])
async def test_the_arm_fills_the_picture_in_every_pose(biceps, size, flexion):
    async with biceps(size=size) as session:
        app = session.app
        app.scene = app.scene.with_arm(app.scene.arm.at_flexion(flexion))
        await session.settle()
        assert_fills_the_view(picture(session))


async def test_three_zooms_keep_the_middle_of_the_arm_in_view(biceps):
    async with biceps(size=(120, 36)) as session:
        before = picture(session)
        await session.pilot.press("plus", "plus", "plus")
        await session.settle()
        after = picture(session)
        height, width = after.shape
        top, bottom, left, right = box(before)
        # Scaled by 1.1^3 about the picture's centre, the middle third of the arm's height
        # still lies in the picture, and the arm runs through every row of it.
        zoom = 1.1**3
        middle = [round(height / 2 + zoom * (row - height / 2))
                  for row in (top + (bottom - top) / 3, bottom - (bottom - top) / 3)]
        assert 0 < middle[0] < middle[1] < height - 1
        assert after[middle[0]:middle[1] + 1].any(axis=1).all()
        assert after[:, width // 3: 2 * width // 3].any()


async def test_fit_brings_the_whole_arm_back_keeping_the_turn(biceps):
    async with biceps(size=(100, 30)) as session:
        await session.pilot.press("plus", "plus", "plus", "plus", *"aaaaa", "right", "f")
        view = session.app.scene.view
        assert (view.scale, view.offset, view.yaw) == (1.0, (0.0, 0.0, 0.0), -20.0)
        await session.settle()
        assert_fills_the_view(picture(session))
