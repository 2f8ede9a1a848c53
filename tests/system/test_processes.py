"""The command as a user runs it: its own process, what it imports, and an installed wheel."""

from __future__ import annotations

import os
import pkgutil
import select
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import biceps.engine
import biceps.terminal
from biceps.engine.config import DEFAULT_CONFIG
from pty_app import first_picture

ROOT = Path(__file__).resolve().parents[2]
INVALID = ROOT / "tests" / "invalid_configs"


def _python(code: str, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code), *args],
                          capture_output=True, text=True, timeout=300, cwd=cwd)


def _imported_after(argv: list[str], *packages: str) -> list[str]:
    """The modules of ``packages`` that ``biceps ARGV`` imports, run in a fresh process."""
    process = _python(f"""
        import sys
        from biceps.cli import main
        try:
            main({argv!r})
        except SystemExit as done:
            assert done.code in (0, None), done.code
        print(sorted(m for m in sys.modules if m.split('.')[0] in {packages!r}
                     or m.startswith({packages!r})))
    """)
    assert process.returncode == 0, process.stderr
    return eval(process.stdout.strip().splitlines()[-1])


def test_no_engine_module_imports_a_terminal_library_or_the_app():
    modules = [info.name for info in pkgutil.walk_packages(biceps.engine.__path__, "biceps.engine.")]
    assert "biceps.engine.scene" in modules and len(modules) > 10
    process = _python(f"""
        import importlib, sys
        for name in {modules!r}:
            importlib.import_module(name)
        print(sorted(m for m in sys.modules
                     if m.split('.')[0] in ('textual', 'rich', 'rich_pixels')
                     or m.startswith(('biceps.tui', 'biceps.cli'))))
    """)
    assert process.returncode == 0, process.stderr
    assert process.stdout.strip() == "[]"


TERMINAL_PROTOCOLS = ["detect", "choose", "palette", "cells", "writing", "kitty", "sixel",
                      "iterm", "ansi", "printed"]


def test_the_terminal_layer_imports_no_textual_nor_the_app():
    # The questions, the choices, the palettes, the encoders and their byte writers: the
    # app's Textual stays out of them.
    modules = [info.name for info in pkgutil.walk_packages(biceps.terminal.__path__,
                                                           "biceps.terminal.")]
    assert sorted(name.rsplit(".", 1)[1] for name in modules) == sorted(TERMINAL_PROTOCOLS)
    process = _python(f"""
        import importlib, sys
        for name in {modules!r}:
            importlib.import_module(name)
        print(sorted(m for m in sys.modules if m.split('.')[0] == 'textual'
                     or m.startswith('biceps.tui')))
    """)
    assert process.returncode == 0, process.stderr
    assert process.stdout.strip() == "[]"


@pytest.mark.parametrize("argv", [
    ["--help"],
    ["info"],
    ["info", "--flexion", "90", "--json"],
    ["sweep", "--json"],
])
def test_commands_that_draw_nothing_import_no_numba(argv):
    assert _imported_after(argv, "numba", "llvmlite", "textual") == []


def test_export_mesh_imports_no_numba(tmp_path):
    assert _imported_after(["export-mesh", "-o", str(tmp_path / "arm.glb")], "numba") == []
    assert (tmp_path / "arm.glb").stat().st_size > 0


def test_snapshot_runs_without_importing_textual_or_rich(tmp_path):
    out = tmp_path / "arm.png"
    argv = ["snapshot", str(DEFAULT_CONFIG), "-o", str(out), "--size", "64x48"]
    assert _imported_after(argv, "textual", "rich", "biceps.tui") == []
    assert out.exists()


@pytest.mark.parametrize("printed", ["--ansi", "--kitty", "--sixel", "--iterm"])
def test_snapshot_printed_to_a_terminal_imports_no_textual_nor_the_app(printed):
    # (its output, into the pipe, ends up in the test's output: a small picture)
    argv = ["snapshot", str(DEFAULT_CONFIG), printed, "--size", "16x10"]
    assert _imported_after(argv, "textual", "biceps.tui") == []


def test_animate_runs_without_importing_textual_or_rich(tmp_path):
    out = tmp_path / "cycle.gif"
    argv = ["animate", "-o", str(out), "--size", "64x36", "--frames", "4"]
    assert _imported_after(argv, "textual", "rich", "biceps.tui", "av") == []
    assert out.exists()


