"""The software renderer against Mesa's llvmpipe: the ratio of frame times, side by side.

    .venv/bin/pip install -e '.[bench]'   # moderngl; Mesa's EGL and llvmpipe from Debian
    .venv/bin/python benchmarks/vs_llvmpipe.py [--quick] [--budget S] [--threads N]

The scene is `render.arm_scene` (the arm at mid flexion, turned as the default view turns
it) at about 5k, 20k and 100k triangles, drawn at 200x120 to 3840x2160 in two framings:
"app", the whole arm framed as the app frames it, and "close-up", the belly so near that it
covers about 37 % of the pixels (the camera's distance found by bisection on our own
picture). Each is drawn with Gouraud and with Phong shading, by this project's `Renderer`
and by llvmpipe through moderngl with shaders that compute the same lighting (Lambert plus
ambient at the vertices; per pixel, Blinn-Phong with the same threshold), from the same
model, view and projection matrices, into a framebuffer read back with glReadPixels.

Frames of the two alternate (the order swapped every round) so that both see the same load
on a busy machine; each cell is the ratio of the medians, ours / llvmpipe's, below 1 being
faster. llvmpipe runs with LP_NUM_THREADS threads (2 unless set), ours with --threads (as
many as the machine has, unless given). "differ" is the share of the pixels drawn by either
where some channel differs by more than `TOLERANCE` levels: the two rasterizers' coverage
rules and rounding disagree on a few edge pixels. The last line is
``worst ratio R (the cell)``, for scripts.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("LP_NUM_THREADS", "2")  # before Mesa loads

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from render import MUSCLE, SIZES, TRIANGLES, arm_scene  # noqa: E402

from biceps.engine.raster import highlight_threshold  # noqa: E402
from biceps.engine.render import Renderer  # noqa: E402
from biceps.engine.transforms import (Camera, Light, frame_camera, model_matrix,  # noqa: E402
                                      normal_matrix, transform_points)

BACKGROUND = (18, 22, 28)
TOLERANCE = 24
"""Colour levels by which a pixel of the two pictures may differ and still count as the same
(that of the golden images' test, ``tests/engine/test_golden.py``)."""
CLOSE_UP_COVER = 0.37

VERTEX_SHADER = """
#version 330
uniform mat4 model;
uniform mat3 normal_matrix;
uniform mat4 view_projection;
uniform vec3 light;
uniform float ambient;
uniform float diffuse;
in vec3 in_position;
in vec3 in_normal;
in vec3 in_albedo;
out vec3 position;
out vec3 normal;
out vec3 albedo;
out vec3 colour;
void main() {
    vec4 world = model * vec4(in_position, 1.0);
    position = world.xyz;
    normal = normalize(normal_matrix * in_normal);
    albedo = in_albedo;
    vec3 to_light = light - position;
    float lambert = max(dot(normal, to_light), 0.0) / length(to_light);
    colour = clamp(in_albedo * (ambient + diffuse * lambert), 0.0, 1.0);
    gl_Position = view_projection * world;
}
"""

GOURAUD_SHADER = """
#version 330
in vec3 colour;
out vec4 fragment;
void main() { fragment = vec4(colour, 1.0); }
"""

PHONG_SHADER = """
#version 330
uniform vec3 light;
uniform vec3 eye;
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform float shininess;
uniform float threshold;
in vec3 position;
in vec3 normal;
in vec3 albedo;
out vec4 fragment;
void main() {
    vec3 n = normalize(normal);
    vec3 l = normalize(light - position);
    vec3 v = normalize(eye - position);
    float n_dot_l = dot(n, l);
    float intensity = ambient;
    float highlight = 0.0;
    if (n_dot_l > 0.0) {
        intensity += diffuse * n_dot_l;
        float n_dot_h = dot(n, normalize(l + v));
        if (n_dot_h > threshold) highlight = specular * pow(n_dot_h, shininess);
    }
    fragment = vec4(albedo * intensity + highlight, 1.0);
}
"""


class Llvmpipe:
    """The same mesh drawn by Mesa's llvmpipe through moderngl, headless (EGL)."""

    def __init__(self, mesh, albedo):
        import moderngl

        self.moderngl = moderngl
        self.context = moderngl.create_standalone_context(backend="egl")
        self.renderer_name = self.context.info["GL_RENDERER"]
        data = np.hstack([mesh.vertices, mesh.normals, albedo]).astype("f4")
        self.buffer = self.context.buffer(data.tobytes())
        self.indices = self.context.buffer(np.ascontiguousarray(mesh.triangles, "i4").tobytes())
        self.programs = {
            name: self.context.program(vertex_shader=VERTEX_SHADER, fragment_shader=fragment)
            for name, fragment in (("gouraud", GOURAUD_SHADER), ("phong", PHONG_SHADER))
        }
        self.arrays = {
            name: self.context.vertex_array(
                program, [(self.buffer, "3f 3f 3f", "in_position", "in_normal", "in_albedo")],
                index_buffer=self.indices, index_element_size=4)
            for name, program in self.programs.items()
        }
        self.size = None

    def resize(self, width, height):
        if self.size == (width, height):
            return
        if self.size is not None:
            self.framebuffer.release()
        self.framebuffer = self.context.simple_framebuffer((width, height), components=4)
        self.size = (width, height)

    def render(self, shading, model, camera: Camera, light: Light, width, height):
        """The picture, (height, width, 3) uint8, top row first."""
        context = self.context
        self.resize(width, height)
        self.framebuffer.use()
        context.enable(self.moderngl.DEPTH_TEST | self.moderngl.CULL_FACE)
        self.framebuffer.clear(*(c / 255.0 for c in BACKGROUND), 1.0, depth=1.0)
        program = self.programs[shading]
        values = {
            "model": model.T, "normal_matrix": normal_matrix(model).T,
            "view_projection": (camera.projection_matrix(width / height)
                                @ camera.view_matrix()).T,
            "light": light.position, "eye": camera.eye, "ambient": light.ambient,
            "diffuse": light.diffuse, "specular": light.specular,
            "shininess": light.shininess,
            "threshold": highlight_threshold(light.specular, light.shininess),
        }
        for name, value in values.items():
            if name in program:
                program[name].write(np.asarray(value, "f4").tobytes())
        self.arrays[shading].render(self.moderngl.TRIANGLES)
        pixels = self.framebuffer.read(components=3, alignment=1)
        return np.frombuffer(pixels, np.uint8).reshape(height, width, 3)[::-1]


def cover(picture) -> float:
    """The share of pixels not the background."""
    return float(np.mean(np.any(picture != BACKGROUND, axis=2)))


def close_up(renderer, common, light, width, height) -> Camera:
    """A camera on the belly, near enough that the arm covers `CLOSE_UP_COVER` of the
    pixels: the belly framed as `render.views` frames it, then the eye moved along its line
    of sight, the distance found by bisection on a picture a quarter the size."""
    mesh, albedo, model = common
    world = transform_points(model, mesh.vertices)
    muscle = world[np.all(albedo == np.float32(MUSCLE), axis=1)]
    middle = np.median(muscle[:, 1])
    belly = muscle[np.abs(muscle[:, 1] - middle) < np.ptp(muscle[:, 1]) / 8.0]
    framed = frame_camera(belly.min(axis=0), belly.max(axis=0), width / height)
    eye, target = np.array(framed.eye), np.array(framed.target)
    small = (max(width // 4, 50), max(height // 4, 30))

    def at(factor: float) -> Camera:
        return Camera(eye=tuple(target + factor * (eye - target)), target=framed.target,
                      fov_y_deg=framed.fov_y_deg, near=framed.near * factor, far=framed.far)

    low, high = 0.5, 4.0  # nearer covers more
    for _ in range(20):
        middle_factor = (low + high) / 2.0
        picture = renderer.render(mesh.vertices, mesh.normals, mesh.triangles, albedo, model,
                                  at(middle_factor), light, *small, background=BACKGROUND)
        if cover(picture) > CLOSE_UP_COVER:
            low = middle_factor
        else:
            high = middle_factor
    return at((low + high) / 2.0)


def interleaved(ours, theirs, budget: float, least: int = 5) -> tuple[float, float]:
    """Median seconds of ``ours()`` and ``theirs()``, called in turn, the order swapped
    every round, after one warm-up call each, over at least ``least`` rounds and about
    ``budget`` seconds."""
    ours(), theirs()
    times = ([], [])
    start = time.perf_counter()
    rounds = 0
    while rounds < least or time.perf_counter() - start < budget:
        pair = (ours, theirs) if rounds % 2 == 0 else (theirs, ours)
        for action in pair:
            t = time.perf_counter()
            action()
            times[0 if action is ours else 1].append(time.perf_counter() - t)
        rounds += 1
        if rounds >= 100:
            break
    return statistics.median(times[0]), statistics.median(times[1])


def differ(ours, theirs) -> float:
    """The share of the pixels drawn in either picture that differ by more than
    `TOLERANCE` levels in some channel."""
    drawn = np.any(ours != BACKGROUND, axis=2) | np.any(theirs != BACKGROUND, axis=2)
    apart = np.abs(ours.astype(np.int16) - theirs.astype(np.int16)).max(axis=2) > TOLERANCE
    return float(np.count_nonzero(apart & drawn) / max(np.count_nonzero(drawn), 1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="shorter runs, no 4K")
    parser.add_argument("--budget", type=float, default=None,
                        help="seconds of frames per cell (default 0.6, 0.2 with --quick)")
    parser.add_argument("--threads", type=int, default=None,
                        help="our rasterizer's threads (default: every core)")
    args = parser.parse_args()
    sizes = SIZES[:3] if args.quick else SIZES
    budget = args.budget if args.budget is not None else (0.2 if args.quick else 0.6)
    light = Light()
    model = model_matrix(math.radians(-25.0), math.radians(10.0), 0.0)
    renderer = Renderer(threads=args.threads)
    columns = [(framing, shading) for shading in ("gouraud", "phong")
               for framing in ("app", "close-up")]
    worst = (0.0, "")
    load = os.getloadavg()
    details = []
    for target in TRIANGLES:
        mesh, albedo = arm_scene(target)
        gl = Llvmpipe(mesh, albedo)
        if target == TRIANGLES[0]:
            print(f"llvmpipe: {gl.renderer_name}, LP_NUM_THREADS={os.environ['LP_NUM_THREADS']};"
                  f" ours: {renderer.threads} thread(s); load average {load[0]:.2f}"
                  f" on {os.cpu_count()} cores")
            print("ratio ours / llvmpipe, medians of interleaved frames (below 1 is faster)")
        print(f"\n{len(mesh.triangles):>7} triangles" + "".join(
            f"{shading.capitalize() + ', ' + framing:>20}" for framing, shading in columns))
        common = (mesh.vertices, mesh.normals, mesh.triangles, albedo, model)
        world = transform_points(model, mesh.vertices)
        for width, height in sizes:
            cameras = {"app": frame_camera(world.min(axis=0), world.max(axis=0), width / height),
                       "close-up": close_up(renderer, (mesh, albedo, model), light, width,
                                            height)}
            ratios = []
            for framing, shading in columns:
                camera = cameras[framing]

                def ours():
                    return renderer.render(*common, camera, light, width, height,
                                           shading=shading, background=BACKGROUND)

                def theirs():
                    return gl.render(shading, model, camera, light, width, height)

                ours_s, theirs_s = interleaved(ours, theirs, budget)
                mine, other = ours().copy(), theirs()
                ratio = ours_s / theirs_s
                cell = f"{len(mesh.triangles)} triangles, {width}x{height}, {shading}, {framing}"
                worst = max(worst, (ratio, cell))
                ratios.append(f"{ratio:.2f}")
                details.append(f"{cell:>44}: {1e3 * ours_s:8.2f} ms {1e3 * theirs_s:8.2f} ms"
                               f"  cover {100 * cover(mine):4.1f} %  differ"
                               f" {100 * differ(mine, other):.4f} %")
            print(f"{f'{width}x{height}':>17}" + "".join(f"{ratio:>20}" for ratio in ratios))
        gl.context.release()
    print(f"\n{'cell':>44}      ours  llvmpipe  (cover: pixels drawn; differ: drawn pixels"
          f" > {TOLERANCE} levels apart)")
    print("\n".join(details))
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")
    print(f"worst ratio {worst[0]:.2f} ({worst[1]})")


if __name__ == "__main__":
    main()
