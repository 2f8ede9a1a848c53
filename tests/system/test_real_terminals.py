"""The app in the terminals people have, headless under Xvfb: a matrix of terminals, and of
tmux, GNU screen and ssh in front of them, each cell compared with what the renderer draws.

In each cell a terminal (Debian's xterm as a VT340, kitty, mlterm, xfce4-terminal for VTE,
alacritty) runs ``biceps doctor`` and then the app, both with the cell's ``--graphics``
(``auto`` unless the cell is about a mode), directly or inside tmux, GNU screen, or ssh to
an sshd of the test's own from inside tmux. The doctor's report must say what the README's
table says ``auto`` picks, and the colours; it also gives the size of a cell and of the
terminal, from which the test makes the picture the app should show: the renderer's frame
for the viewport, and for text the cells the encoder makes of it (in 256 colours, of the
frame mapped onto the palette) drawn at the terminal's cell size. Screenshots (ImageMagick's
``import``) are taken until the picture is found in one and matches (the mean difference
within the cell's bound: see ``Cell``); a white box (xterm's background where no image was
drawn) or missing-glyph boxes would not. Two cells then open the help, which must hide the
image, close it, which must bring it back, and quit, which must leave none of it.

The terminals are Debian packages (xvfb, xterm, kitty, mlterm, xfce4-terminal, alacritty,
imagemagick, xdotool, tmux, screen, openssh-server, and fonts); ``.ci/run`` installs them.
Without one, its cells are skipped, except in CI (``CI`` set), where that is a failure.
The screenshots are kept in pytest's temporary folder, one per cell.
"""

from __future__ import annotations

import os
import pwd
import re
import shlex
import shutil
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from biceps.engine.config import DEFAULT_CONFIG, load_config, rgb
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal.cells import SHAPES, CellRows
from biceps.terminal.palette import Palette256
from pictures import cell_pixels
from waiting import came

ROOT = Path(__file__).resolve().parents[2]
SCREEN = (1600, 1000)  # Xvfb's, in pixels: room for a maximised xterm
SIDE = 32  # the side panel's columns; the viewport's border takes one cell each side
FONT = "DejaVu Sans Mono"
PROGRAMS = {"vt340": "xterm", "xterm": "xterm", "kitty": "kitty", "mlterm": "mlterm",
            "xfce4-terminal": "xfce4-terminal", "alacritty": "alacritty"}
WAIT = 120.0  # seconds for a picture to come, at most: a loaded machine starts slowly
NOTIFICATION = (52, 10)  # cells at the bottom right where a notification may be


@dataclass(frozen=True)
class Cell:
    """A terminal, what is in front of the app in it, and what the app must show there.

    The picture matches when the mean difference per channel is below ``mean``: for text,
    sampled in the middle of each of its pixels, the cells' colours exactly, in 24 bits or
    the palette's (measured 0 in every cell); for kitty, every pixel, the frame exactly
    (measured 0); for sixel, every pixel of a picture quantised to 256 colours (measured
    0.5 in mlterm, 0.7 in xterm and 1.2 scaled down in a maximised xterm: the bones' dark
    edges, rare shades the octree folds into others).
    """

    terminal: str
    size: tuple[int, int] | None  # columns, rows; None: maximised
    shows: str  # the graphics the doctor and the app must use
    colours: str = "24-bit"  # and the colours: "24-bit" or "256"
    graphics: str = "auto"
    within: str | None = None  # None, "tmux", "screen", or "ssh" (from inside tmux)
    passthrough: bool = False  # tmux's allow-passthrough
    mean: float = 0.5
    screens: bool = False  # the help hides the image, and quitting leaves none of it


