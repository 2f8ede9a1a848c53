"""A storm of what a terminal sends, for the real app in a raw pseudo-terminal or in tmux:
keys, pastes holding control characters, bytes that are not UTF-8, broken escape sequences,
mouse reports and resizes, at random (seeded) and at any rate; then the app is ended as a
person ends it (escape, q, and no to saving), and asked how it ended.

The storm leaves out the keys that end the app (q, ctrl+q) and those that save the model
(ctrl+s, ctrl+d), so that a run lasts and the model file is left as it was; every other
key is in, ctrl+\\, ctrl+z and ctrl+c among them, which a terminal turns into signals
wherever the app has not turned that off.
"""

from __future__ import annotations

import collections
import fcntl
import os
import random
import re
import select
import shutil
import signal
import subprocess
import sys
import termios
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator, Protocol

from pty_app import DEVICE_ATTRIBUTES_ANSWER, DEVICE_ATTRIBUTES_QUERY, app_environment, set_size

ESC = b"\x1b"
# What a person does with this app, as the bytes a terminal sends for it; the signal keys.
KEYS = [
    b"c", b"C", b"x", b"X", b"c", b"x",
    ESC + b"[A", ESC + b"[B", ESC + b"[C", ESC + b"[D", ESC + b"[1;2A", ESC + b"[1;2D",
    b"[", b"]", b"w", b"a", b"s", b"d", b"+", b"-", b"=", b"j", b"l", b"i", b"k", b"u", b"o",
    b"r", b"g", b"m", b"e", b"?", ESC + b"OP", b"\x0f", b"\x10", b"\x12", b"\x19", b"\t",
    ESC + b"[Z", b"\r", b"\r", ESC, ESC, b"\x7f", ESC + b"[3~", ESC + b"[2~", b"n", b"/",
    ESC + b"[5~", ESC + b"[6~", ESC + b"[H", ESC + b"[F", b"y", b"t", b"T", b"b", b"p", b"v",
    b"h", b"f", b"0", b"1", b"5", b".", b" ", ESC + b"[I", ESC + b"[O",
    b"\x1a", b"\x1c", b"\x03",  # ctrl+z (undo), ctrl+\, ctrl+c
]
NOT_UTF8 = [b"\xff", b"\xc3a", b"\xe2\x82", b"\x80", b"\xf0\x9f\x92", b"\xed\xa0\x80"]
PASTED = "aé/ .~\t\n\r\x00\x07\x1b[]{}\x7f\x9b\u202e\U0001f4aa\udcffq\x11\x13"
# Bytes left out of everything but pastes (a paste is text, never a key): q and ctrl+q end
# the app, ctrl+s and ctrl+d save it; u ends a Kitty key sequence, which may spell one.
LEFT_OUT = re.compile(rb"[q\x11\x13\x04u]")
KINDS = ("key", "not UTF-8", "bytes", "broken sequence", "mouse", "paste", "resize")


def storm_inputs(seed: int) -> Iterator[tuple[str, bytes | tuple[int, int]]]:
    """For ever, what a terminal sends, drawn from ``seed``: (kind, bytes), or ("resize",
    (columns, rows))."""
    rng = random.Random(seed)
    while True:
        kind = rng.random()
        if kind < 0.70:
            yield "key", rng.choice(KEYS)
        elif kind < 0.75:
            yield "not UTF-8", rng.choice(NOT_UTF8)
        elif kind < 0.80:  # anything at all
            yield "bytes", LEFT_OUT.sub(b"", rng.randbytes(rng.randint(1, 6))) or b"x"
        elif kind < 0.85:  # a sequence broken off, or nonsense after its start
            yield "broken sequence", ESC + b"[" + LEFT_OUT.sub(b"", rng.randbytes(
                rng.randint(0, 6)))
        elif kind < 0.94:  # buttons, moves, drags, the wheel: anywhere, off the window too
            button = rng.choice([0, 1, 2, 32, 34, 35, 64, 65])
            x, y = rng.randint(1, 200), rng.randint(1, 60)
            yield "mouse", ESC + f"[<{button};{x};{y}{rng.choice('Mm')}".encode()
        elif kind < 0.985:
            text = "".join(rng.choice(PASTED) for _ in range(rng.randint(0, 40)))
            if rng.random() < 0.05:
                text *= 2_000  # a long one: every key after must not slow down
            yield "paste", ESC + b"[200~" + text.encode("utf-8", "surrogatepass") + ESC + b"[201~"
        else:
            yield "resize", (rng.choice([1, 2, 20, 40, 80, 100, 160, 250]),
                             rng.choice([1, 3, 10, 24, 30, 60]))


