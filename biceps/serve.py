"""``biceps serve``: the app in a browser tab, one process a visitor, through textual-serve.

Each visitor who opens the page gets a process of its own (``biceps visit``) running the app
under Textual's web driver, in a scratch folder of its own under the server's, which is
removed when the visitor leaves. The page's websocket is that process's terminal; closing
the tab ends it. At most ``max_visitors`` at once: the next is shown a page saying so.

Each page is given a token of its own, unguessable, in its websocket's address and in the
address its bar uploads models to (``/upload/TOKEN``): while that page's visitor is there,
an upload with its token is written into its folder (``biceps/uploads.py``), and one with
any other token is refused. A websocket at ``/ws`` without a token gets the app, but no
uploads.

textual-serve is an optional extra (``pip install 'biceps[serve]'``); this module imports it
only when the server starts.
"""

from __future__ import annotations

import asyncio
import json
import secrets
import shlex
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Any
from urllib.parse import unquote

from biceps.engine.errors import BicepsError
from biceps.engine.names import printable

EXTRA = "serve"
LOCAL_HOSTS = ("localhost", "127.0.0.1", "::1")
QUIT_GRACE = 5.0
"""Seconds a visitor's process has to end after its tab closed before it is killed."""
PAGE_LIFE = 300.0
"""Seconds a page's token waits for its websocket; a page connects at once when it loads."""
MOST_PAGES = 1000
"""Tokens at most waiting for their websockets (pages loaded, their tabs closed at once)."""
CHUNK_PATIENCE = 60.0
"""Seconds the server waits for a visitor's app to send the next chunk of a download it asked
for. textual-serve's own 4 s ran out on a loaded server, and the visitor's download was lost;
a slow chunk only makes the download slower."""
PAGE = Path(__file__).with_name("templates")


@dataclass(frozen=True)
class Limits:
    """What each visitor's process may use: ``memory`` MB of data (``biceps visit
    --memory``), for ``minutes`` minutes."""

    memory: int
    minutes: float

CLEAR = "\x1b[?1049l\x1b[2J\x1b[H"
"""Back from the app's screen, cleared, the cursor at the top left."""

FULL_PAGE = """<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>biceps: full</title>
<style>body {{ background: #0c181f; color: #eee; font: 18px monospace; margin: 3em; }}</style>
</head><body><h1>biceps is full</h1>
<p>All {limit} places are taken. Try again in a minute: a place frees when someone closes
their tab.</p></body></html>
"""


def textual_serve() -> Any:
    """The textual_serve.server module, or a BicepsError naming the extra to install."""
    try:
        from textual_serve import server
    except ImportError:
        raise BicepsError(
            "serving the app to browsers needs textual-serve, the optional extra "
            f"{EXTRA!r}: pip install 'biceps[{EXTRA}]' (or pip install textual-serve)"
        ) from None
    return server


def is_local(host: str) -> bool:
    """Whether ``host`` is reachable only from this machine."""
    return host in LOCAL_HOSTS or host.startswith("127.")


def visit_command(config: Path, scratch: Path, limits: Limits, folder: Path | None = None) -> str:
    """The shell command textual-serve runs for each visitor: ``biceps visit``, forked
    from the zygote listening in ``scratch`` (``biceps/zygote.py``), or started afresh
    where it does not answer; in ``folder`` (the server made it, and writes the visitor's
    uploads into it), or without one in a new folder under ``scratch``. The shell becomes
    it (exec), so that it is the server's child and ends with the server."""
    words = [sys.executable, "-m", "biceps.zygote", str(zygote_socket(scratch)),
             "visit", str(config), "--scratch", str(scratch), "--memory", str(limits.memory)]
    return "exec " + shlex.join(words + (["--folder", str(folder)] if folder else []))


async def _turn_away(websocket: Any, note: str) -> Any:
    """Say ``note`` in the page's terminal, close its websocket and return it."""
    await websocket.send_bytes(f"\r\n{note}\r\n".encode())
    await websocket.close()
    return websocket