CELLS = {
    "xterm-vt340-120x36": Cell("vt340", (120, 36), "sixel", mean=2.0, screens=True),
    # 1593x988 pixels of 9x19: sixel images of at most 1000x1000, scaled into the middle.
    "xterm-vt340-maximised": Cell("vt340", None, "sixel", mean=2.0),
    "kitty": Cell("kitty", (100, 30), "kitty", mean=0.05, screens=True),
    # Debian's kitty 0.26 predates Unicode placeholders: no images, sextants kitty draws;
    # and tmux 3.3a knows no RGB for it: 256 colours (tmux maps 24-bit ones itself).
    "kitty-tmux-passthrough": Cell("kitty", (100, 30), "sextants", "256", within="tmux",
                                   passthrough=True),
    "mlterm": Cell("mlterm", (100, 30), "sixel", "256", mean=2.0),  # its colours: 256
    "xfce4-terminal": Cell("xfce4-terminal", (100, 30), "sextants"),
    "xfce4-terminal-halfblocks": Cell("xfce4-terminal", (100, 30), "halfblocks",
                                      graphics="halfblocks"),
    "alacritty": Cell("alacritty", (100, 30), "halfblocks"),
    "alacritty-quadrants": Cell("alacritty", (100, 30), "quadrants", graphics="quadrants"),
    "tmux-in-xterm": Cell("xterm", (100, 30), "halfblocks", within="tmux"),
    "screen-in-alacritty": Cell("alacritty", (100, 30), "halfblocks", "256",
                                within="screen"),
    "ssh-from-tmux-in-xterm": Cell("xterm", (100, 30), "halfblocks", within="ssh"),
}
INSIDE = {"tmux": ["tmux"], "screen": ["screen"], "ssh": ["tmux", "ssh", "sshd"]}


def _needed(cell: Cell) -> None:
    tools = ["Xvfb", "import", "xdotool", PROGRAMS[cell.terminal],
             *INSIDE.get(cell.within, [])]
    missing = [tool for tool in tools
               if shutil.which(tool) is None and not Path("/usr/sbin", tool).exists()]
    if missing:
        if os.environ.get("CI"):
            pytest.fail(f"missing {', '.join(missing)}: .ci/run installs them")
        pytest.skip(f"needs {', '.join(missing)} (Debian: see .ci/run)")


@pytest.fixture(scope="module")
def display():
    """An X server of its own, as ``:N``."""
    if shutil.which("Xvfb") is None:
        if os.environ.get("CI"):
            pytest.fail("missing Xvfb: .ci/run installs it")
        pytest.skip("needs Xvfb (Debian: xvfb)")
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-noreset", "-screen", "0",
                               f"{SCREEN[0]}x{SCREEN[1]}x24", "-nolisten", "tcp"],
                              pass_fds=(write,), stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as answer:
        number = answer.readline().strip()
    try:
        yield f":{number}"
    finally:
        server.terminate()
        server.wait()


