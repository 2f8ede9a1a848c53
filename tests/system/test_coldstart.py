"""A cold start: the kernels compiled ahead of the first frame, in child processes."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from biceps.engine import coldstart
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer

ROOT = Path(__file__).resolve().parents[2]

# In a fresh interpreter, so that no kernel has a version from elsewhere: prepare, then
# render, and print the versions the frame had to add (none, if prepare made the right ones).
ADDED_BY_THE_FRAME = """
import json, pkgutil, sys
from importlib import import_module
from numba.core.registry import CPUDispatcher
from biceps.engine import raster
from biceps.engine.config import load_config
from biceps.engine.render import Renderer
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer

modules = [import_module(f"{raster.__name__}.{module.name}")
           for module in pkgutil.iter_modules(raster.__path__)]
kernels = {name: kernel for module in modules for name, kernel in vars(module).items()
           if isinstance(kernel, CPUDispatcher)}
added = {}
for shading, ssaa in (("gouraud", 1), ("phong", 1), ("overdraw", 1), ("gouraud", 2)):
    Renderer().prepare(shading, ssaa)
    before = {name: set(kernel.signatures) for name, kernel in kernels.items()}
    scene = Scene.of(load_config(sys.argv[1])).with_render(shading=shading, ssaa=ssaa)
    SceneRenderer().render(scene, 64, 128)  # taller than a small picture, drawn supersampled
    added[f"{shading} x{ssaa}"] = sorted(name for name, kernel in kernels.items()
                                         if set(kernel.signatures) != before[name])
print(json.dumps(added))
"""


def test_prepare_makes_the_very_kernels_a_frame_runs():
    process = subprocess.run([sys.executable, "-c", ADDED_BY_THE_FRAME, str(DEFAULT_CONFIG)],
                             capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert process.returncode == 0, process.stderr
    assert json.loads(process.stdout) == {"gouraud x1": [], "phong x1": [], "overdraw x1": [],
                                          "gouraud x2": []}


@pytest.mark.skipif(coldstart._cores() < 2, reason="the second process needs a second core")
def test_on_a_cold_cache_the_rasterizer_comes_from_the_second_process(tmp_path):
    out = tmp_path / "arm.png"
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache"),
                   "NUMBA_DEBUG_CACHE": "1"}
    process = subprocess.run(
        [sys.executable, "-m", "biceps.cli", "snapshot", str(DEFAULT_CONFIG), "-o", str(out),
         "--size", "96x54"],
        capture_output=True, text=True, cwd=ROOT, env=environment, timeout=300,
    )  # fmt: skip
    assert process.returncode == 0, process.stderr
    # The child saved the rasterizer, and the command's own process loaded it from there
    # instead of compiling it too.
    log = process.stdout.splitlines()
    assert any("data saved" in line and "rasterize_gouraud" in line for line in log)
    assert any("data loaded" in line and "rasterize_gouraud" in line for line in log)
    expected = SceneRenderer().render(Scene.of(load_config(DEFAULT_CONFIG)), 96, 54)
    np.testing.assert_array_equal(np.asarray(Image.open(out)), expected)


# A snapshot's start on an empty cache: what its frame compiles after prepare_kernels.
SNAPSHOT_FIRST_RUN = """
import json, sys
from numba.core import event
from biceps.engine.coldstart import prepare_kernels
from biceps.engine.config import load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer, supersampling

scene = Scene.of(load_config(sys.argv[1]))
prepare_kernels(scene.render.shading, supersampling(scene.render, 54))
with event.install_recorder("numba:compile") as recorder:
    SceneRenderer().render(scene, 96, 54)
print(json.dumps(sorted({e.data["dispatcher"].py_func.__name__ for _, e in recorder.buffer})))
"""


@pytest.mark.skipif(coldstart._cores() < 2, reason="the second process needs a second core")
def test_on_a_cold_cache_a_snapshot_frame_compiles_nothing_after_prepare_kernels(tmp_path):
    assert _printed_on_a_cold_cache(SNAPSHOT_FIRST_RUN, tmp_path) == []


# The app's start on an empty cache (biceps/cli.py, tui/ahead.py), without Textual: the
# children compile, this process compiles the probe; the render thread waits for them; then
# the first frame, and the output minimizer once ready, find every kernel made. Prints what
# numba compiled here in each step.
APP_FIRST_RUN = """
import json, sys
from numba.core import event
from biceps.engine import coldstart
from biceps.engine.config import load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.tui import ahead
from biceps.tui.halfblocks import HalfBlocks
from biceps.tui.sgr import minimized

def compiled_by(step):
    with event.install_recorder("numba:compile") as recorder:
        step()
    return sorted({e.data["dispatcher"].py_func.__name__ for _, e in recorder.buffer})

