"""``biceps serve`` in a real browser: Debian's chromium, headless, driven by selenium.

The page is opened, the picture awaited and compared with the renderer's frame of the same
view as half-block cells, sampled in the screenshot at each half cell's middle; keys turn
the model and contract the muscle, and the picture must change to the new view's; ``e``
exports a PNG, which must arrive as a download and be that view's picture. Both of the
app's paths (through Textual's internals, and Textual's public one) are tried.

Needs Debian's chromium and chromium-driver (``.ci/run`` installs them) and the test extra's
selenium and textual-serve; without them the test is skipped, except in CI, where that
is a failure. The screenshots are kept in pytest's temporary folder.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from biceps.engine.config import BUNDLED, DEFAULT_CONFIG, load_config
from biceps.engine.scene import Scene
from biceps.engine.scene_renderer import SceneRenderer
from biceps.terminal.cells import SHAPES, CellRows
from biceps.tui.app import DRAG_TURN
from biceps.tui.changes import length_changed, turned
from browser import (browser, forget_received, missing, press, received, served,
                     terminal_geometry, until_received)
from pictures import cell_pixels
from waiting import came

SIDE = 32  # the side panel's columns, shown from 100 columns on
WAIT = 120.0  # seconds for a picture to come, at most: a loaded machine starts slowly
MATCH = 12.0  # the mean difference per channel within which the picture is the view's


def _expected(scene: Scene, columns: int, rows: int) -> np.ndarray:
    """The viewport's half-block pixels for ``scene`` in a terminal of columns x rows:
    (2 * its rows, its columns, 3)."""
    width = columns - (SIDE if columns >= 100 else 0) - 2  # its border's two columns
    height = rows - 3  # the border's two rows, and the footer
    shape = SHAPES["halfblocks"]
    frame = SceneRenderer().render(scene, width, height * 2)
    cells = CellRows(shape)
    cells.fit(np.ascontiguousarray(frame))
    return cell_pixels(shape, cells.cells).astype(int)


def _shown(screenshot: np.ndarray, geometry, pixels: np.ndarray) -> np.ndarray:
    """The screenshot's colours at the middle of each half cell of the viewport."""
    _, _, left, top, width, height = geometry
    rows, columns = pixels.shape[:2]
    xs = (left + (1 + np.arange(columns) + 0.5) * width).astype(int)
    ys = (top + (1 + np.arange(rows) // 2 + 0.25 + 0.5 * (np.arange(rows) % 2))
          * height).astype(int)
    return screenshot[ys][:, xs]


def _difference(shown: np.ndarray, pixels: np.ndarray) -> float:
    """The mean difference per channel over the arm (where the expected picture is not its
    background, the colour of its first pixel)."""
    arm = (pixels != pixels[0, 0]).any(axis=2)
    return float(np.abs(shown - pixels)[arm].mean())


def _screenshot(driver) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("RGB"),
                      dtype=int)


def _shows(driver, scene: Scene, tmp_path: Path, name: str) -> float:
    """Wait until the page shows ``scene``'s picture; its mean difference per channel. The
    screenshot that showed it is kept as ``name``.png."""
    geometry = came(lambda: terminal_geometry(driver), "the terminal's size")
    pixels = _expected(scene, *geometry[:2])
    best = [np.inf]

    def matching():
        screenshot = _screenshot(driver)
        difference = _difference(_shown(screenshot, geometry, pixels), pixels)
        best[0] = min(best[0], difference)
        if difference < MATCH:
            Image.fromarray(screenshot.astype(np.uint8)).save(tmp_path / f"{name}.png")
            return difference
        return None

    try:
        return came(matching, f"the picture of {name}")
    except AssertionError:
        Image.fromarray(_screenshot(driver).astype(np.uint8)).save(tmp_path / f"{name}.png")
        raise AssertionError(f"{name}: the picture never matched, at best {best[0]:.1f} per "
                             f"channel (the bound {MATCH}); see {tmp_path}") from None


def _downloaded(driver, downloads: Path, tmp_path: Path) -> Path:
    """Wait for the PNG to be downloaded whole; if it never is, say what the app and the
    server said of it, and keep a screenshot."""
    try:
        png = came(lambda: next(iter(downloads.glob("*.png")), None), "the download")
        came(lambda: True if not list(downloads.glob("*.crdownload")) else None,
               "the download's end")
        return png
    except AssertionError as error:
        Image.fromarray(_screenshot(driver).astype(np.uint8)).save(tmp_path / "export.png")
        handed_over = received(driver, "downloading")
        log = (tmp_path / "serve.log").read_text(errors="replace").splitlines()
        said = [line for line in log if "WARNING" in line or "ERROR" in line]
        raise AssertionError(f"{error}; the app said it handed the file over: {handed_over}; "
                             f"the server warned: {said}; see {tmp_path}") from None


def _needs_the_browser() -> None:
    """Skip without Chromium and its driver, selenium or textual-serve; in CI, fail."""
    gone = missing()
    if gone:
        if os.environ.get("CI"):
            pytest.fail(f"missing {', '.join(gone)}: .ci/run installs them")
        pytest.skip(f"needs {', '.join(gone)} (Debian's chromium and chromium-driver, the "
                    "test extra's selenium and textual-serve)")


