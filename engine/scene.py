"""What one picture shows: the arm, how it is viewed and lit, and how it is rendered.

The camera frames a sphere that holds the arm in every pose its joint allows, centred on a
fixed pivot, so contracting the muscle bends the arm in place instead of re-zooming, and
turning the model about that pivot never swings it out of view.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from biceps.engine import coldstart
from biceps.engine.arm import Arm
from biceps.engine.config import Config, rgb
from biceps.engine.mesh import Mesh, arm_parts
from biceps.engine.render import Renderer
from biceps.engine.settings import RenderSettings, View
from biceps.engine.skeleton import Skeleton
from biceps.engine.transforms import Camera, Light, frame_sphere, model_matrix


@dataclass(frozen=True)
class Scene:
    """Everything a frame depends on; immutable, so a render thread can hold one safely.

    Each setting checks its rules when it is made, so ``with_view(scale=-3)`` raises
    :class:`~engine.errors.SettingError` rather than making a scene that cannot be drawn
    or saved.
    """

    arm: Arm
    view: View
    light: Light
    render: RenderSettings

    @classmethod
    def of(cls, config: Config) -> Scene:
        return cls(config.arm, config.view, config.light, config.render)

    def with_view(self, **changes) -> Scene:
        return replace(self, view=replace(self.view, **changes))

    def with_light(self, **changes) -> Scene:
        return replace(self, light=replace(self.light, **changes))

    def with_render(self, **changes) -> Scene:
        return replace(self, render=replace(self.render, **changes))

    def with_arm(self, arm: Arm) -> Scene:
        return replace(self, arm=arm)


def scene_mesh(arm: Arm, segments: int, muscle_colour: str,
               bone_colour: str) -> tuple[Mesh, np.ndarray]:
    """The arm as one world-space mesh, and its per-vertex albedo (n, 3) float32 in [0, 1]."""
    parts = arm_parts(arm, segments)
    colours = {"muscle": _unit_rgb(muscle_colour)}
    albedo = [np.broadcast_to(colours.get(name, _unit_rgb(bone_colour)), (len(part.vertices), 3))
              for name, part in parts.items()]
    return Mesh.concatenate(list(parts.values())), np.concatenate(albedo).astype(np.float32)


def _unit_rgb(colour: str) -> np.ndarray:
    return np.array(rgb(colour), dtype=np.float32) / 255.0


@lru_cache(maxsize=16)
def reach(skeleton: Skeleton) -> tuple[np.ndarray, float]:
    """The centre (3,) and radius (cm) of a sphere holding the arm in every allowed pose."""
    flexions = np.linspace(skeleton.min_flexion, skeleton.max_flexion, 33)
    hands = [skeleton.pose(skeleton.length_at(f)).hand for f in flexions]
    top = max(skeleton.upper_arm, skeleton.origin_to_elbow)
    points = np.array([[0.0, top, 0.0], [0.0, 0.0, 0.0], *hands])
    centre = (points.min(axis=0) + points.max(axis=0)) / 2
    margin = 3.0  # the muscle's belly and the bones' radii stand out of the skeleton's lines
    return centre, float(np.linalg.norm(points - centre, axis=1).max()) + margin


def view_camera(scene: Scene, aspect: float) -> tuple[Camera, np.ndarray]:
    """The camera for ``scene`` at this width / height, and the model matrix (4, 4)."""
    centre, radius = reach(scene.arm.skeleton)
    view = scene.view
    camera = frame_sphere(centre, radius, aspect, view.fov, view.scale)
    model = model_matrix(
        np.radians(view.yaw), np.radians(view.pitch), np.radians(view.roll),
        view.scale, view.offset, pivot=centre,
    )  # fmt: skip
    return camera, model


class SceneRenderer:
    """Turns scenes into pictures, reusing its buffers and the last mesh between frames.

    Not thread-safe: give each thread its own.
    """

    def __init__(self) -> None:
        coldstart.wait_for_aside()  # load, rather than compile again, what a child compiles
        self._renderer = Renderer()
        self._mesh_key: tuple | None = None
        self._mesh: tuple[Mesh, np.ndarray] | None = None

    def render(self, scene: Scene, width: int, height: int) -> np.ndarray:
        """The picture of ``scene``: (height, width, 3) uint8, valid until the next call."""
        mesh, albedo = self._mesh_of(scene)
        camera, model = view_camera(scene, width / height)
        return self._renderer.render(
            mesh.vertices, mesh.normals, mesh.triangles, albedo, model, camera,
            scene.light, width, height, shading=scene.render.shading,
            ssaa=scene.render.ssaa, background=rgb(scene.render.background),
        )  # fmt: skip

    def _mesh_of(self, scene: Scene) -> tuple[Mesh, np.ndarray]:
        # Turning, moving and lighting leave the mesh as it was: rebuild it only when the
        # arm or its look changes.
        render = scene.render
        # The arm compares its muscle by identity (a new muscle is a new object), and the
        # key holds the arm, so the identity cannot be reused by another.
        key = (scene.arm, render.segments, render.muscle_colour, render.bone_colour)
        if key != self._mesh_key:
            self._mesh = scene_mesh(scene.arm, render.segments, render.muscle_colour,
                                    render.bone_colour)
            self._mesh_key = key
        return self._mesh