class Terminal(Protocol):
    """Where the app runs: started on a command, typed to, resized, asked how it ended."""

    def type(self, data: bytes) -> None: ...
    def resize(self, columns: int, rows: int) -> None: ...
    def running(self) -> bool: ...
    def exit_status(self) -> int | None: ...
    def mark(self) -> int: ...
    def shown(self, since: int = 0) -> str:
        """What it has shown since :meth:`mark` gave ``since`` (a pseudo-terminal: what the
        app wrote; tmux: its window as it is now)."""
    def close(self) -> None: ...


WRITE_PATIENCE = 30.0


class RawTerminal(Terminal):
    """A pseudo-terminal the app has as its controlling terminal, as a shell gives its jobs
    (so that ctrl+c, ctrl+\\ and ctrl+z are signals while its mode says so), read all along,
    answering the questions a terminal answers (device attributes, the cursor's place)."""

    def __init__(self, command: list[str], cwd: Path, size: tuple[int, int]) -> None:
        self.master, slave = os.openpty()
        set_size(slave, *size)

        def controlling() -> None:
            os.setsid()
            fcntl.ioctl(0, termios.TIOCSCTTY, 0)

        self.process = subprocess.Popen(command, stdin=slave, stdout=slave, stderr=slave,
                                        cwd=cwd, env=app_environment(),
                                        preexec_fn=controlling)
        os.close(slave)
        os.set_blocking(self.master, False)  # see type()
        self._output: collections.deque[bytes] = collections.deque(maxlen=4096)
        self._written = 0  # bytes read from the app, all along
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        tail = b""
        while True:
            try:
                ready = select.select([self.master], [], [], 0.2)[0]
                if not ready:
                    if self.process.poll() is not None:
                        return
                    continue
                chunk = os.read(self.master, 1 << 16)
            except OSError:  # the other side has closed
                return
            if not chunk:
                return
            with self._lock:
                self._output.append(chunk)
                self._written += len(chunk)
            seen = tail + chunk
            answers = DEVICE_ATTRIBUTES_ANSWER * seen.count(DEVICE_ATTRIBUTES_QUERY)
            answers += b"".join(b"\x1b[1;%sR" % column
                                for column in re.findall(rb"\x1b\[1;(\d+)H\x1b\[6n", seen))
            if answers:
                self.type(answers)
            tail = seen[-16:]

    def type(self, data: bytes) -> None:
        # As a terminal does when the app stops reading: what it cannot take within
        # WRITE_PATIENCE seconds is lost (a blocking write would wait for ever).
        deadline = time.monotonic() + WRITE_PATIENCE
        while data and (left := deadline - time.monotonic()) > 0:
            try:
                if select.select([], [self.master], [], left)[1]:
                    data = data[os.write(self.master, data):]
            except BlockingIOError:  # room for less than a write's worth: again
                continue
            except OSError:  # gone
                return

    def resize(self, columns: int, rows: int) -> None:
        set_size(self.master, columns, rows)

    def running(self) -> bool:
        return self.process.poll() is None

    def exit_status(self) -> int | None:
        return self.process.poll()

    def mark(self) -> int:
        with self._lock:
            return self._written

    def shown(self, since: int = 0) -> str:
        with self._lock:
            kept = b"".join(self._output)
            new = self._written - since
        return kept[-new:].decode("utf-8", "replace") if new > 0 else ""

    def close(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self._reader.join(timeout=5)
        os.close(self.master)


class TmuxTerminal(Terminal):
    """A window of a tmux server of its own, on the socket ``cwd/tmux`` (``tmux -S``); the
    app's exit status is written to a file by the shell that runs it."""

    def __init__(self, command: list[str], cwd: Path, size: tuple[int, int]) -> None:
        self._tmux = ["tmux", "-S", str(cwd / "tmux")]
        self._status = cwd / "exit-status"
        shell = " ".join(_quoted(part) for part in command)
        subprocess.run([*self._tmux, "-f", "/dev/null", "new-session", "-d", "-s", "storm",
                        "-x", str(size[0]), "-y", str(size[1]), "-c", str(cwd),
                        # The shell stays after the app so that what it printed last (an
                        # error's traceback) can still be read from the window.
                        f"{shell}; echo $? > {_quoted(str(self._status))}; sleep 600"],
                       check=True,
                       env={**os.environ, "TERM": "xterm-256color"})

    def type(self, data: bytes) -> None:
        if len(data) <= 256:  # as keys, a byte each
            subprocess.run([*self._tmux, "send-keys", "-t", "storm", "-H",
                            *(f"{byte:02x}" for byte in data)], capture_output=True)
            return
        # More at once (a long paste among them) as a buffer, its bytes as they are (-r):
        # a byte each, send-keys takes minutes over 80,000.
        subprocess.run([*self._tmux, "load-buffer", "-b", "storm", "-"], input=data,
                       capture_output=True)
        subprocess.run([*self._tmux, "paste-buffer", "-d", "-r", "-b", "storm", "-t", "storm"],
                       capture_output=True)

    def resize(self, columns: int, rows: int) -> None:
        subprocess.run([*self._tmux, "resize-window", "-t", "storm", "-x", str(columns), "-y",
                        str(rows)], capture_output=True)

    def running(self) -> bool:
        return not self._status.exists()

    def exit_status(self) -> int | None:
        try:
            return int(self._status.read_text())
        except (OSError, ValueError):
            return None

    def mark(self) -> int:
        return 0

    def shown(self, since: int = 0) -> str:
        return subprocess.run([*self._tmux, "capture-pane", "-p", "-S", "-200", "-t", "storm"],
                              capture_output=True, text=True).stdout

    def close(self) -> None:
        subprocess.run([*self._tmux, "kill-server"], capture_output=True)


def _quoted(text: str) -> str:
    return "'" + text.replace("'", "'\\''") + "'"


@dataclass
class Outcome:
    """How a storm went: what was sent, whether the app lived through it, how it ended."""

    sent: collections.Counter = field(default_factory=collections.Counter)
    alive_after: bool = False
    exit_status: int | None = None
    quit_seconds: float | None = None
    model_untouched: bool = False
    quits_held: int = 0  # quits asked for during the storm (the palette's, the footer's)
    shown_at_the_end: str = ""
    stacks: str = ""  # every thread's stack of an app that did not quit, as it was then

    @property
    def passed(self) -> bool:
        return self.alive_after and self.exit_status == 0 and self.model_untouched


def wait_for(terminal: Terminal, text: str, seconds: float, since: int = 0) -> bool:
    """Whether ``terminal`` shows ``text`` (since its mark ``since``) within ``seconds``."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if text in terminal.shown(since):
            return True
        if not terminal.running():
            return False
        time.sleep(0.2)
    return False


def storm(terminal: Terminal, seconds: float, seed: int, sent: collections.Counter) -> None:
    """``seconds`` of :func:`storm_inputs`: bursts of 1 to 60 inputs, with pauses of up to a
    tenth of a second, or none, between them."""
    rng = random.Random(seed + 1)
    inputs = storm_inputs(seed)
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and terminal.running():
        burst = bytearray()
        for _ in range(rng.randint(1, 60)):
            kind, data = next(inputs)
            sent[kind] += 1
            if kind == "resize":
                terminal.type(bytes(burst))
                burst.clear()
                terminal.resize(*data)
            else:
                burst += data
        terminal.type(bytes(burst))
        time.sleep(rng.choice([0.0, 0.0, 0.01, 0.05, 0.1]))


def quit_app(terminal: Terminal, size: tuple[int, int], attempts: int = 8) -> float | None:
    """End the app as a person does: back to a window of its size, escape out of whatever is
    open, q, and "n" (don't save) if it asks; again if nothing comes of it (input the app
    was too far behind to answer is left out: tui/behind.py). The seconds it took, or None
    if it did not end."""
    start = time.monotonic()
    terminal.resize(*size)
    for _ in range(attempts):
        for _ in range(3):
            terminal.type(ESC)
            time.sleep(0.3)
        mark = terminal.mark()
        terminal.type(b"q")
        answered = False
        deadline = time.monotonic() + 8.0
        while time.monotonic() < deadline:
            if not terminal.running():
                return time.monotonic() - start
            if not answered and "nsaved edits" in terminal.shown(mark):  # title, or text
                terminal.type(b"n")
                answered = True
                deadline = time.monotonic() + 20.0  # for it to end
            time.sleep(0.2)
    return None


# The app as installed, with each request to quit and each exit logged, with its stack, to
# the file named first. The storm leaves out the keys that quit, but the palette's "Quit the
# application" and a click on the footer's ask for a quit too: while the file named second
# exists (the storm is on), such a request is logged and held, not done, as the fuzz test
# counts it; an exit that comes another way (a fault) still ends the app. On SIGUSR1 it
# writes every thread's stack to STACKS beside the log, and its process id is in PID there.
STACKS, PID = "stacks.txt", "pid"
QUITS_LOGGED = f"""
import faulthandler, os, signal, sys, traceback
from biceps.cli import run
from biceps.tui.app import BicepsApp

log, storming = sys.argv.pop(1), sys.argv.pop(1)
folder = os.path.dirname(log)
stacks = open(os.path.join(folder, "{STACKS}"), "w")
faulthandler.register(signal.SIGUSR1, file=stacks, all_threads=True)
with open(os.path.join(folder, "{PID}"), "w") as pid:
    pid.write(str(os.getpid()))

def logged(method, hold=False):
    def logging(*args, **kwargs):
        held = hold and os.path.exists(storming)
        with open(log, "a") as out:
            out.write(f"{{method.__name__}}{{' (held: the storm is on)' if held else ''}}:\\n"
                      + "".join(traceback.format_stack()) + "\\n")
        return None if held else method(*args, **kwargs)
    return logging

BicepsApp.action_quit = logged(BicepsApp.action_quit, hold=True)
BicepsApp.action_quit_in_turn = logged(BicepsApp.action_quit_in_turn, hold=True)
BicepsApp.exit = logged(BicepsApp.exit)
sys.argv[0] = "biceps"
run()
"""


def _stacks(folder: Path) -> str:
    """Every thread's stack of the app started in ``folder``, as it is now."""
    try:
        os.kill(int((folder / PID).read_text()), signal.SIGUSR1)
    except (OSError, ValueError) as error:
        return f"no stacks: {error}"
    time.sleep(1.0)  # written by the app's signal handler
    return (folder / STACKS).read_text()


def run_storm(harness: str, model: Path, folder: Path, seconds: float, seed: int,
              size: tuple[int, int] = (100, 30)) -> Outcome:
    """The app on a copy of ``model`` in ``folder``, in ``harness`` ("pty" or "tmux"), given
    ``seconds`` of storm from ``seed``, then quit (see the module)."""
    copy = folder / model.name
    shutil.copy(model, copy)
    before = copy.read_bytes()
    storming = folder / "storming"
    command = [sys.executable, "-c", QUITS_LOGGED, str(folder / "quits.txt"), str(storming),
               "app", str(copy)]
    terminal = (RawTerminal(command, folder, size) if harness == "pty"
                else TmuxTerminal(command, folder, size))
    outcome = Outcome()
    try:
        if not wait_for(terminal, "\u2580", 180.0):  # its first picture
            outcome.shown_at_the_end = terminal.shown()[-3000:]
            return outcome
        storming.touch()
        storm(terminal, seconds, seed, outcome.sent)
        storming.unlink()
        outcome.alive_after = terminal.running()
        if outcome.alive_after:
            outcome.quit_seconds = quit_app(terminal, size)
            if outcome.quit_seconds is None:
                outcome.stacks = _stacks(folder)
        deadline = time.monotonic() + 10
        while terminal.exit_status() is None and time.monotonic() < deadline:
            time.sleep(0.2)
        outcome.exit_status = terminal.exit_status()
        shown = terminal.shown()
        outcome.shown_at_the_end = shown[-3000:]  # an error's last words, if any
        (folder / "shown.txt").write_text(shown)  # all of them: a traceback is longer
    finally:
        terminal.close()
    outcome.model_untouched = copy.read_bytes() == before
    log = folder / "quits.txt"
    outcome.quits_held = log.read_text().count("(held: ") if log.exists() else 0
    return outcome
