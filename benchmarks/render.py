"""Frame times of the software renderer: median milliseconds per frame, one thread.

    .venv/bin/python benchmarks/render.py [--quick]

The scene is a fixed arm (a muscle, two rods and a ball for the elbow, from the meshes of
``engine/mesh.py``, as the app drew it before it had bones; fixed so that the figures of
one version compare with another's) at mid flexion, turned as the default view turns it
(yaw -25, pitch 10 degrees) and tessellated to about 5k, 20k and 100k triangles, seen two
ways: "arm" frames the whole arm, as the app
does, and the thin arm then covers a few percent of the picture; "belly" frames the middle
of the muscle, which then covers about 30 % (a fill-rate test). Each row gives the share of
pixels drawn in both views. The baselines come first, measured in the same run (clearing
the whole buffers as the renderer does after a frame drawn on every pixel, and with numpy's
plain fill), so that ratios stay meaningful on a noisy machine. One thread (``Renderer(threads=1)``), so that the figures of one version
compare with another's; benchmarks/vs_llvmpipe.py measures every core.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from biceps.engine.mesh import (Mesh, cylinder_mesh, muscle_mesh,  # noqa: E402
                               sphere_mesh)
from biceps.engine.raster import clear_drawn  # noqa: E402
from biceps.engine.render import Renderer  # noqa: E402
from biceps.engine.transforms import Light, frame_camera, model_matrix, transform_points  # noqa: E402

SIZES = [(200, 120), (640, 360), (1920, 1080), (3840, 2160)]
TRIANGLES = [5_000, 20_000, 100_000]
BICEPS = [0.35, 0.40, 0.60, 1.00, 1.45, 1.80, 2.00, 2.08, 2.02, 1.85, 1.55, 1.10, 0.65, 0.42, 0.35]
MUSCLE, BONE = (0.706, 0.282, 0.243), (0.890, 0.851, 0.753)


def arm_scene(target: int) -> tuple[Mesh, np.ndarray]:
    """The arm with about ``target`` triangles, and its albedo (n, 3) float32."""
    length = 33.0
    # The muscle from 30.2 cm up the humerus to 5.4 cm down the forearm, 33 cm long: the
    # elbow's interior angle is then arccos((30.2^2 + 5.4^2 - 33^2) / (2 30.2 5.4)).
    angle = math.acos((30.2**2 + 5.4**2 - length**2) / (2 * 30.2 * 5.4))
    forearm = np.array([math.sin(angle), math.cos(angle), 0.0])
    origin, elbow = np.array([0.0, 30.2, 0.0]), np.zeros(3)
    for segments in range(8, 1024, 2):
        # As many muscle nodes as make its facets roughly square.
        nodes = max(len(BICEPS), round(segments * length / (2 * math.pi * 1.6)))
        radii = np.interp(np.linspace(0, 1, nodes), np.linspace(0, 1, len(BICEPS)), BICEPS)
        parts = {
            "muscle": muscle_mesh(radii, length, origin, 5.4 * forearm, segments),
            "humerus": cylinder_mesh(elbow, origin, 1.0, segments),
            "forearm": cylinder_mesh(elbow, 25.4 * forearm, 0.8, segments),
            "elbow": sphere_mesh(elbow, 1.4, segments),
        }
        if sum(len(part.triangles) for part in parts.values()) >= target:
            break
    albedo = np.concatenate([
        np.tile(np.float32(MUSCLE if name == "muscle" else BONE), (len(part.vertices), 1))
        for name, part in parts.items()
    ])
    return Mesh.concatenate(parts.values()), albedo


def median_ms(action, budget: float, warmup: int = 2, least: int = 5) -> float:
    """Median wall time of ``action()`` in ms, after ``warmup`` calls, over at least
    ``least`` runs and about ``budget`` seconds."""
    for _ in range(warmup):
        action()
    times = []
    start = time.perf_counter()
    while len(times) < least or time.perf_counter() - start < budget:
        t = time.perf_counter()
        action()
        times.append(time.perf_counter() - t)
        if len(times) >= 200:
            break
    return 1e3 * statistics.median(times)


def views(mesh: Mesh, albedo: np.ndarray, model: np.ndarray, aspect: float) -> dict:
    """Two cameras: "arm" frames the whole arm (the app's default view); "belly" frames the
    middle quarter of the muscle, so the picture is mostly muscle (a fill-rate test)."""
    world = transform_points(model, mesh.vertices)
    muscle = world[np.all(albedo == np.float32(MUSCLE), axis=1)]
    middle = np.median(muscle[:, 1])
    reach = np.ptp(muscle[:, 1]) / 8.0
    belly = muscle[np.abs(muscle[:, 1] - middle) < reach]
    return {
        "arm": frame_camera(world.min(axis=0), world.max(axis=0), aspect),
        "belly": frame_camera(belly.min(axis=0), belly.max(axis=0), aspect),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="shorter runs, no 4K")
    args = parser.parse_args()
    sizes = SIZES[:3] if args.quick else SIZES
    budget = 0.3 if args.quick else 1.0
    light = Light()
    model = model_matrix(math.radians(-25.0), math.radians(10.0), 0.0)
    renderer = Renderer(threads=1)

    print("baselines (ms)")
    print(f"{'size':>11}{'clear':>9}{'numpy fills':>13}")
    for width, height in sizes:
        colour = np.empty((height, width, 3), np.uint8)
        depth = np.empty((height, width), np.float32)
        spans = np.empty((4, height), np.int64)
        background = [np.uint8(channel) for channel in (18, 22, 28)]

        def clear_all():  # as the renderer clears a frame after one drawn on every pixel
            spans[2], spans[3] = 0, width
            clear_drawn(colour.reshape(-1), depth.reshape(-1), width, 0, height, spans,
                        *background)

        cleared = median_ms(clear_all, budget)
        fills = median_ms(lambda: (colour.fill(18), depth.fill(0.0)), budget)
        print(f"{width:>6}x{height:<4}{cleared:>9.3f}{fills:>13.3f}")

    columns = [("arm", "gouraud", 1), ("belly", "gouraud", 1), ("belly", "phong", 1),
               ("belly", "gouraud", 2)]
    print("\nmedian ms per frame; cover: the share of pixels drawn, arm / belly view")
    print(f"{'triangles':>9}{'size':>11}{'cover':>9}" + "".join(
        f"{view + ' ' + shading + (f' x{ssaa}' if ssaa > 1 else ''):>18}"
        for view, shading, ssaa in columns))
    for target in TRIANGLES:
        mesh, albedo = arm_scene(target)
        for width, height in sizes:
            cameras = views(mesh, albedo, model, width / height)
            common = (mesh.vertices, mesh.normals, mesh.triangles, albedo, model)
            cover = []
            for view in ("arm", "belly"):
                counts = renderer.render(*common, cameras[view], light, width, height,
                                         shading="overdraw")[..., 0]
                cover.append(f"{100 * np.count_nonzero(counts) / counts.size:.0f}")
            cells = []
            for view, shading, ssaa in columns:
                if ssaa > 1 and width * height > 1920 * 1080:
                    cells.append("-")
                    continue
                ms = median_ms(lambda: renderer.render(
                    *common, cameras[view], light, width, height, shading=shading, ssaa=ssaa,
                    background=(18, 22, 28)), budget)
                cells.append(f"{ms:.3f}")
            print(f"{len(mesh.triangles):>9}{f'{width}x{height}':>11}{'/'.join(cover) + '%':>9}"
                  + "".join(f"{cell:>18}" for cell in cells))


if __name__ == "__main__":
    main()