async def _read_at_most(content: Any, largest: int) -> bytes:
    """The request body from ``content`` (aiohttp's StreamReader), stopping once it is
    longer than ``largest`` bytes."""
    chunks, length = [], 0
    while length <= largest and (chunk := await content.read(64 * 1024)):
        chunks.append(chunk)
        length += len(chunk)
    return b"".join(chunks)


def zygote_socket(scratch: Path) -> Path:
    """Where the zygote of the server whose scratch folder is ``scratch`` listens."""
    return scratch / "zygote"


def start_zygote(config: Path, scratch: Path, environment: dict[str, str]) -> subprocess.Popen:
    """The zygote for ``config``, listening in ``scratch``, started with the environment
    a visitor's process gets (Textual reads some of it as it is imported)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET) as listening:
        listening.bind(str(zygote_socket(scratch)))
        listening.listen(64)
        # Its own session: ctrl+c in the server's terminal reaches the server, which stops
        # the visitors and then this.
        return subprocess.Popen(
            [sys.executable, "-m", "biceps.zygote", "--zygote", str(listening.fileno()),
             str(config)], pass_fds=[listening.fileno()], stdin=subprocess.DEVNULL,
            env=environment, start_new_session=True)


def stop_zygote(zygote: subprocess.Popen) -> None:
    zygote.terminate()
    try:
        zygote.wait(QUIT_GRACE)
    except subprocess.TimeoutExpired:
        zygote.kill()
        zygote.wait()


def ending_note(status: int | None, limits: Limits) -> str | None:
    """What a visitor is told when its app has ended with ``status`` (None: it has not ended
    yet, and is about to be killed)."""
    if status == 0 or status is None:
        return None
    return (f"biceps ended on an error (exit status {status}). Each visitor may use "
            f"{limits.memory} MB of memory here, and a picture or an animation that needs "
            "more is refused. Reload the page to start again.")


def make_server(config: Path, host: str, port: int, max_visitors: int, scratch: Path,
                limits: Limits, zygote: subprocess.Popen | None = None) -> Any:
    """A textual-serve Server for ``config`` (see :func:`serve`)."""
    server = textual_serve()
    from textual_serve import download_manager

    # Read on every chunk it waits for: textual-serve has no option for it.
    download_manager.DOWNLOAD_TIMEOUT = CHUNK_PATIENCE
    from aiohttp import web
    import aiohttp_jinja2

    from biceps import uploads
    from biceps.engine.config import LARGEST_FILE

    class Visit(server.AppService):
        note: str | None = None  # said in the visitor's terminal once its app has ended
        _time_limit: asyncio.TimerHandle | None = None
        _stopping: asyncio.Future | None = None

        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.ended = asyncio.Event()  # the app's process has ended: its place is free

        async def start(self, width: int, height: int) -> None:
            await super().start(width, height)
            self._time_limit = asyncio.get_running_loop().call_later(
                limits.minutes * 60, self._time_up)

        def _time_up(self) -> None:
            self.note = (f"Your {limits.minutes:g} minutes are up, the most a visitor has on "
                         "this server. Reload the page to start again.")
            if self._stopping is None:
                self._stopping = asyncio.ensure_future(self._stop())

        async def on_meta(self, data: bytes) -> None:
            if json.loads(data).get("type") == "exit":
                return  # the page is closed once the process ends, after the note
            await super().on_meta(data)

        async def run(self) -> None:
            await super().run()  # until the app's output ends
            try:
                status = await asyncio.wait_for(self._process.wait(), QUIT_GRACE)
            except asyncio.TimeoutError:
                status = None
            self.ended.set()
            note = self.note or ending_note(status, limits)
            try:
                if note:  # left on the page, which textual-serve's "Session ended" would hide;
                    # alone on it, so that the app's last frame does not look alive
                    await self.remote_write_bytes(f"{CLEAR}{note}\r\n".encode())
                else:
                    await self.remote_close()
            except ConnectionError:
                pass  # the tab has closed

        async def send_bytes(self, data: bytes) -> bool:
            return not self.ended.is_set() and await super().send_bytes(data)

        async def send_meta(self, data: dict) -> bool:
            return not self.ended.is_set() and await super().send_meta(data)

        async def stop(self) -> None:
            # Stopped once, whoever asks first (the tab closing, the time limit, the server
            # stopping): the others wait for the same.
            if self._stopping is None:
                self._stopping = asyncio.ensure_future(self._stop())
            await asyncio.shield(self._stopping)

        async def _stop(self) -> None:
            if self._time_limit is not None:
                self._time_limit.cancel()
            # textual-serve asks the app to quit and waits for its output to end; a process
            # that does not end (stuck in a long render) is killed, so none outlives its tab.
            try:
                await asyncio.wait_for(super().stop(), QUIT_GRACE)
            except asyncio.TimeoutError:
                pass
            process = self._process
            if process is not None and process.returncode is None:
                process.kill()
                await process.wait()

    class ClassServer(server.Server):
        watching: asyncio.Task | None = None

        def __init__(self, *args: Any, **options: Any) -> None:
            super().__init__(*args, **options)
            self.visits: set[Visit] = set()  # every open page's
            self.pages: dict[str, float] = {}
            """Each page's token, waiting for its websocket, and when it was made."""
            self.folders: dict[str, Path] = {}
            """Each visitor's folder by its page's token, while the visitor is there."""

        @property
        def visitors(self) -> int:
            """The visitors whose apps run: a page left open after its app ended holds no
            place."""
            return sum(not visit.ended.is_set() for visit in self.visits)

        async def _make_app(self) -> web.Application:
            app = await super()._make_app()
            app.add_routes([web.get("/ws/{token}", self.handle_websocket),
                            web.post("/upload/{token}", self.handle_upload)])
            return app

        async def on_startup(self, app: web.Application) -> None:
            address = f"[{host}]" if ":" in host else host
            self.say(f"biceps: serving {config.name} at http://{address}:{port}/ to at most "
                     f"{max_visitors} visitors at once, each for {limits.minutes:g} minutes "
                     f"with {limits.memory} MB of memory; ctrl+c stops")
            if zygote is not None:
                self.watching = asyncio.create_task(self.watch(zygote))

        def say(self, line: str) -> None:
            self.console.print(line, highlight=False, markup=False, soft_wrap=True)

        async def watch(self, zygote: subprocess.Popen) -> None:
            while zygote.poll() is None:
                await asyncio.sleep(1.0)
            self.say(f"biceps: the process visitors' apps are forked from has ended (exit "
                     f"status {zygote.returncode}): each visitor's app now starts on its own, "
                     "which takes longer")

        async def on_shutdown(self, app: web.Application) -> None:
            # Every visitor's app asked to quit at once, rather than one tab after another.
            for visit in self.visits:
                visit.note = "The server has stopped."
            await asyncio.gather(*(visit.stop() for visit in list(self.visits)))

        async def handle_index(self, request: web.Request) -> web.StreamResponse:
            if self.visitors >= max_visitors:
                return web.Response(status=503, content_type="text/html",
                                    text=FULL_PAGE.format(limit=max_visitors))
            # The page's links are made from the address the browser used, not from the host
            # the server binds to: 0.0.0.0 is no address a browser can reach.
            origin = f"{request.scheme}://{request.host}"
            scheme = "wss" if request.scheme == "https" else "ws"
            token = self._new_page()
            context = {
                "font_size": server.to_int(request.query.get("fontsize", "16"), 16),
                "app_websocket_url": f"{scheme}://{request.host}/ws/{token}",
                "upload_url": f"{origin}/upload/{token}",
                "largest_upload": LARGEST_FILE,
                "config": {"static": {"url": f"{origin}/static/"}},
                "application": {"name": self.title},
            }
            return aiohttp_jinja2.render_template("app_index.html", request, context)

        def _new_page(self) -> str:
            """A token for a new page, after forgetting those whose websockets never came."""
            now = time.monotonic()
            for token, made in list(self.pages.items()):
                if now - made > PAGE_LIFE or len(self.pages) >= MOST_PAGES:
                    del self.pages[token]  # the oldest first: a dict keeps its order
            token = secrets.token_urlsafe(32)
            self.pages[token] = now
            return token

        async def handle_upload(self, request: web.Request) -> web.Response:
            folder = self.folders.get(request.match_info["token"])
            if folder is None:
                return web.Response(status=403, text="Not uploaded: this page's visit has "
                                    "ended, or never began; reload the page")
            try:
                name = uploads.upload_name(unquote(request.headers.get("X-File-Name", "")))
                uploads.check_size(request.content_length or 0)
                data = await _read_at_most(request.content, LARGEST_FILE)
                replaced = await asyncio.to_thread(uploads.save_upload, folder, name, data)
            except uploads.UploadRefused as refusal:
                return web.Response(status=refusal.status, text=f"Not uploaded: {refusal}")
            except OSError as error:  # the folder gone with its visitor, the disk full
                return web.Response(status=500, text=f"Not uploaded: {error.strerror or error}")
            earlier = ", replacing the earlier one" if replaced else ""
            return web.Response(text=f"{printable(name)} is in your folder{earlier}: open it "
                                "in the app with ctrl+o")

        async def handle_websocket(self, request: web.Request) -> web.WebSocketResponse:
            websocket = web.WebSocketResponse(heartbeat=15)
            await websocket.prepare(request)
            if self.visitors >= max_visitors:  # two pages opened at once for the last place
                return await _turn_away(
                    websocket, f"biceps is full: all {max_visitors} places are taken.")
            token = request.match_info.get("token")
            if token is not None and self.pages.pop(token, None) is None:
                return await _turn_away(websocket, "This page is out of date: reload it.")
            folder = Path(tempfile.mkdtemp(prefix="visitor-", dir=scratch))
            width = server.to_int(request.query.get("width", "80"), 80)
            height = server.to_int(request.query.get("height", "24"), 24)
            if token is not None:
                self.folders[token] = folder
            visit = Visit(visit_command(config, scratch, limits, folder),
                          write_bytes=websocket.send_bytes, write_str=websocket.send_str,
                          close=websocket.close, download_manager=self.download_manager,
                          debug=self.debug)
            self.visits.add(visit)  # its place taken before anything is awaited
            try:
                await visit.start(width, height)
                await self._process_messages(websocket, visit)
            except asyncio.CancelledError:
                await websocket.close()
            except Exception as error:  # one visitor's fault must not stop the server
                server.log.exception(error)
            finally:
                # Its place is free as the tab closes, not once its app has ended.
                self.visits.discard(visit)
                self.folders.pop(token, None)
                await visit.stop()
                shutil.rmtree(folder, ignore_errors=True)  # a killed process left it
            return websocket

    return ClassServer(visit_command(config, scratch, limits), host=host, port=port,
                       title=f"biceps: {config.stem}", templates_path=PAGE)


def serve(config: Path, host: str, port: int, max_visitors: int, limits: Limits) -> None:
    """Serve the app on ``config`` at ``host``:``port`` until ctrl+c; raises BicepsError if
    textual-serve is missing."""
    server = textual_serve()
    scratch = Path(tempfile.mkdtemp(prefix="biceps-serve-"))
    # The environment textual-serve gives each visitor's process, less its terminal size.
    environment = server.AppService._build_environment(SimpleNamespace(debug=False))
    zygote = start_zygote(config, scratch, environment)
    try:
        make_server(config, host, port, max_visitors, scratch, limits, zygote).serve()
    except OSError as error:  # the port taken, the address not this machine's
        raise BicepsError(f"cannot serve on {host}:{port}: {error.strerror or error}") from None
    finally:
        stop_zygote(zygote)
        shutil.rmtree(scratch, ignore_errors=True)
