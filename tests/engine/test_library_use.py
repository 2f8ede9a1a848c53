"""The engine used as a library leaves the process as it found it: no fork, the heap not
frozen, no thread left once its renderer is closed. Process-wide set-up is the commands'
(biceps/cli.py)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# In a fresh interpreter, so that nothing else has forked, frozen or started threads. A
# picture large enough to be drawn in bands on two threads (BICEPS_THREADS=2).
LIBRARY_USE = """
import gc, json, os, threading

def no_fork():
    raise AssertionError("the engine forked")

os.fork = no_fork
from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer

alone = threading.active_count()
renderer = SceneRenderer()
picture = renderer.render(Scene.of(load_config(DEFAULT_CONFIG)), 640, 360)
drawing = threading.active_count()
renderer.close()
print(json.dumps({"alone": alone, "drawing": drawing, "closed": threading.active_count(),
                  "frozen": gc.get_freeze_count(), "shape": list(picture.shape)}))
"""


def test_the_engine_as_a_library_forks_nothing_freezes_nothing_and_leaves_no_thread():
    process = subprocess.run([sys.executable, "-c", LIBRARY_USE], capture_output=True,
                             text=True, cwd=ROOT, timeout=300,
                             env={**os.environ, "BICEPS_THREADS": "2"})
    assert process.returncode == 0, process.stderr
    figures = json.loads(process.stdout)
    assert figures["shape"] == [360, 640, 3]
    # A pool thread drew the second band while the renderer was open, and is gone after.
    assert figures["drawing"] == figures["alone"] + 1
    assert figures["closed"] == figures["alone"]
    assert figures["frozen"] == 0
