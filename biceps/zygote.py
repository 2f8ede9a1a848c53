"""Visitors' processes forked from one preloaded process, under ``biceps serve``.

Every visitor's app needs Python, Textual, numpy and numba imported and a frame's kernels
loaded from numba's cache before its first picture; ten visitors arriving at once each paid
that on two cores. So the server starts one process, the zygote (:func:`zygote`), that does
it once and then only waits; each visitor's process is a fork of it, which has it all.

textual-serve still starts one process a visitor and talks to it through its pipes: a small
one (:func:`visit`, ``python -m biceps.zygote SOCKET ARGS...``, the standard library only)
that hands its stdin, stdout and stderr over the zygote's Unix socket with the command's
arguments, its environment and its folder. The zygote forks a child which takes those pipes
as its own and runs ``biceps ARGS...`` (the ``visit`` command) as the cold process would;
the small process stays as textual-serve's child, passing on SIGINT, SIGTERM and SIGHUP to
the child and ending with its exit status. If it ends first (killed), the zygote kills the
child. Where there is no zygote to answer (it failed or was stopped), the small process
becomes the cold one (``python -m biceps ARGS...``), so a visitor always gets the app.

The zygote runs no event loop and no thread, so that a fork is safe (a fork copies only the
calling thread; a lock another held would stay held in the child): it loads the kernels in
this process, without the forked helpers of ``engine/coldstart.py``, and never draws a frame
with the band pool (``engine/raster/bands.py``), which starts its threads on first use.
"""

from __future__ import annotations

import json
import os
import select
import selectors
import signal
import socket
import sys

PASSED_ON = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
"""Signals the small process passes on to the visitor's process it stands for."""
ZYGOTE_NAME = "biceps-zygote"
VISITOR_NAME = "biceps-visitor"
"""Process names (ps, pgrep) of the zygote and of the visitors' processes forked from it."""
LARGEST_REQUEST = 1 << 20
"""Bytes of a visitor's request (its arguments, environment and folder) at most."""


def visit(socket_path: str, arguments: list[str]) -> None:
    """Run ``biceps ARGUMENTS`` in a child of the zygote listening at ``socket_path``, with
    this process's stdin, stdout, stderr, environment and folder, and exit as it does;
    where no zygote answers, become ``python -m biceps ARGUMENTS`` instead.

    Started by the server itself (``exec`` in textual-serve's shell command), it ends with
    the server, however that ends, and the child with it."""
    server = _end_with_the_parent()
    try:
        connection = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        connection.connect(socket_path)
        request = json.dumps({"arguments": arguments, "environment": dict(os.environ),
                              "folder": os.getcwd()}).encode()
        socket.send_fds(connection, [request], [0, 1, 2])
        answer = connection.recv(64)  # the child's process id, once it is forked
    except OSError:
        answer = b""
    if not answer:
        if os.getppid() != server:  # the server ended (and the zygote with it)
            sys.exit(1)
        os.execv(sys.executable, [sys.executable, "-m", "biceps", *arguments])
    child = int(answer)
    for number in PASSED_ON:
        signal.signal(number, lambda number, _frame: _signal(child, number))
    status = connection.recv(64)  # the child's exit status, once the zygote has reaped it
    if not status:  # the zygote ended first: wait for the child ourselves
        _wait_for(child)
        sys.exit(1)
    code = int(status)
    sys.exit(128 - code if code < 0 else code)  # as a shell reports a signal


def _signal(pid: int, number: int) -> None:
    try:
        os.kill(pid, number)
    except ProcessLookupError:
        pass


def _wait_for(pid: int) -> None:
    """Return once ``pid``, not this process's child, has ended."""
    try:
        handle = os.pidfd_open(pid)
    except ProcessLookupError:
        return
    select.select([handle], [], [])
    os.close(handle)


def zygote(listening: socket.socket, config: str) -> None:
    """Preload the app for ``config`` and then fork a visitor's process for each request
    on ``listening``, until SIGTERM or the server's end, which end the children too."""
    _end_with_the_parent()
    _name_this_process(ZYGOTE_NAME)
    _preload(config)
    # What exists now is shared with every child: left out of collections, so that the
    # collector does not write to those pages and copy them into every child.
    import gc

    gc.collect()
    gc.freeze()
    signal.signal(signal.SIGTERM, lambda _number, _frame: sys.exit(0))
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the server stops visitors, then this
    watched = selectors.DefaultSelector()
    watched.register(listening, selectors.EVENT_READ)
    children: dict[int, tuple[int, socket.socket]] = {}  # pidfd: (pid, its small process)
    started: dict[socket.socket, int] = {}  # a small process: its child's pid
    connections: set[socket.socket] = set()  # every small process's, until closed
    try:
        while True:
            for key, _events in watched.select():
                if key.fileobj is listening:
                    connection, _address = listening.accept()
                    connections.add(connection)
                    watched.register(connection, selectors.EVENT_READ)
                elif key.data == "child":  # a child ended: tell its small process how
                    pid, connection = children.pop(key.fd)
                    watched.unregister(key.fd)
                    os.close(key.fd)
                    _tell(connection, os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]))
                    if started.pop(connection, None) is not None:
                        watched.unregister(connection)
                    connections.discard(connection)
                    connection.close()
                elif key.fileobj in started:  # its small process ended first (killed)
                    _signal(started.pop(key.fileobj), signal.SIGKILL)
                    watched.unregister(key.fileobj)  # closed once the child is reaped
                else:
                    pid = _fork(key.fileobj, [listening, watched, *connections], children)
                    if pid is None:
                        watched.unregister(key.fileobj)
                        connections.discard(key.fileobj)
                        key.fileobj.close()
                        continue
                    handle = os.pidfd_open(pid)
                    children[handle] = (pid, key.fileobj)
                    started[key.fileobj] = pid
                    watched.register(handle, selectors.EVENT_READ, data="child")
                    _tell(key.fileobj, pid)
    finally:
        for pid, _connection in children.values():
            _signal(pid, signal.SIGKILL)


