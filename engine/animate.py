"""The flex cycle as frames: the elbow swept between two angles, each pose rendered once,
all from one camera that fits every pose.

A cycle of ``frames`` frames either plays from one angle to the other and starts again
(``loop``), or goes there and comes back (``bounce``). A bounce shows each pose between the
ends on the way out and again on the way back: those frames are the same pictures, rendered
once. So a bounce has an even number of frames: an odd one would show a pose twice in a
row, and the encoders merge such frames into one, leaving fewer than were asked for.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from biceps.engine.cost import check_frames, check_picture
from biceps.engine.errors import BicepsError
from biceps.engine.movie import Progress
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer, supersampling


@dataclass(frozen=True)
class FlexCycle:
    """``frames`` frames between ``start`` and ``end`` degrees of flexion."""

    start: float
    end: float
    frames: int
    bounce: bool = True

    def __post_init__(self) -> None:
        if self.frames < 2:
            raise BicepsError(f"a cycle needs at least 2 frames, not {self.frames}")
        if self.bounce and self.frames % 2:
            raise BicepsError(
                f"a bounce goes out and back through the same poses, so it needs an even "
                f"number of frames, not {self.frames}"
            )
        if self.start == self.end:
            raise BicepsError(f"the cycle starts and ends at {self.start:g} degrees: "
                              "nothing would move")

    def poses(self) -> np.ndarray:
        """The distinct flexions (degrees) to render, from ``start`` to ``end``: (k,) float64.

        A bounce of ``2k - 2`` frames goes out in ``k`` poses and back through the ``k - 2``
        between the ends.
        """
        count = self.frames // 2 + 1 if self.bounce else self.frames
        return np.linspace(self.start, self.end, count)

    def order(self) -> list[int]:
        """Which pose each frame of the cycle shows, in playing order."""
        out = list(range(len(self.poses())))
        return out + out[-2:0:-1] if self.bounce else out

    def flexions(self) -> np.ndarray:
        """The flexion (degrees) of each frame in playing order: (frames,) float64."""
        return self.poses()[self.order()]


def check_cycle(scene: Scene, cycle: FlexCycle, width: int, height: int) -> None:
    """Raise :class:`BicepsError` if the arm cannot reach the cycle's ends or its pictures
    would not fit in memory: before any work, since rendering a cycle takes a while."""
    for flexion in (cycle.start, cycle.end):  # the poses between lie within them
        scene.arm.at_flexion(flexion)
    check_picture(width, height, supersampling(scene.render, height))
    check_frames(len(cycle.poses()), width, height)


def render_cycle(scene: Scene, cycle: FlexCycle, width: int, height: int,
                 progress: Progress | None = None) -> list[np.ndarray]:
    """The cycle's frames in playing order, each (height, width, 3) uint8; a frame that
    shows the same pose as another is the same array.

    Refuses (see :func:`check_cycle`) before rendering anything.
    """
    check_cycle(scene, cycle, width, height)
    scenes = [scene.with_arm(scene.arm.at_flexion(float(flexion))) for flexion in cycle.poses()]
    with SceneRenderer() as renderer:
        # One camera for the whole cycle, fitted to every pose: framed pose by pose, the
        # shoulder would drift and the arm grow and shrink as the forearm swings.
        framed = np.concatenate([renderer.outline(posed) for posed in scenes])
        pictures = []
        for posed in scenes:
            pictures.append(renderer.render(posed, width, height, framed).copy())
            if progress is not None:
                progress(len(pictures), len(scenes))
    return [pictures[index] for index in cycle.order()]
