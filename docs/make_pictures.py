"""Make the README's pictures again from the code as it is: ``docs/biceps.png`` and
``docs/elbow.png`` with ``biceps snapshot``, and ``docs/kitty.png``, the app in a real kitty
under a headless X server (Xvfb), taken with ImageMagick's ``import``.

    .venv/bin/python docs/make_pictures.py [--only NAME ...]

Kept beside the pictures, and the README's captions say the same views, so that a picture
never shows a model or a screen the code no longer makes. The screenshot needs Debian's
xvfb, kitty, imagemagick and fonts-dejavu (which ``.ci/run`` installs for the tests).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from PIL import Image

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
BICEPS = [sys.executable, "-m", "biceps"]

SNAPSHOTS = {
    # The README's first picture, and its command, word for word.
    "biceps.png": ["snapshot", "-o", "docs/biceps.png", "--size", "960x540", "--flexion", "95",
                   "--yaw", "-35", "--pitch", "8", "--shading", "phong", "--ssaa", "2"],
    # The six from the side at 60 degrees, as the app opens them.
    "elbow.png": ["snapshot", "configs/elbow.toml", "-o", "docs/elbow.png", "--flexion", "60",
                  "--yaw", "0", "--size", "960x540"],
}
COLUMNS, ROWS = 90, 30  # kitty.png: the app in kitty, cells of DejaVu Sans Mono at 10 points
SETTLE = 4.0  # seconds for the picture to be drawn once it shows, and the notice to go


def snapshot(name: str) -> None:
    subprocess.run([*BICEPS, *SNAPSHOTS[name]], cwd=ROOT, check=True)


def kitty_screenshot(target: Path) -> None:
    """The app on the bundled model in kitty (``--graphics kitty``), the window's pixels."""
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x800x24",
                               "-nolisten", "tcp"], pass_fds=(write,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as answer:
        display = f":{answer.readline().strip()}"
    environment = {**os.environ, "DISPLAY": display, "LIBGL_ALWAYS_SOFTWARE": "1"}
    for key in ("TMUX", "STY", "COLORTERM", "TERM_PROGRAM", "LC_TERMINAL"):
        environment.pop(key, None)
    app = " ".join([*BICEPS, "--graphics", "kitty", "--colors", "truecolor"])
    kitty = subprocess.Popen(
        ["kitty", "--config", "NONE", "-o", "font_family=DejaVu Sans Mono", "-o", "font_size=10",
         "-o", f"initial_window_width={COLUMNS}c", "-o", f"initial_window_height={ROWS}c",
         "-o", "window_padding_width=0", "-o", "remember_window_size=no", "sh", "-c",
         f"{app}; sleep 60"], env=environment, cwd=ROOT,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        with tempfile.TemporaryDirectory() as folder:
            shot = Path(folder) / "screen.png"
            window = None
            deadline = time.monotonic() + 120
            while window is None and time.monotonic() < deadline:
                time.sleep(1.0)
                subprocess.run(["import", "-window", "root", str(shot)], env=environment,
                               check=True)
                window = _window(np.asarray(Image.open(shot).convert("RGB")))
            if window is None:
                raise SystemExit("kitty never showed the app's picture")
            time.sleep(SETTLE)
            subprocess.run(["import", "-window", "root", str(shot)], env=environment, check=True)
            screen = np.asarray(Image.open(shot).convert("RGB"))
            width, height = _window(screen)
            Image.fromarray(screen[:height, :width]).save(target, optimize=True)
    finally:
        for process in (kitty, server):
            process.terminate()
            process.wait()


def _window(screen: np.ndarray) -> tuple[int, int] | None:
    """The width and height of kitty's window at the top left of ``screen`` (the X root
    beyond it is black), once the muscle's reds are in it; else None."""
    r, g, b = (screen[..., channel].astype(int) for channel in range(3))
    if not ((r > 90) & (r > g + 50) & (r > b + 50) & (np.abs(g - b) < 40)).any():
        return None
    lit = screen.any(axis=2)
    return int(np.argwhere(lit.any(axis=0)).max()) + 1, int(np.argwhere(lit.any(axis=1)).max()) + 1


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    names = [*SNAPSHOTS, "kitty.png"]
    parser.add_argument("--only", nargs="+", choices=names, default=names)
    for name in parser.parse_args().only:
        if name == "kitty.png":
            kitty_screenshot(DOCS / name)
        else:
            snapshot(name)
        print(f"made docs/{name}")


if __name__ == "__main__":
    main()