def _fork(connection: socket.socket, inherited: list, children: dict) -> int | None:
    """Fork a child for the request on ``connection`` and return its pid; None if there
    is no whole request (the small process ended before sending it)."""
    try:
        request, fds, _flags, _address = socket.recv_fds(connection, LARGEST_REQUEST, 3)
    except OSError:
        request, fds = b"", []
    if not request or len(fds) != 3:
        for fd in fds:
            os.close(fd)
        return None
    pid = os.fork()
    if pid == 0:
        _become_visitor(request, fds, inherited, list(children))  # never returns
    for fd in fds:
        os.close(fd)
    return pid


def _tell(connection: socket.socket, number: int) -> None:
    try:
        connection.send(str(number).encode())
    except OSError:
        pass  # the small process has gone: nobody to tell


def _become_visitor(request: bytes, fds: list[int], inherited: list, handles: list[int]) -> None:
    """In the forked child: take the visitor's pipes, environment and folder, and run the
    command it asked for; exit with its status, never returning into the zygote's loop.
    ``inherited``: the zygote's sockets and selector, and ``handles``, the other children's
    pidfds, none of which stays open here."""
    status = 1
    try:
        for held in inherited:
            held.close()
        for handle in handles:
            os.close(handle)
        asked = json.loads(request)
        os.setsid()  # the server's terminal's ctrl+c reaches the server, which ends this
        _name_this_process(VISITOR_NAME)
        for number, fd in enumerate(fds):
            os.dup2(fd, number)
            os.close(fd)
        for number in (signal.SIGTERM, signal.SIGINT):
            signal.signal(number, signal.SIG_DFL)
        os.environ.clear()
        os.environ.update(asked["environment"])
        os.chdir(asked["folder"])
        from biceps.cli import main

        main(args=asked["arguments"], prog_name="biceps")
        status = 0
    except SystemExit as leaving:  # as Python ends on it
        status = leaving.code if isinstance(leaving.code, int) else leaving.code is not None
        if isinstance(leaving.code, str):
            print(leaving.code, file=sys.stderr)
    except BaseException:
        import traceback

        traceback.print_exc()
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(status)


def _name_this_process(name: str) -> None:
    """Name this process as ps and pgrep show it (not its command line, the zygote's)."""
    import ctypes

    PR_SET_NAME = 15
    ctypes.CDLL(None).prctl(PR_SET_NAME, name.encode())


def _end_with_the_parent() -> int:
    """Have the kernel send SIGTERM to this process (kept across an exec) when its parent,
    the server, ends, however it ends; return the parent's pid."""
    import ctypes

    PR_SET_PDEATHSIG = 1
    parent = os.getppid()
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    if parent == 1 or os.getppid() != parent:  # the server ended before the line above
        sys.exit(1)
    return parent


def _preload(config: str) -> None:
    """Import what a visitor's app imports, build ``config``'s model and draw a small
    picture of it through the half-block encoder, so that every kernel of a frame is
    loaded from numba's cache (compiled into it if it is cold); without starting a thread:
    drawn with one drawing thread, this one."""
    import threading

    import biceps.cli  # noqa: F401
    import biceps.tui.app  # noqa: F401
    import textual.drivers.web_driver  # noqa: F401
    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene
    from biceps.engine.scene_renderer import SceneRenderer
    from biceps.tui.pixels import HalfBlocks
    from biceps.tui.sgr import minimized

    asked = os.environ.get("BICEPS_THREADS")
    os.environ["BICEPS_THREADS"] = "1"  # every stage on this thread, even a large mesh's
    try:
        with SceneRenderer() as renderer:
            HalfBlocks().encode(renderer.render(Scene.of(load_config(config)), 8, 8))
    finally:
        os.environ.pop("BICEPS_THREADS")
        if asked is not None:
            os.environ["BICEPS_THREADS"] = asked
    minimized("\x1b[1m \x1b[0m")  # the output minimizer's kernel
    if threading.active_count() > 1:
        raise RuntimeError("a thread started while preloading; a fork would not be safe")


if __name__ == "__main__":
    if sys.argv[1] == "--zygote":  # python -m biceps.zygote --zygote FD CONFIG
        zygote(socket.socket(fileno=int(sys.argv[2])), sys.argv[3])
    else:  # python -m biceps.zygote SOCKET ARGS...
        visit(sys.argv[1], sys.argv[2:])