@pytest.mark.parametrize("path", ["private", "public"])
def test_a_browser_shows_the_app_turns_contracts_and_downloads_a_png(path, tmp_path):
    _needs_the_browser()
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    start = Scene.of(load_config(DEFAULT_CONFIG))
    arm, _ = length_changed(start.arm, -2.0)
    turned_and_contracted = turned(start, roll=-15.0).with_arm(arm)
    with served(DEFAULT_CONFIG, private=path == "private", log=tmp_path / "serve.log") as url:
        driver = browser(downloads)
        try:
            driver.get(url)
            first = _shows(driver, start, tmp_path, "first")
            press(driver, "]]]CC")  # roll clockwise 3 x 5 degrees, contract 2 x 1 cm
            after = _shows(driver, turned_and_contracted, tmp_path, "turned")
            geometry = terminal_geometry(driver)
            before_keys = _expected(start, *geometry[:2])
            shown = _shown(_screenshot(driver), geometry, before_keys)
            assert _difference(shown, before_keys) > 2 * after  # no longer the first view
            forget_received(driver)
            press(driver, "e")
            until_received(driver, "Export a PNG")
            press(driver, "\n")  # biceps.png, 1920x1080, as offered
            png = _downloaded(driver, downloads, tmp_path)
        finally:
            driver.quit()
    assert png.name == "biceps.png"
    picture = np.asarray(Image.open(png).convert("RGB"), dtype=int)
    expected = SceneRenderer().render(turned_and_contracted.unmarked(), 1920, 1080)
    assert picture.shape == (1080, 1920, 3)
    assert np.abs(picture - expected).mean() < 0.5
    assert first < MATCH and after < MATCH


DROP = """
const transfer = new DataTransfer();
transfer.items.add(new File([arguments[1]], arguments[0]));
document.body.dispatchEvent(new DragEvent("drop", {dataTransfer: transfer, bubbles: true}));
"""


PASTE = """
const transfer = new DataTransfer();
transfer.setData("text/plain", arguments[0]);
document.querySelector(".xterm-helper-textarea").dispatchEvent(
    new ClipboardEvent("paste", {clipboardData: transfer, bubbles: true, cancelable: true}));
"""


def _upload_status(driver, expected: str, kind: str) -> str:
    """Wait until the upload bar says ``expected`` as a ``kind`` (saved or refused)."""
    from selenium.webdriver.common.by import By

    def said():
        status = driver.find_element(By.ID, "upload-status")
        text = status.text
        return text if expected in text and status.get_attribute("class") == f"-{kind}" else None

    return came(said, f"the upload bar saying {expected!r}")


def test_a_browser_uploads_a_model_opens_it_and_turns_it_with_the_mouse(tmp_path):
    _needs_the_browser()
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    mine = tmp_path / "mine.toml"
    mine.write_bytes((BUNDLED / "toy.toml").read_bytes())
    picture = tmp_path / "picture.png"
    picture.write_bytes(b"\x89PNG\r\n\x1a\n")
    toy = Scene.of(load_config(mine))
    with served(DEFAULT_CONFIG, log=tmp_path / "serve.log") as url:
        driver = browser(tmp_path)
        try:
            driver.get(url)
            _shows(driver, Scene.of(load_config(DEFAULT_CONFIG)), tmp_path, "before-upload")
            picker = driver.find_element(By.ID, "upload-file")
            picker.send_keys(str(picture))
            _upload_status(driver, "Not uploaded: picture.png is not a model", "refused")
            driver.save_screenshot(str(tmp_path / "refused.png"))
            picker.send_keys(str(mine))
            _upload_status(driver, "mine.toml is in your folder: open it in the app with "
                           "ctrl+o", "saved")
            driver.save_screenshot(str(tmp_path / "uploaded.png"))
            driver.execute_script(DROP, "dropped.toml", mine.read_text())
            _upload_status(driver, "dropped.toml is in your folder", "saved")

            forget_received(driver)
            press(driver, Keys.CONTROL + "o" + Keys.NULL)
            until_received(driver, "Open a configuration")
            driver.save_screenshot(str(tmp_path / "open-dialog.png"))
            # Pasted, as one input: a loaded machine may fall so far behind a burst of keys
            # that the app leaves some out (tui/behind.py). The dialog's field is selected,
            # so the paste replaces it.
            forget_received(driver)
            driver.execute_script(PASTE, "mine.toml")
            until_received(driver, "mine.toml")
            press(driver, "\n")
            _shows(driver, toy, tmp_path, "opened")

            # A drag with the left button turns the model, a cell across being as many
            # degrees as in a terminal (tui/widgets/viewport.py, tui/app.py's DRAG_TURN).
            columns, rows, left, top, width, height = terminal_geometry(driver)
            across = 12  # cells
            screen = driver.find_element(By.CSS_SELECTOR, ".xterm-screen")
            start_x = int((columns // 4 + 0.5) * width - screen.rect["width"] / 2)
            start_y = int((rows // 2 + 0.5) * height - screen.rect["height"] / 2)
            (ActionChains(driver).move_to_element_with_offset(screen, start_x, start_y)
             .click_and_hold().move_by_offset(round(across * width), 0).release().perform())
            viewport_rows = rows - 3  # its border's two rows, and the footer
            yaw = across / (2 * viewport_rows) * DRAG_TURN  # a half-block cell is 1 x 2 pixels
            _shows(driver, turned(toy, yaw=yaw), tmp_path, "dragged")
        finally:
            driver.quit()
