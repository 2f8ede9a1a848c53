"""``biceps serve`` and Debian's chromium, headless, driven by selenium: for the browser test
and benchmarks/serve.py.

A script put in the page before its own records what the page's terminal (xterm.js) tells
the server: its size in cells, from which, with the size of its screen in pixels, comes
where each cell is in a screenshot.
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

from waiting import came

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"

RECORD_THE_TERMINAL = """
window.__sizes = [];
window.__received = "";
const Original = window.WebSocket;
window.WebSocket = function (url, protocols) {
    const socket = new Original(url, protocols);
    const decoder = new TextDecoder();
    socket.addEventListener("message", (event) => {
        if (event.data instanceof ArrayBuffer) {
            window.__received += decoder.decode(event.data, {stream: true});
        }
    });
    const send = socket.send.bind(socket);
    socket.send = (data) => {
        if (typeof data === "string" && data.startsWith('["resize"')) {
            window.__sizes.push(JSON.parse(data)[1]);
        }
        send(data);
    };
    return socket;
};
"""


def missing() -> list[str]:
    """The Debian packages and Python packages the browser needs that are not here."""
    gone = [name for name, path in (("chromium", CHROMIUM), ("chromium-driver", CHROMEDRIVER))
            if not os.path.exists(path)]
    for module, package in (("selenium", "selenium"), ("textual_serve", "textual-serve")):
        try:
            __import__(module)
        except ImportError:
            gone.append(package)
    return gone


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@contextmanager
def served(config: Path, *options: str, private: bool = True,
           log: Path | None = None) -> Iterator[str]:
    """``biceps serve config`` on a free port of localhost, stopped after; yields its URL."""
    port = free_port()
    environment = {**os.environ, "BICEPS_TEXTUAL_PRIVATE": "1" if private else "0"}
    out = open(log, "wb") if log else subprocess.DEVNULL
    server = subprocess.Popen(
        [sys.executable, "-m", "biceps", "serve", str(config), "--port", str(port), *options],
        stdout=out, stderr=subprocess.STDOUT, env=environment)
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if server.poll() is not None or time.monotonic() > deadline:
                    raise AssertionError(f"biceps serve never listened (status {server.poll()})")
                time.sleep(0.1)
        yield f"http://localhost:{port}/"
    finally:
        server.terminate()
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        if log:
            out.close()


def browser(downloads: Path, size: tuple[int, int] = (1280, 800)):
    """Headless chromium (selenium's webdriver), its downloads into ``downloads``."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu",
                     "--enable-unsafe-swiftshader",  # xterm.js draws with WebGL
                     # The page opens each download in a tab of its own, from the websocket:
                     # no click of the visitor's is near enough for a popup blocker.
                     "--disable-popup-blocking", "--force-device-scale-factor=1",
                     f"--window-size={size[0]},{size[1]}"):
        options.add_argument(argument)
    options.add_experimental_option("prefs", {"download.default_directory": str(downloads),
                                              "download.prompt_for_download": False})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.execute_cdp_cmd("Browser.setDownloadBehavior",
                           {"behavior": "allow", "downloadPath": str(downloads)})
    driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument",
                           {"source": RECORD_THE_TERMINAL})
    return driver


def terminal_geometry(driver) -> tuple[int, int, float, float, float, float] | None:
    """The page's terminal: columns, rows, its left and top in the screenshot, and a cell's
    width and height in pixels; None before it has told the server its size."""
    found = driver.execute_script("""
        const sizes = window.__sizes || [];
        const screen = document.querySelector('.xterm-screen');
        if (!sizes.length || !screen) return null;
        const box = screen.getBoundingClientRect();
        const size = sizes[sizes.length - 1];
        return [size.width, size.height, box.left, box.top, box.width, box.height];
    """)
    if not found:
        return None
    columns, rows, left, top, width, height = found
    return columns, rows, left, top, width / columns, height / rows


def forget_received(driver) -> None:
    """Start :func:`received` afresh."""
    driver.execute_script("window.__received = '';")


def received(driver, text: str) -> bool:
    """Whether the page's terminal has been sent ``text`` since :func:`forget_received`
    (colours and cursor moves left out): a dialog has opened, say."""
    return driver.execute_script(
        "return window.__received.replace(/\\x1b\\[[0-9;?]*[A-Za-z]/g, '')"
        ".includes(arguments[0]);", text)


def until_received(driver, text: str, timeout: float = 120.0) -> None:
    """Wait until :func:`received` says ``text`` has come."""
    came(lambda: received(driver, text) or None, repr(text), timeout, step=0.1)


def press(driver, keys: str) -> None:
    """Type ``keys`` into the page's terminal."""
    from selenium.webdriver.common.by import By

    driver.find_element(By.CSS_SELECTOR, ".xterm-helper-textarea").send_keys(keys)

