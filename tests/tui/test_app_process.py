"""Process-wide set-up is the command's: an app a test builds forks nothing, freezes no heap
and leaves no thread behind; the command, in a process of its own, starts the children
compiling ahead, one pool of render threads and the heap's freeze, and mends a cache of
Textual's (biceps/cli.py)."""

from __future__ import annotations

import gc
import threading
import weakref
from concurrent.futures import ThreadPoolExecutor

import pytest
from click.testing import CliRunner
from textual.color import Color

from biceps.cli import OWN_PROCESS, main
from biceps.engine.coldstart import Asides
from biceps.engine.raster import bands
from biceps.tui import textual_private
from biceps.tui.app import AppProcess, BicepsApp
from biceps.tui.widgets.viewport import Viewport
from waiting import until


def _band_threads() -> list[threading.Thread]:
    return [thread for thread in threading.enumerate()
            if thread.name.startswith("biceps-band")]


async def test_an_app_in_a_test_freezes_no_heap_and_stops_its_render_threads(
        config, monkeypatch):
    # Every picture drawn in two bands, one on a pool's thread, on any machine.
    monkeypatch.setenv("BICEPS_THREADS", "2")
    monkeypatch.setattr(bands, "SMALL_PICTURE", 0)
    frozen = gc.get_freeze_count()  # (the test run's own, tests/conftest.py)
    app = BicepsApp(config)
    async with app.run_test() as pilot:
        viewport = app.screen.query_one(Viewport)
        await until(pilot, lambda: viewport.up_to_date and viewport.border_title)
        assert gc.get_freeze_count() == frozen
        assert _band_threads()
    for thread in _band_threads():
        thread.join(10)
    assert not _band_threads()


def test_the_app_command_sets_up_its_own_process(monkeypatch):
    runs, started, collector = [], [], []
    monkeypatch.setattr("biceps.tui.app.run_app",
                        lambda config, **options: runs.append(options["process"]))
    monkeypatch.setattr("biceps.cli._check_terminal", lambda: None)  # the runner has none
    monkeypatch.setattr("biceps.cli._keys_are_keys", lambda: None)  # the test's signals kept
    monkeypatch.setattr(Asides, "start", lambda self, job, what="": started.append(what))
    monkeypatch.setattr(gc, "collect", lambda: collector.append("collect"))
    monkeypatch.setattr(gc, "freeze", lambda: collector.append("freeze"))
    monkeypatch.setattr(textual_private, "release_styles_caches",
                        lambda: collector.append("mend"))
    result = CliRunner().invoke(main, ["app"], obj=OWN_PROCESS)
    assert result.exit_code == 0, result.output
    [process] = runs
    assert isinstance(process, AppProcess) and isinstance(process.asides, Asides)
    assert started == ["the rasterizer"]  # before Textual loads, its child on the way
    assert isinstance(process.pool, ThreadPoolExecutor)
    with pytest.raises(RuntimeError):  # shut down once the app has ended
        process.pool.submit(int)
    assert collector == ["mend"]  # the heap is frozen once the app is up, not before
    process.when_up()
    assert collector == ["mend", "collect", "freeze"]


def test_mended_textual_lets_go_of_the_lines_of_widgets_gone(private_path):
    # Each widget draws its lines into a StylesCache of its own. Textual's
    # StylesCache.get_inner_outer, cached for each StylesCache, kept the last 1,024 it was
    # asked on, and every line in them, after their widgets had gone.
    from textual._styles_cache import StylesCache

    assert textual_private.release_styles_caches()
    lines = StylesCache()
    inner, outer = lines.get_inner_outer(Color(10, 20, 30), Color(40, 50, 60, 0.5))
    assert (inner.background, outer.background) == (Color(25, 35, 45), Color(10, 20, 30))
    gone = weakref.ref(lines)
    del lines
    gc.collect()
    assert gone() is None