def test_animate_shows_its_progress_on_a_terminal_and_none_when_piped(tmp_path):
    command = [sys.executable, "-m", "biceps", "animate", "--size", "64x36", "--frames", "8"]
    piped = subprocess.run([*command, "-o", str(tmp_path / "piped.gif")], capture_output=True,
                           text=True, timeout=300)
    assert piped.returncode == 0, piped.stderr
    assert piped.stderr.splitlines() == [f"wrote {tmp_path / 'piped.gif'} (64x36, 8 frames "
                                         "at 25 a second)"]
    master, slave = os.openpty()
    try:
        process = subprocess.run([*command, "-o", str(tmp_path / "shown.gif")],
                                 stdout=subprocess.PIPE, stderr=slave, timeout=300)
        os.close(slave)
        shown = _read_all(master).decode()
    finally:
        os.close(master)
    assert process.returncode == 0
    assert "rendering" in shown and "5/5" in shown  # 5 poses: out in 5, back through 3
    assert "encoding" in shown and "8/8" in shown


def _read_all(master: int) -> bytes:
    output = bytearray()
    while select.select([master], [], [], 0.5)[0]:
        try:
            chunk = os.read(master, 1 << 16)
        except OSError:  # the other side has closed
            break
        if not chunk:
            break
        output += chunk
    return bytes(output)


@pytest.mark.parametrize("name", ["binary_junk.toml", "broken_toml.toml", "unknown_key.toml"])
def test_a_real_process_prints_no_traceback(name):
    process = subprocess.run(
        [sys.executable, "-m", "biceps", "info", str(INVALID / name)],
        capture_output=True, text=True, timeout=60,
    )
    assert process.returncode == 2
    assert process.stderr.count("\n") == 1
    assert "Traceback" not in process.stderr


def test_a_wheel_installs_one_biceps_package_and_the_bundled_models(installed):
    process = subprocess.run([installed / "python", "-c", """
import importlib.util, pathlib, biceps, biceps.configs
print(pathlib.Path(biceps.__file__).parent.parent)
print(biceps.configs.DEFAULT)
print([n for n in ("engine", "tui", "terminal", "configs") if importlib.util.find_spec(n)])
"""], capture_output=True, text=True, cwd=installed, timeout=60)
    assert process.returncode == 0, process.stderr
    site, default, tops = process.stdout.splitlines()
    assert default.startswith(site) and Path(default).is_file()
    assert tops == "[]"
    assert not any(Path(site, name).exists()
                   for name in ("engine", "tui", "terminal", "configs"))


def test_the_installed_command_runs_on_the_bundled_model_from_anywhere(installed, tmp_path):
    def biceps(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([installed / "biceps", *args], capture_output=True, text=True,
                              cwd=tmp_path, timeout=300)

    info = biceps("info", "--json")
    assert info.returncode == 0, info.stderr
    assert '"nodes": 15' in info.stdout
    shot = biceps("snapshot", "-o", "arm.png", "--size", "160x90")
    assert shot.returncode == 0, shot.stderr
    printed = biceps("snapshot", "--ansi", "--size", "16x10")  # the terminal layer, installed
    assert printed.returncode == 0, printed.stderr
    assert printed.stdout.count("\u2580") + printed.stdout.count("\u2584") > 0
    assert Image.open(tmp_path / "arm.png").size == (160, 90)
    assert np.asarray(Image.open(tmp_path / "arm.png")).std() > 0  # a picture, not a blank
    mesh = biceps("export-mesh", "-o", "arm.obj")
    assert mesh.returncode == 0, mesh.stderr
    assert "o muscle" in (tmp_path / "arm.obj").read_text()
    app = first_picture([str(installed / "biceps")], cwd=tmp_path, keys=b"q")
    assert b"biceps.toml" in app.output
    assert app.exit_code == 0
    # The other bundled models by name, as README.md and the help give them, and the app.
    for name in ("elbow", "configs/elbow.toml"):
        elbow = biceps("info", name)
        assert elbow.returncode == 0, elbow.stderr
        assert "TRIlong" in elbow.stdout
    app = first_picture([str(installed / "biceps"), "elbow"], cwd=tmp_path, keys=b"q")
    assert b"elbow.toml" in app.output
    assert app.exit_code == 0
