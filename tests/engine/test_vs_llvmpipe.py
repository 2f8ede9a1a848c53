"""The llvmpipe benchmark compares like with like: its OpenGL pictures are ours."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from biceps.engine.render import Renderer
from biceps.engine.transforms import Light, frame_camera, model_matrix, transform_points

BENCHMARK = Path(__file__).resolve().parents[2] / "benchmarks" / "vs_llvmpipe.py"


@pytest.fixture(scope="module")
def benchmark():
    spec = importlib.util.spec_from_file_location("vs_llvmpipe", BENCHMARK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def scene(benchmark):
    mesh, albedo = benchmark.arm_scene(5_000)
    return mesh, albedo, model_matrix(math.radians(-25.0), math.radians(10.0), 0.0)


@pytest.mark.parametrize("shading", ["gouraud", "phong"])
@pytest.mark.parametrize("framing", ["app", "close-up"])
def test_llvmpipe_draws_the_picture_we_draw(benchmark, scene, shading, framing):
    mesh, albedo, model = scene
    width, height, light = 160, 96, Light()
    renderer = Renderer(threads=1)
    world = transform_points(model, mesh.vertices)
    camera = (frame_camera(world.min(axis=0), world.max(axis=0), width / height)
              if framing == "app" else benchmark.close_up(renderer, scene, light, width, height))
    ours = renderer.render(mesh.vertices, mesh.normals, mesh.triangles, albedo, model, camera,
                           light, width, height, shading=shading,
                           background=benchmark.BACKGROUND).copy()
    gl = benchmark.Llvmpipe(mesh, albedo)
    try:
        theirs = gl.render(shading, model, camera, light, width, height)
    finally:
        gl.context.release()
    assert "llvmpipe" in gl.renderer_name
    drawn = benchmark.cover(ours)
    assert drawn > (0.3 if framing == "close-up" else 0.02)
    assert abs(benchmark.cover(theirs) - drawn) < 0.01
    assert benchmark.differ(ours, theirs) < 0.002
    # Colours agree to a level or two wherever both drew (float32 against float64, and
    # llvmpipe's 8-bit rounding).
    both = np.any(ours != benchmark.BACKGROUND, axis=2) & np.any(theirs != benchmark.BACKGROUND,
                                                                  axis=2)
    apart = np.abs(ours.astype(int) - theirs.astype(int)).max(axis=2)[both]
    assert np.mean(apart) < 1.0
