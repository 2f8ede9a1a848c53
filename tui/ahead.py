"""The app's kernels compiled ahead, on every core, while Textual starts.

On a first run (an empty numba cache) the first picture waits for numba to compile what a
frame runs, and Textual's first screen for the output minimizer (``tui/sgr.py``). Each
compiles in a forked child of its own (``engine/coldstart.py``): the rasterizer, much the
longest, in one, which the command line starts as soon as it has read the config
(``biceps/cli.py``); the framing, the vertex stage, the downsampling, the 256-colour
palette where the terminal has no more, and the encoder in another. This process first
compiles the outline's small kernel, which also tells a warm cache from a cold one: with a
warm cache no other child starts, and the rasterizer's is stopped. The render thread waits
for the children and loads what they compiled.

On a first run the viewport says so (:func:`preparing`), with the parts done and the time
so far, until the first picture comes; the keys work meanwhile.

The minimizer only saves bytes: its child runs at the lowest priority, so that it takes no
share of a core from the frame's, and until it is done the app writes Textual's output as
it is, which the terminal shows the same.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass

import numpy as np
from textual.driver import Driver

from biceps.engine import coldstart
from biceps.engine.config import Config
from biceps.engine.scene_renderer import supersampling
from biceps.tui.encoder import PictureEncoder
from biceps.terminal.palette import Palette256
from biceps.tui.sgr import lean, minimized

_minimizer_ready = threading.Event()
_minimizer_ready.set()  # unless a child is compiling it


@dataclass(frozen=True)
class Preparation:
    """A first run's compilation for the first picture: since when, and its children."""

    started: float  # monotonic seconds
    children: tuple[coldstart.Aside, ...]  # those the first picture waits for

    def parts(self) -> tuple[int, int]:
        """The parts done and all of them: each child's, then the first picture's own."""
        return sum(child.ended for child in self.children), len(self.children) + 1

    def compiling(self) -> list[str]:
        """What the children that have not ended compile, in words."""
        return [child.what for child in self.children if not child.ended]


_preparation: Preparation | None = None


def preparing() -> Preparation | None:
    """This process's first run's compilation (:func:`compile_ahead` found the cache
    cold), or None: a warm cache, or no compilation ahead."""
    return _preparation


def compile_ahead(asides: coldstart.Asides, config: Config, encoder: PictureEncoder,
                  palette: bool = False) -> None:
    """Once the rasterizer's child of ``asides`` is on its way (see the module's
    docstring), probe the cache with the outline's kernel; if it is cold, start the children
    compiling the rest of the app's first frame of ``config`` through ``encoder`` (mapped
    onto the 256-colour palette first, if ``palette``), and the minimizer, and say so
    (:func:`preparing`). Call it before any other thread starts (see `Asides.start`)."""
    global _preparation
    started = time.monotonic()
    if asides.stop_if_cached(coldstart.prepare_outline):
        return  # this process loads the kernels as it goes, in milliseconds
    # A frame of one cell: so small that it is supersampled, as the app's first most
    # likely is (engine/scene_renderer.py).
    shading = config.render.shading
    ssaa = supersampling(config.render, encoder.cell.height)
    asides.start(lambda: _prepare_around_the_rasterizer(shading, ssaa, encoder, palette),
                 "the rest of a frame")
    _preparation = Preparation(started, tuple(asides.children))
    minimizer = coldstart.compile_later(_load_minimizer)
    if minimizer is not None:
        _minimizer_ready.clear()
        threading.Thread(target=_load_once_compiled, args=(minimizer,), name="minimizer",
                         daemon=True).start()


def lean_once_ready(driver_class: type[Driver]) -> type[Driver]:
    """``lean(driver_class)``, writing its output as it is until the minimizer is ready.
    Textual leaves the terminal in its default state after every write, so either way of
    writing may follow the other."""
    lean_class = lean(driver_class)

    class LeanOnceReady(lean_class):
        def write(self, data: str) -> None:
            if _minimizer_ready.is_set():
                super().write(data)
            else:
                driver_class.write(self, data)

    LeanOnceReady.__name__ = LeanOnceReady.__qualname__ = lean_class.__name__
    return LeanOnceReady


def _prepare_around_the_rasterizer(shading: str, ssaa: int, encoder: PictureEncoder,
                                   palette: bool) -> None:
    """What a frame runs before and after the rasterizer (`coldstart`'s), and the encoder,
    given a read-only frame as the renderer returns (mapped onto the palette, if
    ``palette``)."""
    coldstart.prepare_around_the_rasterizer(shading, ssaa)
    frame = np.zeros((encoder.cell.height, encoder.cell.width, 3), np.uint8)
    frame.flags.writeable = False
    if palette:
        frame = Palette256().mapped(frame, (0, 0, 0))
    encoder.encode(frame)


def _load_minimizer() -> None:
    minimized("\x1b[1m \x1b[0m")


def _load_once_compiled(minimizer: coldstart.Aside) -> None:
    minimizer.wait()
    _load_minimizer()
    _minimizer_ready.set()