config, encoder, asides = load_config(sys.argv[1]), HalfBlocks(), coldstart.Asides()
asides.start_rasterizer(config.render.shading)
ahead_ = compiled_by(lambda: ahead.compile_ahead(asides, config, encoder))
renderers = []
waiting = compiled_by(lambda: renderers.append(SceneRenderer(wait_for_kernels=asides.wait)))
cell = encoder.cell
frame = compiled_by(lambda: encoder.encode(
    renderers[0].render(Scene.of(config), 60 * cell.width, 28 * cell.height)))
assert ahead._minimizer_ready.wait(120)
minimizer = compiled_by(lambda: minimized("\x1b[1m\x1b[31mA\x1b[0m\x1b[1mB\x1b[0m"))
print(json.dumps({"ahead": ahead_, "waiting": waiting, "frame": frame,
                  "minimizer": minimizer}))
"""


@pytest.mark.skipif(coldstart._cores() < 2, reason="the children need a second core")
def test_on_a_cold_cache_the_app_loads_what_its_children_compiled(tmp_path):
    # Only the probe, this process's part; the children made the rest.
    assert _printed_on_a_cold_cache(APP_FIRST_RUN, tmp_path) == {
        "ahead": ["_farthest_along"], "waiting": [], "frame": [], "minimizer": []}


def _printed_on_a_cold_cache(script: str, tmp_path: Path) -> object:
    """What ``script`` prints (JSON), run on the default model in a fresh interpreter with
    an empty numba cache."""
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    process = subprocess.run([sys.executable, "-c", script, str(DEFAULT_CONFIG)],
                             capture_output=True, text=True, cwd=ROOT, env=environment,
                             timeout=300)
    assert process.returncode == 0, process.stderr
    return json.loads(process.stdout)


# A child that takes two seconds, and a probe that compiles (a cold cache) or does not.
# Prints whether the cache was taken for warm, and whether the child finished its job.
PROBED = """
import sys, time
from pathlib import Path
import numba
from biceps.engine import coldstart

done = Path(sys.argv[2])
asides = coldstart.Asides()
asides.start(lambda: (time.sleep(2), done.write_text("done")))
probe = numba.njit(lambda: 1) if sys.argv[1] == "cold" else lambda: None
warm = asides.stop_if_cached(probe)
asides.wait()
print(warm, done.exists())
"""


@pytest.mark.skipif(coldstart._cores() < 2, reason="no second process on one core")
@pytest.mark.parametrize("cache", ["cold", "warm"])
def test_children_are_waited_for_on_a_cold_cache_and_stopped_on_a_warm_one(tmp_path, cache):
    process = subprocess.run([sys.executable, "-c", PROBED, cache, str(tmp_path / "done")],
                             capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert process.returncode == 0, process.stderr
    assert process.stdout.split() == [str(cache == "warm"), str(cache == "cold")]


LATER = """
import os
from biceps.engine import coldstart

read, write = os.pipe()
before = os.nice(0)
coldstart.compile_later(lambda: os.write(write, str(os.nice(0)).encode())).wait()
print(before, os.read(read, 16).decode(), os.nice(0))
"""


@pytest.mark.skipif(coldstart._cores() < 2, reason="no second process on one core")
def test_what_can_wait_compiles_at_the_lowest_priority():
    process = subprocess.run([sys.executable, "-c", LATER], capture_output=True, text=True,
                             cwd=ROOT, timeout=60)
    assert process.returncode == 0, process.stderr
    # The child at the lowest priority, whatever the tests run at; the parent as it was.
    before, child, after = process.stdout.split()
    assert (int(child), after) == (coldstart.LATER, before)


def test_there_is_no_fork_beside_another_thread(monkeypatch):
    def no_fork():
        raise AssertionError("forked beside another thread")

    monkeypatch.setattr(os, "fork", no_fork)
    release = threading.Event()
    other = threading.Thread(target=release.wait)
    other.start()
    try:
        coldstart.prepare_kernels("gouraud")
    finally:
        release.set()
        other.join()


# The child's job sleeps for ten minutes: waiting with a timeout, or stopping it from
# another thread, must end it and leave no child behind.
HANGING_CHILD = """
import os, sys, threading, time
from biceps.engine.coldstart import Asides

def no_child_left():
    try:
        os.waitpid(-1, os.WNOHANG)
    except ChildProcessError:
        return True
    return False

aside = Asides().start(lambda: time.sleep(600))
if sys.argv[1] == "timeout":
    aside.wait(timeout=0.2)
else:
    waiting = threading.Thread(target=aside.wait)
    waiting.start()
    time.sleep(0.2)
    aside.stop()
    waiting.join()
print(no_child_left())
"""


@pytest.mark.skipif(coldstart._cores() < 2, reason="no second process on one core")
@pytest.mark.parametrize("how", ["timeout", "stop"])
def test_a_child_that_does_not_end_is_stopped(how):
    process = subprocess.run([sys.executable, "-c", HANGING_CHILD, how], capture_output=True,
                             text=True, cwd=ROOT, timeout=60)
    assert process.returncode == 0, process.stderr
    assert process.stdout.strip() == "True"
