"""``biceps serve``: the app in a browser tab, one process a visitor, through textual-serve.

Each visitor who opens the page gets a process of its own (``biceps visit``) running the app
under Textual's web driver, in a scratch folder of its own under the server's, which is
removed when the visitor leaves. The page's websocket is that process's terminal; closing
the tab ends it. At most ``max_visitors`` at once: the next is shown a page saying so.

textual-serve is an optional extra (``pip install 'biceps[serve]'``); this module imports it
only when the server starts.
"""

from __future__ import annotations

import asyncio
import shlex
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any

from biceps.engine.errors import BicepsError

EXTRA = "serve"
LOCAL_HOSTS = ("localhost", "127.0.0.1", "::1")
QUIT_GRACE = 5.0
"""Seconds a visitor's process has to end after its tab closed before it is killed."""

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


def visit_command(config: Path, scratch: Path) -> str:
    """The shell command textual-serve runs for each visitor."""
    return shlex.join([sys.executable, "-m", "biceps", "visit", str(config),
                       "--scratch", str(scratch)])


def make_server(config: Path, host: str, port: int, max_visitors: int, scratch: Path) -> Any:
    """A textual-serve Server for ``config`` (see :func:`serve`)."""
    server = textual_serve()
    from aiohttp import web
    import aiohttp_jinja2

    class Visit(server.AppService):
        async def stop(self) -> None:
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
        visitors = 0

        async def on_startup(self, app: web.Application) -> None:
            address = f"[{host}]" if ":" in host else host
            self.console.print(f"biceps: serving {config.name} at http://{address}:{port}/ to "
                               f"at most {max_visitors} visitors at once; ctrl+c stops",
                               highlight=False, markup=False)

        async def handle_index(self, request: web.Request) -> web.StreamResponse:
            if self.visitors >= max_visitors:
                return web.Response(status=503, content_type="text/html",
                                    text=FULL_PAGE.format(limit=max_visitors))
            # The page's links are made from the address the browser used, not from the host
            # the server binds to: 0.0.0.0 is no address a browser can reach.
            origin = f"{request.scheme}://{request.host}"
            scheme = "wss" if request.scheme == "https" else "ws"
            context = {
                "font_size": server.to_int(request.query.get("fontsize", "16"), 16),
                "app_websocket_url": f"{scheme}://{request.host}/ws",
                "config": {"static": {"url": f"{origin}/static/"}},
                "application": {"name": self.title},
            }
            return aiohttp_jinja2.render_template("app_index.html", request, context)

        async def handle_websocket(self, request: web.Request) -> web.WebSocketResponse:
            websocket = web.WebSocketResponse(heartbeat=15)
            await websocket.prepare(request)
            if self.visitors >= max_visitors:  # two pages opened at once for the last place
                await websocket.send_bytes(
                    f"\r\nbiceps is full: all {max_visitors} places are taken.\r\n".encode())
                await websocket.close()
                return websocket
            self.visitors += 1
            width = server.to_int(request.query.get("width", "80"), 80)
            height = server.to_int(request.query.get("height", "24"), 24)
            visit = Visit(self.command, write_bytes=websocket.send_bytes,
                          write_str=websocket.send_str, close=websocket.close,
                          download_manager=self.download_manager, debug=self.debug)
            try:
                await visit.start(width, height)
                await self._process_messages(websocket, visit)
            except asyncio.CancelledError:
                await websocket.close()
            except Exception as error:  # one visitor's fault must not stop the server
                server.log.exception(error)
            finally:
                self.visitors -= 1
                await visit.stop()
            return websocket

    return ClassServer(visit_command(config, scratch), host=host, port=port,
                       title=f"biceps: {config.stem}")


def serve(config: Path, host: str, port: int, max_visitors: int) -> None:
    """Serve the app on ``config`` at ``host``:``port`` until ctrl+c; raises BicepsError if
    textual-serve is missing."""
    textual_serve()
    scratch = Path(tempfile.mkdtemp(prefix="biceps-serve-"))
    try:
        make_server(config, host, port, max_visitors, scratch).serve()
    except OSError as error:  # the port taken, the address not this machine's
        raise BicepsError(f"cannot serve on {host}:{port}: {error.strerror or error}") from None
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