@pytest.fixture(scope="module")
def sshd(tmp_path_factory):
    """An sshd of this test's own, on the loopback, on a free port, with its own host key
    and the test's key the only one it takes; stopped after. (As root, as CI runs, sshd
    wants its privilege separation folder, which Debian's service would make.)"""
    if shutil.which("ssh-keygen") is None or not Path("/usr/sbin/sshd").exists():
        yield None  # (the ssh cell says so)
        return
    folder = tmp_path_factory.mktemp("sshd")
    for key in ("host", "client"):
        subprocess.run(["ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-f",
                        str(folder / key)], check=True)
    (folder / "authorized_keys").write_text((folder / "client.pub").read_text())
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    (folder / "sshd_config").write_text(
        f"Port {port}\nListenAddress 127.0.0.1\nHostKey {folder / 'host'}\n"
        f"AuthorizedKeysFile {folder / 'authorized_keys'}\nPidFile {folder / 'sshd.pid'}\n"
        "UsePAM no\nStrictModes no\nPasswordAuthentication no\n"
        "KbdInteractiveAuthentication no\nPermitRootLogin prohibit-password\n")
    if os.getuid() == 0:
        Path("/run/sshd").mkdir(mode=0o755, exist_ok=True)
    server = subprocess.Popen(["/usr/sbin/sshd", "-D", "-e", "-f", str(folder / "sshd_config")],
                              stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        with socket.socket() as client:
            if client.connect_ex(("127.0.0.1", port)) == 0:
                break
        time.sleep(0.05)
    try:
        yield port, folder / "client"
    finally:
        server.terminate()
        server.wait()


def _window(cell: Cell, command: list[str]) -> list[str]:
    """The terminal running ``command``, at the top left of the screen."""
    columns, rows = cell.size or (0, 0)
    if cell.terminal in ("xterm", "vt340"):
        vt340 = (["-ti", "vt340", "-xrm", "XTerm*numColorRegisters: 256"]
                 if cell.terminal == "vt340" else [])
        place = ["-maximized"] if cell.size is None else ["-geometry", f"{columns}x{rows}+0+0"]
        return ["xterm", *vt340, "-fa", FONT, "-fs", "11" if cell.size is None else "10",
                *place, "-e", *command]
    if cell.terminal == "kitty":
        return ["kitty", "--config", "NONE", "-o", f"font_family={FONT}", "-o", "font_size=10",
                "-o", f"initial_window_width={columns}c", "-o",
                f"initial_window_height={rows}c", "-o", "window_padding_width=0", "-o",
                "remember_window_size=no", *command]
    if cell.terminal == "alacritty":
        return ["alacritty", "--config-file", "/dev/null", "-o", "font.size=10", "-o",
                f'font.normal.family="{FONT}"', "-o", f"window.dimensions.columns={columns}",
                "-o", f"window.dimensions.lines={rows}", "-e", *command]
    if cell.terminal == "xfce4-terminal":
        return ["xfce4-terminal", "--disable-server", "--hide-menubar", "--hide-scrollbar",
                "--hide-toolbar", "--geometry", f"{columns}x{rows}+0+0", "--font",
                f"{FONT} 10", "-x", *command]
    return ["mlterm", "-w", "10", "-g", f"{columns}x{rows}+0+0", "-e", *command]


class Run:
    """A cell running: its terminal on ``display``, the doctor's report, screenshots."""

    def __init__(self, cell: Cell, display: str, folder: Path, sshd) -> None:
        self.cell, self.folder = cell, folder
        self.doctor = folder / "doctor.txt"
        self.environment = {key: value for key, value in os.environ.items()
                            if not key.startswith(("TMUX", "STY", "COLORTERM", "TERM_PROGRAM",
                                                   "LC_TERMINAL", "VTE_VERSION", "WT_SESSION",
                                                   "TEXTUAL"))}
        # A home of its own: no terminal, tmux or screen reads a person's settings.
        self.environment.update(DISPLAY=display, LIBGL_ALWAYS_SOFTWARE="1", HOME=str(folder),
                                XDG_CONFIG_HOME=str(folder))
        options = f"--graphics {cell.graphics}"
        script = folder / "run.sh"
        script.write_text(
            f"cd {shlex.quote(str(ROOT))}\n"
            f"{shlex.quote(sys.executable)} -m biceps doctor {options} > {self.doctor}.part "
            f"2>&1; mv {self.doctor}.part {self.doctor}\n"
            # The shell keeps the window open after the app, to see what it leaves behind.
            f"{shlex.quote(sys.executable)} -m biceps app {options}\n"
            "echo the app has ended; sleep 600\n")
        command = ["sh", str(script)]
        self.socket = folder / "tmux.socket"
        if cell.within == "ssh":
            port, key = sshd
            user = pwd.getpwuid(os.getuid()).pw_name
            command = ["ssh", "-F", "/dev/null", "-i", str(key), "-p", str(port), "-t",
                       "-o", "StrictHostKeyChecking=no", "-o", "UserKnownHostsFile=/dev/null",
                       "-o", "BatchMode=yes", "-o", "LogLevel=ERROR", f"{user}@127.0.0.1",
                       f"sh {shlex.quote(str(script))}"]
        if cell.within in ("tmux", "ssh"):
            configuration = folder / "tmux.conf"
            configuration.write_text("set -g status off\n" + (
                "set -g allow-passthrough on\n" if cell.passthrough else ""))
            command = ["tmux", "-S", str(self.socket), "-f", str(configuration),
                       "new-session", shlex.join(command)]
        if cell.within == "screen":
            (folder / "screenrc").write_text("startup_message off\n")
            command = ["screen", "-S", f"biceps-test-{os.getpid()}", "-c",
                       str(folder / "screenrc"), *command]
        self.said = folder / "terminal.txt"  # what the terminal itself printed
        with self.said.open("wb") as said:
            self.process = subprocess.Popen(_window(cell, command), env=self.environment,
                                            stdout=said, stderr=subprocess.STDOUT,
                                            start_new_session=True)

    def report(self) -> str:
        try:
            return came(lambda: self.doctor.read_text() if self.doctor.exists() else None,
                        "the doctor's report", WAIT)
        except AssertionError:
            self.screenshot()  # what the terminal shows instead
            ended = self.process.poll()
            raise AssertionError(
                f"never came: the doctor's report; the screen is in "
                f"{self.folder / 'screen.png'}; the terminal "
                f"{'is running' if ended is None else f'ended with {ended}'} and said: "
                f"{self.said.read_text(errors='replace')[-2000:]!r}") from None

    def screenshot(self) -> np.ndarray:
        shot = self.folder / "screen.png"
        subprocess.run(["import", "-window", "root", str(shot)], env=self.environment,
                       check=True, timeout=30)
        return np.asarray(Image.open(shot).convert("RGB")).astype(int)

    def keys(self, *names: str) -> None:
        # XTEST keys reach the window under the pointer (no window manager, no focus).
        subprocess.run(["xdotool", "mousemove", "200", "200", "key", "--delay", "80", *names],
                       env=self.environment, check=True, timeout=30)

    def close(self) -> None:
        if self.cell.within in ("tmux", "ssh"):
            subprocess.run(["tmux", "-S", str(self.socket), "kill-server"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if self.cell.within == "screen":
            subprocess.run(["screen", "-S", f"biceps-test-{os.getpid()}", "-X", "quit"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if self.process.poll() is None:
            os.killpg(self.process.pid, 15)
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(self.process.pid, 9)
                self.process.wait()


@dataclass(frozen=True)
class Expected:
    """The picture the app should show: ``image`` as the terminal draws it, and for text,
    ``samples``: the pixels' colours ((h, w, 3)) and where the middle of each is in
    ``image`` (rows (h,), columns (w,)); the terminal's cell, and the bottom right corner
    of its cells, in pixels."""

    image: np.ndarray  # (H, W, 3) int
    cell: tuple[int, int]
    corner: tuple[int, int]
    samples: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


def _expected(cell: Cell, report: str) -> Expected:
    """What the app should draw, from the doctor's cell and terminal sizes."""
    found = re.search(r"cell size +(\d+)x(\d+) pixels, in a terminal of (\d+)x(\d+) cells",
                      report)
    width, height, columns, rows = map(int, found.groups())
    viewport = columns - SIDE - 2, rows - 3  # the border, and the footer below
    corner = columns * width, rows * height
    config = load_config(DEFAULT_CONFIG)
    scene, background = Scene.of(config), rgb(config.render.background)
    if cell.shows in ("kitty", "sixel"):
        frame = SceneRenderer().render(scene, viewport[0] * width, viewport[1] * height)
        limit = re.search(r"at most (\d+)x(\d+) pixels", report)
        if cell.shows == "sixel" and limit:  # drawn no larger than the terminal takes
            most = int(limit[1]), int(limit[2])
            scale = min(1.0, most[0] / frame.shape[1], most[1] / frame.shape[0])
            size = int(frame.shape[1] * scale), int(frame.shape[0] * scale)
            frame = np.asarray(Image.fromarray(frame).resize(size, Image.Resampling.BOX))
        return Expected(frame.astype(int), (width, height), corner)
    shape = SHAPES[cell.shows]
    aspect = 1.0 if cell.shows == "halfblocks" else (width / shape.columns) / (
        height / shape.rows)
    frame = SceneRenderer().render(scene, viewport[0] * shape.columns,
                                   viewport[1] * shape.rows, pixel_aspect=aspect)
    if cell.colours == "256":
        frame = Palette256().mapped(frame, background)
    cells = CellRows(shape, exact=cell.colours == "256")
    cells.fit(np.ascontiguousarray(frame))
    pixels = cell_pixels(shape, cells.cells).astype(int)
    # As the terminal draws them: each cell's pixels split its width and height.
    across = np.arange(viewport[0] * width) * shape.columns // width
    down = np.arange(viewport[1] * height) * shape.rows // height
    image = pixels[down][:, across]
    middles_x = ((np.arange(pixels.shape[1]) + 0.5) * width / shape.columns).astype(int)
    middles_y = ((np.arange(pixels.shape[0]) + 0.5) * height / shape.rows).astype(int)
    return Expected(image, (width, height), corner, (pixels, middles_y, middles_x))


def _muscle(pixels: np.ndarray) -> np.ndarray:
    """Where the muscle's reds are: red well above green and blue, which are close (not the
    orange of the borders and keys)."""
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return (r > 90) & (r > g + 50) & (r > b + 50) & (np.abs(g - b) < 40)


def _placed(screen: np.ndarray, expected: np.ndarray) -> tuple[int, int] | None:
    """Where ``expected``'s top-left corner is on ``screen``, found by the muscle in both;
    None while the muscle is not on the screen."""
    shown, drawn = _muscle(screen), _muscle(expected)
    if shown.sum() < 0.8 * drawn.sum():
        return None
    (sy, sx), (fy, fx) = (np.argwhere(mask).min(axis=0) for mask in (shown, drawn))
    best = None
    # The masks' corners differ by a pixel or more where colours differ a little (sixel's
    # palette, a glyph's edge): look around for where the whole picture matches best.
    for dy in range(-4, 5):
        for dx in range(-4, 5):
            y, x = sy - fy + dy, sx - fx + dx
            if (y < 0 or x < 0 or y + expected.shape[0] > screen.shape[0]
                    or x + expected.shape[1] > screen.shape[1]):
                continue
            error = np.abs(screen[y:y + expected.shape[0], x:x + expected.shape[1]]
                           - expected).mean()
            if best is None or error < best[0]:
                best = (error, (x, y))
    return best[1] if best else None


def _difference(screen: np.ndarray, expected: Expected, corner: tuple[int, int]) -> float:
    """The mean difference per channel between the picture on ``screen`` at ``corner`` and
    the expected one: every pixel of an image, the middle of each pixel of text, but those
    where a notification may be (over text, the app says why ``auto`` chose it, for 12 s:
    the screen's bottom right, NOTIFICATION cells of the terminal's)."""
    x, y = corner
    if expected.samples is None:
        height, width = expected.image.shape[:2]
        return float(np.abs(screen[y:y + height, x:x + width] - expected.image).mean())
    pixels, rows, columns = expected.samples
    shown = screen[y + rows][:, x + columns]
    right, bottom = expected.corner  # of the terminal's cells, in the window at 0, 0
    (across, down), (width, height) = NOTIFICATION, expected.cell
    clear = ~(((y + rows)[:, None] > bottom - down * height)
              & ((x + columns)[None, :] > right - across * width))
    return float(np.abs(shown - pixels)[clear].mean())


def _matching(run: Run, expected: Expected, mean: float) -> tuple[np.ndarray, tuple, float]:
    """The first screenshot whose picture matches, where, and how well; or an error naming
    how near the best came."""
    best = [np.inf]

    def shown():
        screen = run.screenshot()
        corner = _placed(screen, expected.image)
        if corner is None:
            return None
        difference = _difference(screen, expected, corner)
        best[0] = min(best[0], difference)
        return (screen, corner, difference) if difference < mean else None

    try:
        return came(shown, "the picture", WAIT, step=0.5)
    except AssertionError:
        raise AssertionError(f"the picture never matched: at best {best[0]:.2f} per channel, "
                             f"the bound {mean}") from None


def _white(screen: np.ndarray, corner: tuple[int, int], expected: np.ndarray) -> float:
    """The share of the picture's place that is white (a sixel xterm refused, say)."""
    x, y = corner
    place = screen[y:y + expected.shape[0], x:x + expected.shape[1]]
    return float((place.min(axis=2) > 235).mean())


@pytest.mark.parametrize("name", list(CELLS))
def test_the_app_shows_its_picture(name, display, sshd, tmp_path, request):
    cell = CELLS[name]
    _needed(cell)
    # Real pixels and the colours the app chooses are the private path's (on the public one,
    # half-blocks in the colours Textual guesses).
    request.getfixturevalue("private_path")
    if cell.within == "ssh" and sshd is None:
        if os.environ.get("CI"):
            pytest.fail("ssh-keygen or sshd is missing: .ci/run installs openssh-server")
        pytest.skip("needs openssh-server (ssh-keygen, /usr/sbin/sshd)")
    run = Run(cell, display, tmp_path, sshd)
    try:
        report = run.report()
        graphics = re.search(r"graphics +(\w+):", report)
        assert graphics and graphics[1] == cell.shows, report
        assert re.search(rf"colours +{cell.colours}", report), report
        expected = _expected(cell, report)
        screen, corner, difference = _matching(run, expected, cell.mean)
        Image.fromarray(screen.astype(np.uint8)).save(tmp_path / f"{name}.png")
        assert _white(screen, corner, expected.image) <= 0.001
        if cell.passthrough:  # kitty's question never reached a title
            title = subprocess.run(["tmux", "-S", str(run.socket), "display-message", "-p",
                                    "#{pane_title}"], capture_output=True, text=True).stdout
            assert "Gi=" not in title and "\x1b" not in title
        if cell.screens:
            run.keys("question")  # the help screen, over the picture
            came(lambda: True if _muscle(run.screenshot()).sum() == 0 else None,
                 "the help over the picture", 30)
            run.keys("Escape")
            _matching(run, expected, cell.mean)
            run.keys("q")
            came(lambda: True if _muscle(run.screenshot()).sum() == 0 else None,
                 "a screen without the picture after quitting", 30)
    finally:
        run.close()
