"""The app in real terminals that show real pixels, headless: ``xterm -ti vt340`` (sixel)
and ``kitty`` (its graphics protocol, drawn with Mesa's software OpenGL) under Xvfb.

Each test starts the app in the terminal, takes a screenshot of the screen with
ImageMagick's ``import``, finds the picture in it, and compares its pixels with the frame
the renderer makes for the viewport's size: kitty's exactly (at most a rounding step in a
channel), xterm's within sixel's palette (see the tolerances below). Then the help screen
must hide the picture, closing it must bring the picture back, and after quitting no pixel
of the picture may be left on the screen.

The terminals are Debian packages (xvfb, xterm, kitty, imagemagick, xdotool, and fonts);
``.ci/run`` installs them. Without them the tests are skipped, except in CI (``CI`` set),
where that is a failure.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from biceps.engine.config import DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene, SceneRenderer

ROOT = Path(__file__).resolve().parents[2]
COLUMNS, ROWS = 90, 30
SIDE, FRAME_ROWS = 32 + 2, 3  # the side panel and the picture's border; border and footer
TOOLS = ("Xvfb", "xterm", "kitty", "import", "xdotool")


def _tools_or_skip() -> None:
    missing = [tool for tool in TOOLS if shutil.which(tool) is None]
    if missing:
        if os.environ.get("CI"):
            pytest.fail(f"missing {', '.join(missing)}: .ci/run installs them")
        pytest.skip(f"needs {', '.join(missing)} (Debian: xvfb xterm kitty imagemagick xdotool)")


@pytest.fixture
def display():
    """A new X server of its own, as ``:N``."""
    _tools_or_skip()
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x800x24",
                               "-nolisten", "tcp"], pass_fds=(write,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as answer:
        number = answer.readline().strip()
    try:
        yield f":{number}"
    finally:
        server.terminate()
        server.wait()


class Window:
    """A terminal running the app on ``display``, seen through screenshots."""

    def __init__(self, display: str, argv: list[str], tmp_path: Path) -> None:
        self.environment = {**os.environ, "DISPLAY": display, "LIBGL_ALWAYS_SOFTWARE": "1"}
        for key in ("TMUX", "STY", "COLORTERM", "TERM_PROGRAM", "LC_TERMINAL"):
            self.environment.pop(key, None)
        self.shot = tmp_path / "screen.png"
        self.process = subprocess.Popen(argv, env=self.environment, cwd=ROOT,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def screenshot(self) -> np.ndarray:
        subprocess.run(["import", "-window", "root", str(self.shot)], env=self.environment,
                       check=True, timeout=30)
        return np.asarray(Image.open(self.shot).convert("RGB")).astype(int)

    def keys(self, *names: str) -> None:
        # XTEST keys reach the window under the pointer (no window manager, no focus).
        subprocess.run(["xdotool", "mousemove", "200", "200", "key", "--delay", "80", *names],
                       env=self.environment, check=True, timeout=30)

    def close(self) -> None:
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()


def _app(graphics: str) -> list[str]:
    # The shell keeps the window open after the app, to see what it leaves behind.
    command = (f"{sys.executable} -m biceps app --graphics {graphics} --colors truecolor; "
               "echo; echo the app has ended; sleep 60")
    return ["sh", "-c", command]


def _muscle_mask(pixels: np.ndarray) -> np.ndarray:
    """Where the muscle's reds are: red well above green and blue, which are close (not
    the orange of the borders and keys)."""
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return (r > 90) & (r > g + 50) & (r > b + 50) & (np.abs(g - b) < 40)


def _until(condition, timeout: float = 90.0, step: float = 0.5):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        result = condition()
        if result is not None:
            return result
        time.sleep(step)
    raise AssertionError("the terminal never showed what was expected")


def _picture(screen: np.ndarray, frame: np.ndarray) -> tuple[int, int] | None:
    """Where ``frame``'s top-left corner is on ``screen``, found by the muscle in both;
    None while the muscle is not on the screen."""
    shown, drawn = _muscle_mask(screen), _muscle_mask(frame)
    if shown.sum() < 0.9 * drawn.sum():
        return None
    (sy, sx), (fy, fx) = (np.argwhere(mask).min(axis=0) for mask in (shown, drawn))
    best = None
    # The masks' corners can differ by a pixel or two where the palette differs: look
    # around for the offset where the whole picture matches best.
    for dy in range(-3, 4):
        for dx in range(-3, 4):
            y, x = sy - fy + dy, sx - fx + dx
            if y < 0 or x < 0 or y + frame.shape[0] > screen.shape[0] \
                    or x + frame.shape[1] > screen.shape[1]:
                continue
            error = np.abs(screen[y:y + frame.shape[0], x:x + frame.shape[1]] - frame).mean()
            if best is None or error < best[0]:
                best = (error, (x, y))
    return best[1] if best else None


def _frame(cell: tuple[int, int]) -> np.ndarray:
    width, height = (COLUMNS - SIDE) * cell[0], (ROWS - FRAME_ROWS) * cell[1]
    return SceneRenderer().render(Scene.of(load_config(DEFAULT_CONFIG)), width, height).astype(int)


def _cell(display: str, terminal: list[str], tmp_path: Path) -> tuple[int, int]:
    """The cell size the app will find, as biceps doctor finds it in the same terminal."""
    report = tmp_path / "doctor.txt"
    window = Window(display, [*terminal, "sh", "-c",
                              f"{sys.executable} -m biceps doctor > {report}"], tmp_path)
    try:
        text = _until(lambda: report.read_text() if report.exists()
                      and "graphics" in report.read_text() else None, timeout=60)
    finally:
        window.close()
    line = next(line for line in text.splitlines() if "cell size" in line)
    width, height = line.split()[2].split("x")
    return int(width), int(height)


def _run_in(display: str, terminal: list[str], graphics: str, tmp_path: Path,
            mean: float, share: float, gap: int) -> None:
    """Start the app in ``terminal``, compare its picture with the frame, then open and
    close the help and quit. The picture matches when the mean difference per channel is
    below ``mean`` and all but ``share`` of the pixels are within ``gap`` in every channel."""
    frame = _frame(_cell(display, terminal, tmp_path))
    window = Window(display, [*terminal, *_app(graphics)], tmp_path)
    try:
        corner = _until(lambda: _picture(window.screenshot(), frame))
        time.sleep(1.0)  # the first frame may have been followed by another
        screen = window.screenshot()
        x, y = _picture(screen, frame)
        Image.fromarray(screen.astype(np.uint8)).save(tmp_path / f"{graphics}.png")
        shown = screen[y:y + frame.shape[0], x:x + frame.shape[1]]
        difference = np.abs(shown - frame)
        assert difference.mean() < mean, (corner, difference.mean())
        assert (difference.max(axis=2) > gap).mean() <= share

        window.keys("question")  # the help screen, over the picture
        _until(lambda: True if _muscle_mask(window.screenshot()).sum() == 0 else None, 20)
        window.keys("Escape")
        _until(lambda: _picture(window.screenshot(), frame), 20)
        window.keys("q")
        _until(lambda: True if _muscle_mask(window.screenshot()).sum() == 0 else None, 20)
    finally:
        window.close()


def test_sixel_in_xterm(display, tmp_path):
    # xterm's vt340 has 16 colour registers unless told more; 256 is what sixel allows.
    xterm = ["xterm", "-ti", "vt340", "-xrm", "XTerm*numColorRegisters: 256", "-fa",
             "DejaVu Sans Mono", "-fs", "10", "-geometry", f"{COLUMNS}x{ROWS}+0+0", "-e"]
    # Sixel quantises to 256 colours: measured on this picture (8x17-pixel cells), a mean
    # difference of 1.29 per channel and 1.1 % of the pixels more than 16 off: the bones'
    # dark silhouettes, rare shades the octree folds into others, now that the arm and its
    # bones fill the picture (on the thin arm of before: 0.70, none more than 9 off).
    _run_in(display, xterm, "sixel", tmp_path, mean=1.5, share=0.02, gap=16)


def test_kitty_graphics_in_kitty(display, tmp_path):
    kitty = ["kitty", "--config", "NONE", "-o", "font_family=DejaVu Sans Mono", "-o",
             "font_size=10", "-o", f"initial_window_width={COLUMNS}c", "-o",
             f"initial_window_height={ROWS}c", "-o", "window_padding_width=0", "-o",
             "remember_window_size=no"]
    # Kitty shows the pixels as sent, drawn 1:1 with OpenGL: measured, no difference at all.
    _run_in(display, kitty, "kitty", tmp_path, mean=0.05, share=0.0005, gap=1)
