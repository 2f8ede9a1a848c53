"""The ``biceps`` command: the app by default, and headless subcommands.

``biceps [CONFIG]`` opens the terminal app; ``biceps info``, ``sweep``, ``snapshot``,
``animate`` and ``export-mesh`` work with no terminal at all. Each command imports what it
needs inside itself: Textual only for the app, numba only where a picture is rendered, PyAV
only for an MP4, and nothing heavy for ``--help``, so every command starts as fast as its
work allows.

Every deliberate refusal (a bad config, an impossible length, a file that cannot be
written) ends the process with exit code 2 and one clear message on stderr.
"""

from __future__ import annotations

import csv
import difflib
import functools
import gc
import io
import json
import math
import os
import signal
import sys
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterator, get_args

import click

from biceps.configs import (DEFAULT as DEFAULT_CONFIG, FOLDER as BUNDLED, file_or_bundled,
                            named as bundled_model)
from biceps.engine.bounds import (ACTIVATION, ANGLE, COORDINATE, MASS, SCALE, OutOfBounds,
                                  finite)
from biceps.engine.errors import BicepsError
from biceps.engine.names import printable
from biceps.engine.settings import SEGMENTS, SUPERSAMPLING, Colors, Graphics, drawing_threads

if TYPE_CHECKING:
    import numpy as np

    from biceps.engine.arm import Arm
    from biceps.engine.coldstart import Asides
    from biceps.engine.movie import Progress
    from biceps.engine.scene import Scene
    from biceps.engine.scene_renderer import SceneRenderer
    from biceps.tui.app import AppProcess


class _FiniteFloat(click.ParamType):
    """A number that is not NaN or infinite (click's float, even a FloatRange, lets them by),
    optionally within ``[low, high]``."""

    name = "number"

    def __init__(self, low: float = -math.inf, high: float = math.inf) -> None:
        self.low, self.high = low, high

    def convert(self, value: Any, param: Any, ctx: Any) -> float:
        number = click.FLOAT.convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail(f"must be a finite number, got {value!r}", param, ctx)
        if not self.low <= number <= self.high:
            self.fail(f"must be {self.low:g} to {self.high:g}, got {value!r}", param, ctx)
        return number


FINITE = _FiniteFloat()
TURN = _FiniteFloat(ANGLE.low, ANGLE.high)
ACTIVATION_RANGE = (ACTIVATION.low, ACTIVATION.high)
MASS_RANGE = (MASS.low, MASS.high)

USAGE_ERROR = 2
GRAPHICS = list(get_args(Graphics))
COLORS = list(get_args(Colors))


class _AppByDefault(click.Group):
    """A group whose bare invocation, or one naming a config, runs the ``app`` command.

    A first word that is neither a command nor a file that could be a config is taken for
    a mistyped command: ``biceps snaphsot -o x.png`` asks "did you mean 'snapshot'?"
    rather than opening the app on a file named snaphsot.
    """

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        first = args[0] if args else None
        if first is None or (first not in self.commands and first not in OWN_OPTIONS):
            if first is not None and not first.startswith("-") and _not_a_config(first):
                self._no_such_command(ctx, first)
            args = ["app", *args]
        return super().parse_args(ctx, args)

    def collect_usage_pieces(self, ctx: click.Context) -> list[str]:
        return ["[OPTIONS]", "[CONFIG | COMMAND [ARGS]...]"]

    def _no_such_command(self, ctx: click.Context, word: str) -> None:
        commands = sorted(self.commands)
        close = difflib.get_close_matches(word, commands, n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise click.UsageError(
            f"No such command or file {word!r}.{hint} Commands: {', '.join(commands)}; or "
            "give a configuration file (.toml), or a bundled model's name ("
            f"{', '.join(sorted(model.stem for model in BUNDLED.glob('*.toml')))}), to open "
            "the app on it.", ctx)


OWN_OPTIONS = ("--help", "-h", "--version")


def _not_a_config(word: str) -> bool:
    """Whether ``word`` cannot be meant as a configuration file: no such file or folder,
    not a bundled model's name, and not a name ending in .toml (whose absence the app's own
    message explains)."""
    try:
        return not (word.lower().endswith(".toml") or Path(word).exists()
                    or bundled_model(word) is not None)
    except OSError:  # a name too long to look up, say: the app's reader says why in words
        return False


INTERRUPTED = 130
"""The exit status after ctrl+c: 128 and SIGINT's number, as a shell reports a program it
interrupted."""

READER_GONE = 141
"""The exit status when the program reading stdout stopped reading (``| head -1``): 128 and
SIGPIPE's number, as a shell reports any program that signal ends."""


def _refusals_exit_2(command: Callable) -> Callable:
    """Turn a :class:`BicepsError` into its message on stderr and exit code 2, and ctrl+c
    into a line saying so and exit code 130 (files are written whole or not at all)."""

    @functools.wraps(command)
    def run(*args: Any, **kwargs: Any) -> Any:
        try:
            return command(*args, **kwargs)
        except BicepsError as error:
            _say(f"biceps: {error}")
            sys.exit(USAGE_ERROR)
        except KeyboardInterrupt:
            if _own_process():  # a second ctrl+c must not cut this short
                signal.signal(signal.SIGINT, signal.SIG_IGN)
            _say("\nbiceps: interrupted; no file was written")
            sys.exit(INTERRUPTED)

    return run


def _say(line: str) -> None:
    """``line`` on stderr, if stderr can take it: a message must not become an error."""
    try:
        click.echo(line, err=True)
    except (OSError, ValueError):  # stderr closed or full: the exit status says it
        pass


def _print(text: str) -> None:
    """``text`` and a newline on stdout, all of it (see :func:`_stdout`)."""
    with _stdout() as stream:
        stream.write(text + "\n")


@contextmanager
def _stdout(half_blocks: bool = False) -> Iterator[Any]:
    """stdout, for output to be written to it whole, flushed at the end; ``half_blocks``
    for a picture made of them.

    A write that fails is an error, never a silent exit 0: stdout closed (``>&-``), or one
    that cannot take the half blocks (``PYTHONIOENCODING=ascii``), is refused (before any
    work, where the command asks :func:`_writable_stdout` first); a full device is said as
    it fails. A reader that stopped reading (``| head -c1``) ends the command quietly, with
    :data:`READER_GONE`.
    """
    stream = _writable_stdout(half_blocks)
    sys.stdout = _InPieces(stream)  # what rich and the printed pictures write to, too
    try:
        yield sys.stdout
        stream.flush()
    except OSError as error:
        _detach(stream)  # what is still buffered must not fail again as Python exits
        if isinstance(error, BrokenPipeError):
            sys.exit(READER_GONE)
        raise BicepsError(f"cannot write to stdout: {error.strerror}") from None
    except SystemExit as exit:
        if isinstance(exit.__context__, BrokenPipeError):  # rich's own way out (status 1)
            sys.exit(READER_GONE)
        raise
    finally:
        sys.stdout = stream


class _InPieces:
    """A text stream written to in pieces of at most :data:`PIECE` characters.

    Given more than its buffer at once, CPython's buffered writer loses the error of a pipe
    closed part way: the kernel takes what fits and says so, and the rest is dropped with
    no BrokenPipeError (4 MB of sweep into ``head -c1`` ended with status 0). Piece by
    piece, the write after the reader has gone raises it."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        for start in range(0, len(text), PIECE):
            self._stream.write(text[start:start + PIECE])
        return len(text)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


PIECE = io.DEFAULT_BUFFER_SIZE


def _writable_stdout(half_blocks: bool = False) -> Any:
    """stdout, unless it is closed or, for a picture of ``half_blocks``, cannot take them
    (a text's other characters it cannot take are written as escapes: see :func:`run`);
    :class:`BicepsError` then."""
    stream = sys.stdout
    if stream is None:
        raise BicepsError("stdout is closed, and this command writes there: give it a file "
                          "(> out.txt) or a pipe")
    if half_blocks:
        try:
            "\u2584".encode(stream.encoding or "ascii")
        except (UnicodeEncodeError, LookupError):
            raise BicepsError(f"stdout takes only {stream.encoding}, and the picture is made "
                              "of half blocks (U+2584): set PYTHONIOENCODING=utf-8, or write "
                              "a PNG with -o") from None
    return stream


def _detach(stream: Any) -> None:
    """Point ``stream``'s descriptor at /dev/null."""
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, stream.fileno())
        os.close(null)
    except (OSError, ValueError, io.UnsupportedOperation):  # not a file (a test's buffer)
        pass


# Plain paths: whether each is a file that can be read, or written, is for the engine to
# say (engine/files.py), in its words, with the name made printable.
config_argument = click.argument(
    "config",
    required=False,
    default=str(DEFAULT_CONFIG),
    type=click.Path(path_type=Path),
    callback=lambda _ctx, _param, path: file_or_bundled(path),
)


def pose_options(command: Callable) -> Callable:
    """``--length`` / ``--flexion``: the pose to show, instead of the config's own."""
    flexion = click.option("--flexion", type=FINITE, help="Elbow flexion in degrees (0 = straight).")
    length = click.option("--length", type=FINITE, help="Muscle length in cm.")
    return length(flexion(command))


def posed(arm: Arm, length: float | None, flexion: float | None) -> Arm:
    """``arm`` moved to the asked length or flexion, if any."""
    if length is not None and flexion is not None:
        raise click.UsageError("give --length or --flexion, not both")
    if length is not None:
        return arm.at_length(length)
    if flexion is not None:
        return arm.at_flexion(flexion)
    return arm


@click.group(cls=_AppByDefault, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="biceps", prog_name="biceps")
def main() -> None:
    """A shaded 3D biceps that contracts and stretches at exactly constant volume.

    Run with no command (or just a CONFIG) to open the terminal app; `biceps app --help`
    lists its options. CONFIG is a TOML file, or a bundled model by its name, from any
    folder: biceps (the default), elbow, fine or toy.
    """
    # Read here, before any command, so that a bad value is refused in words at the start
    # rather than raised later inside the app's picture thread.
    try:
        drawing_threads(os.environ)
    except BicepsError as error:
        _say(f"biceps: {error}")
        sys.exit(USAGE_ERROR)


@main.command(short_help="Open the terminal app (the command when none is given).")
@config_argument
@click.option(
    "--colors",
    type=click.Choice(COLORS),
    default="auto",
    show_default=True,
    help="Colour depth; auto takes the config's render.colors, TEXTUAL_COLOR_SYSTEM, then "
    "what the terminal answers (24-bit where it keeps a 24-bit colour), then COLORTERM.",
)
@click.option(
    "--fps",
    type=_FiniteFloat(0.1, 1000),
    default=None,
    help="Most frames a second, 0.1 to 1000 (default: as fast as the terminal takes them, "
    "up to Textual's 60, which TEXTUAL_FPS changes).",
)
@click.option(
    "--graphics",
    type=click.Choice(GRAPHICS),
    default=None,
    help="How the picture reaches the terminal: half-block characters, real pixels in one "
    "of three protocols, or auto, the best the terminal answers it has (default: the "
    "config's render.graphics, halfblocks). See biceps doctor.",
)
@click.option(
    "--pixel-scale",
    type=_FiniteFloat(0.1, 1),
    default=1.0,
    show_default=True,
    help="Real pixels (kitty, iterm): draw this fraction of the terminal's pixels each way "
    "and let the terminal scale the picture up, for a slow link.",
)
@_refusals_exit_2
def app(config: Path, colors: str, fps: float | None, graphics: str | None,
        pixel_scale: float) -> None:
    """Open the terminal app on CONFIG (default: configs/biceps.toml)."""
    from biceps.engine.coldstart import Asides
    from biceps.engine.config import load_config

    asides = Asides() if _own_process() else None
    if asides is not None:
        _keys_are_keys()
    loaded = load_config(config)  # fail here, before the terminal switches screens
    _check_terminal()
    if asides is not None:  # a first run's longest compilation starts before Textual loads
        asides.start_rasterizer(loaded.render.shading)
    from biceps.tui.app import run_app

    with _app_process(asides) as process:
        status = run_app(loaded, colors=colors, fps=fps, graphics=graphics,
                         pixel_scale=pixel_scale, process=process)
    if status:
        sys.exit(status)


def _keys_are_keys() -> None:
    """Ignore SIGQUIT and SIGTSTP, which ctrl+\\ and ctrl+z raise while the terminal is in its
    own mode: before the app has taken it (loading a file, compiling on a first run), and
    between an app that ended on an error and its rescue.

    While the app runs Textual turns those signals off, and the keys are keys: ctrl+z is
    undo, ctrl+\\ nothing. Typed a moment earlier, in a burst, they dumped core or stopped
    the app half started. Textual puts its own SIGTSTP handler in place as it starts, and
    the app ignores the signal again once it is up (tui/app.py's ``on_ready``), so that
    kill -TSTP does not stop it either. ctrl+c before the app is up still ends it,
    quietly (exit status 130).
    """
    signal.signal(signal.SIGQUIT, signal.SIG_IGN)
    signal.signal(signal.SIGTSTP, signal.SIG_IGN)


def _check_terminal() -> None:
    """Refuse to start the app without a terminal to read keys from and draw on (Textual
    reads stdin and draws on stderr): with none it would write its screen into a file or
    a pipe, and wait for keys that never come."""
    for number, name in ((0, "stdin"), (2, "stderr")):
        if not os.isatty(number):
            raise BicepsError(f"the app needs a terminal, and its {name} is not one; for a "
                              "picture without a terminal: biceps snapshot -o arm.png")


VISITOR_MEMORY = 1000
"""MB of memory a visitor's app may use unless ``biceps serve`` is told otherwise."""
VISITOR_MEMORY_LEAST = 400
"""MB of memory a visitor's app needs at the least."""


@main.command(short_help="Serve the app to web browsers, one process a visitor.")
@config_argument
@click.option("--host", default="localhost", show_default=True,
              help="The address to listen on; anything but this machine's own (localhost) "
              "lets anyone who can reach it use the app.")
@click.option("--port", type=click.IntRange(1, 65535), default=8000, show_default=True)
@click.option("--max-visitors", type=click.IntRange(1, 1000), default=10, show_default=True,
              help="At most this many at once, each a process of its own; the next is shown "
              "a page saying it is full.")
@click.option("--visitor-memory", type=click.IntRange(VISITOR_MEMORY_LEAST, None),
              default=VISITOR_MEMORY, show_default=True, metavar="MB",
              help="The memory each visitor's app may use, in MB: an export or an animation "
              "that needs more is refused in its tab.")
@click.option("--visitor-minutes", type=_FiniteFloat(0.1, 10080), default=120,
              show_default=True, metavar="MINUTES",
              help="How long each visitor's app runs before it ends, saying so in its tab.")
@_refusals_exit_2
def serve(config: Path, host: str, port: int, max_visitors: int, visitor_memory: int,
          visitor_minutes: float) -> None:
    """Serve the app on CONFIG to web browsers (needs the serve extra: textual-serve): each
    visitor gets the app in a browser tab, its exports as downloads, its files in a folder of
    its own, removed when the tab closes."""
    from biceps.engine.config import load_config
    from biceps.serve import Limits, is_local, serve as serve_app

    load_config(config)  # a bad file is refused here, not in every visitor's tab
    if not is_local(host):
        _say(f"biceps: warning: serving on {host}: anyone who can reach this machine on port "
             f"{port} can use the app, up to {max_visitors} at once")
    serve_app(config.resolve(), host, port, max_visitors,
              Limits(memory=visitor_memory, minutes=visitor_minutes))


@main.command(hidden=True)
@config_argument
@click.option("--scratch", type=click.Path(path_type=Path, file_okay=False, exists=True),
              required=True)
@click.option("--folder", type=click.Path(path_type=Path, file_okay=False, exists=True))
@click.option("--memory", type=click.IntRange(VISITOR_MEMORY_LEAST, None), metavar="MB",
              help="The most memory this process may use, in MB (its data, RLIMIT_DATA).")
@_refusals_exit_2
def visit(config: Path, scratch: Path, folder: Path | None, memory: int | None) -> None:
    """One visitor's app under biceps serve: Textual's web driver on stdin and stdout, files
    confined to a folder of its own under SCRATCH (FOLDER, made by the server, which writes
    the visitor's uploads there), removed when the visitor leaves."""
    import resource
    import shutil
    import tempfile

    if memory is not None:  # beyond it an allocation fails: a MemoryError, which exports catch
        resource.setrlimit(resource.RLIMIT_DATA, (memory << 20, memory << 20))

    from biceps.engine.config import load_config
    from biceps.tui import visitor
    from biceps.tui.app import run_app

    loaded = load_config(config)
    own = folder or Path(tempfile.mkdtemp(prefix="visitor-", dir=scratch))
    try:
        visitor.confine_to(own)
        # The browser's terminal (xterm.js) shows 24-bit colour and text, never images:
        # nothing is asked of it.
        with _app_process() as process:
            status = run_app(loaded, colors="truecolor", graphics="halfblocks", process=process)
    finally:
        os.chdir(scratch)
        shutil.rmtree(own, ignore_errors=True)
    if status:
        sys.exit(status)


@main.command(short_help="Say what this terminal can show, and what the app would use.")
@click.option("--graphics", type=click.Choice(GRAPHICS), default="auto", show_default=True,
              help="The choice to explain, as the app would take it.")
@click.option("--colors", type=click.Choice(COLORS), default="auto", show_default=True,
              help="The colours to explain, as the app would take them.")
@_refusals_exit_2
def doctor(graphics: str, colors: str) -> None:
    """Ask this terminal what it can show, and say what the app would use and why."""
    from biceps.terminal import choose, detect

    from biceps.tui.textual_private import describe

    answers, place = detect.ask(), detect.Place.here()
    _print(f"biceps doctor: --graphics {graphics} --colors {colors}\n"
           + choose.report(graphics, answers, place, choose.choose(graphics, answers, place),
                           choose.colours(colors, answers, place))
           + f"\n  {'textual':<15} {describe()}")


@main.command()
@config_argument
@pose_options
@click.option("--json", "as_json", is_flag=True, help="Print JSON for scripts.")
@_refusals_exit_2
def info(config: Path, length: float | None, flexion: float | None, as_json: bool) -> None:
    """Length, flexion, volume and radii of the muscle in CONFIG.

    With several muscles, a line for each: length, volume, its error, largest radius."""
    from biceps.engine.config import load_config

    _writable_stdout()  # before any work
    arm = posed(load_config(config).arm, length, flexion)
    facts = describe(arm)
    if as_json:
        # allow_nan=False: NaN and Infinity are not JSON (the engine's bounds keep them out).
        _print(json.dumps(facts, indent=2, allow_nan=False))
        return
    low, high = facts["length_range_cm"]
    radii = " ".join(f"{r:.3f}" for r in facts["radii_cm"])
    lines = [
        f"{printable(config)}\n"
        f"  length         {facts['length_cm']:.3f} cm (allowed {low:.2f} to {high:.2f})\n"
        f"  elbow flexion  {facts['flexion_deg']:.2f} degrees, "
        f"moment arm {facts['moment_arm_cm']:.3f} cm\n"
        f"  volume         {facts['volume_cm3']:.6f} cm^3 ({facts['volume_mode']}), "
        f"relative error {facts['volume_relative_error']:.1e}\n"
        f"  max radius     {facts['max_radius_cm']:.3f} cm, girth {facts['girth_cm']:.3f} cm\n"
        f"  nodes          {facts['nodes']}\n"
        f"  radii (cm)     {radii}"
    ]
    others = facts["muscles"][1:]
    if others:
        width = max(len(each["name"]) for each in facts["muscles"])
        lines.append("  muscles        length, volume (relative error), largest radius; the "
                     "first drives the elbow")
        for each in facts["muscles"]:
            lines.append(f"    {each['name']:<{width}}  {each['length_cm']:7.3f} cm "
                         f"{each['volume_cm3']:9.4f} cm^3 ({each['volume_relative_error']:.1e}) "
                         f"{each['max_radius_cm']:.3f} cm")
    _print("\n".join(lines))


@main.command(short_help="One row per elbow angle: length, moment arm, girth, radii.")
@config_argument
@click.option("--from", "start", type=FINITE,
              help="First elbow flexion, degrees (default: the least the arm allows).")
@click.option("--to", "stop", type=FINITE,
              help="Last elbow flexion, degrees (default: the most the arm allows).")
@click.option("--step", type=FINITE, default=10.0, show_default=True, help="Degrees between rows.")
@click.option("--csv", "form", flag_value="csv", default=True, help="Comma-separated (default).")
@click.option("--json", "form", flag_value="json", help="A JSON list of rows.")
@click.option("--activation", type=_FiniteFloat(*ACTIVATION_RANGE), metavar="A",
              help="Also every muscle's forces at this activation, 0 to 1, at rest (a "
              "Hill-type model after Thelen 2003, with arm26's parameters unless the config "
              "gives its own): its musculotendon length and moment arm (cm), fibre length "
              "(cm), active and passive fibre force and tendon force (N), and torque about "
              "the elbow (N m, positive flexing); and the elbow's net torque.")
@_refusals_exit_2
def sweep(config: Path, start: float | None, stop: float | None, step: float, form: str,
          activation: float | None) -> None:
    """One row per elbow angle: length, flexion, moment arm, volume and its error, largest
    radius, girth and every radius. Numbers are exact: the shortest text that reads back as
    the same double."""
    from biceps.engine.config import load_config
    from biceps.engine.sweep import angles, sweep as sweep_arm

    _writable_stdout()  # before any work
    loaded = load_config(config)
    arm = loaded.arm
    parameters = loaded.force_parameters() if activation is not None else None
    start, stop = _or_the_whole_range(arm, start, stop)
    flexions = angles(start, stop, step)
    with _progress_bar("sweeping", len(flexions), SLOW_SWEEP) as progress:
        records = [row.record() for row in sweep_arm(arm, flexions, progress)]
    if parameters is not None:
        from biceps.engine.actuation import forces_across

        for record, muscles in zip(records, forces_across(arm, parameters, flexions, activation)):
            record["muscles"] = [muscle.record() for muscle in muscles]
            record["elbow_torque_nm"] = sum(muscle.torque for muscle in muscles)
    if form == "json":
        _print(json.dumps(records, indent=2, allow_nan=False))
        return
    radii = len(records[0]["radii_cm"])
    columns = [name for name in records[0] if name not in ("radii_cm", "muscles")]
    table = io.StringIO()
    writer = csv.writer(table, lineterminator="\n")
    # repr (which csv uses for a float) is the shortest form that reads back exactly.
    writer.writerow([*columns, *(f"radius_{i}_cm" for i in range(1, radii + 1)),
                     *_muscle_columns(records[0])])
    for record in records:
        writer.writerow([*(record[name] for name in columns), *record["radii_cm"],
                         *(value for muscle in record.get("muscles", ())
                           for key, value in muscle.items() if key != "name")])
    _print(table.getvalue().removesuffix("\n"))


def _muscle_columns(record: dict[str, Any]) -> list[str]:
    """The CSV columns of a sweep row's muscles, each named after its muscle:
    ``BIClong_tendon_force_n``."""
    return [f"{muscle['name']}_{key}" for muscle in record.get("muscles", ())
            for key in muscle if key != "name"]


@main.command(short_help="The least-effort activations that hold a mass in the hand.")
@config_argument
@click.option("--mass", type=_FiniteFloat(*MASS_RANGE), required=True, metavar="KG",
              help="The mass in the hand, kg, at the forearm's free end.")
@click.option("--flexion", type=FINITE,
              help="Elbow flexion in degrees (default: the config's pose).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON for scripts.")
@_refusals_exit_2
def hold(config: Path, mass: float, flexion: float | None, as_json: bool) -> None:
    """The activations of the muscles in CONFIG that hold MASS kg in the hand still at an
    elbow angle with the least sum of squared activations (each from its minimum, 0.01, to
    1), against the load and the forearm's own weight (arm26's 1.53 kg at 18.1 cm from the
    elbow), the upper arm hanging; or, if the muscles cannot, the strongest torque they
    give there. Forces from a Hill-type model after Thelen 2003 (arm26's parameters unless
    the config gives its own). Lengths and moment arms in cm, forces in N, torques in N m
    about the elbow, positive flexing."""
    from biceps.engine.config import load_config
    from biceps.engine.hold import hold_arm

    _writable_stdout()  # before any work
    loaded = load_config(config)
    arm = loaded.arm
    flexion = arm.flexion if flexion is None else flexion
    arm.at_flexion(flexion)  # refuses an angle outside the joint's range, in words
    held = hold_arm(arm, loaded.force_parameters(), flexion, mass)
    facts = {
        "flexion_deg": flexion,
        "mass_kg": mass,
        "load_torque_nm": held.load.torque,
        "hand_torque_nm": held.load.hand,
        "forearm_torque_nm": held.load.forearm,
        "elbow_torque_nm": held.torque,
        "sum_of_squared_activations": held.cost,
        "muscles": [muscle.record() for muscle in held.muscles],
    }
    if as_json:
        _print(json.dumps(facts, indent=2, allow_nan=False))
        return
    width = max(len(name) for name in arm.names)
    lines = [
        f"{printable(config)}: {mass:g} kg in the hand at {flexion:.2f} degrees of flexion\n"
        f"  load        {held.load.torque:.3f} N m at the elbow: {held.load.hand:.3f} for the "
        f"mass, {held.load.forearm:.3f} for the forearm's own weight\n"
        f"  {'muscle':<{width}}  activation  fibre cm  tendon N  torque N m"]
    lines += [f"  {muscle.name:<{width}}  {muscle.activation:10.4f}  "
              f"{muscle.fibre_length:8.3f}  {muscle.tendon_force:8.2f}  {muscle.torque:10.3f}"
              for muscle in held.muscles]
    lines.append(f"  net torque  {held.torque:.3f} N m; sum of squared activations "
                 f"{held.cost:.4f}")
    _print("\n".join(lines))


def _or_the_whole_range(arm: Arm, start: float | None, stop: float | None) -> tuple[float, float]:
    """``--from`` and ``--to``, each defaulting to its end of the flexions the arm allows."""
    from biceps.engine.sweep import flexion_range

    least, most = flexion_range(arm)
    return least if start is None else start, most if stop is None else stop


def describe(arm: Arm) -> dict[str, Any]:
    """The facts ``info`` prints, as plain data."""
    muscle = arm.muscle
    return {
        "length_cm": muscle.length,
        "length_range_cm": list(arm.length_range()),
        "flexion_deg": arm.flexion,
        "moment_arm_cm": arm.moment_arm,
        "volume_mode": muscle.volume_mode,
        "volume_cm3": muscle.volume,
        "reference_volume_cm3": muscle.reference_volume,
        "volume_relative_error": muscle.volume_error,
        "max_radius_cm": muscle.max_radius,
        "girth_cm": muscle.girth,
        "nodes": muscle.node_count,
        "radii_cm": muscle.radii.tolist(),
        "growth": muscle.growth.tolist(),
        "muscles": [_muscle_facts(name, each, path, moment_arm, arm.flexion)
                    for name, each, path, moment_arm
                    in zip(arm.names, arm.muscles, arm.paths, arm.moment_arms)],
    }


def _muscle_facts(name: str, muscle: Any, path: Any, moment_arm: float,
                  flexion: float) -> dict[str, Any]:
    """One muscle's facts, for ``info``'s list of every muscle (the driver first): its
    length and moment arm (its path's), its widest section's area (the node law's, pi r^2
    at its largest radius) and the points its path runs through at ``flexion``."""
    return {
        "name": name,
        "length_cm": muscle.length,
        "moment_arm_cm": moment_arm,
        "widest_section_cm2": math.pi * muscle.max_radius**2,
        "path_points_cm": path.points_at(flexion).tolist(),
        "rest_length_cm": muscle.reference_length,
        "volume_mode": muscle.volume_mode,
        "volume_cm3": muscle.volume,
        "reference_volume_cm3": muscle.reference_volume,
        "volume_relative_error": muscle.volume_error,
        "max_radius_cm": muscle.max_radius,
        "nodes": muscle.node_count,
    }


def _parse_size(_ctx: Any, _param: Any, value: str | None) -> tuple[int, int] | None:
    from biceps.engine.export import parse_size

    if value is None:
        return None
    try:
        return parse_size(value)
    except ValueError as error:
        raise click.BadParameter(str(error)) from None


def _parse_point(_ctx: Any, _param: Any, value: str | None) -> tuple[float, float, float] | None:
    if value is None:
        return None
    try:
        x, y, z = (float(part) for part in value.split(","))
    except ValueError:
        raise click.BadParameter(f"give X,Y,Z in cm, like 60,80,120; got {value!r}") from None
    try:
        return finite(x, COORDINATE), finite(y, COORDINATE), finite(z, COORDINATE)
    except OutOfBounds as error:
        raise click.BadParameter(f"each coordinate {error}") from None


def view_options(command: Callable) -> Callable:
    """Options that override the config's view, light and rendering."""
    options = [
        click.option("--yaw", type=TURN, help="Turn about the vertical axis, degrees."),
        click.option("--pitch", type=TURN, help="Tilt about the horizontal axis, degrees."),
        click.option("--roll", type=TURN, help="Roll about the line of sight, degrees."),
        click.option("--scale", type=_FiniteFloat(SCALE.low, SCALE.high), help="Zoom factor."),
        click.option("--light", callback=_parse_point, metavar="X,Y,Z",
                     help="Light position in world space, cm."),
        click.option("--ssaa", type=click.IntRange(SUPERSAMPLING.low, SUPERSAMPLING.high),
                     help=f"Supersampling factor, {SUPERSAMPLING}."),
        click.option("--shading", type=click.Choice(["gouraud", "phong"]), help="Shading model."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def posed_scene(config_path: Path, length: float | None, flexion: float | None,
                **overrides: Any) -> Scene:
    """The config's scene in the asked pose, with the command line's overrides applied."""
    from biceps.engine.config import load_config
    from biceps.engine.scene import Scene

    scene = Scene.of(load_config(config_path))
    scene = scene.with_arm(posed(scene.arm, length, flexion))
    view = {k: overrides[k] for k in ("yaw", "pitch", "roll", "scale") if overrides[k] is not None}
    render = {k: overrides[k] for k in ("ssaa", "shading") if overrides[k] is not None}
    scene = scene.with_view(**view).with_render(**render)
    if overrides["light"] is not None:
        scene = scene.with_light(position=overrides["light"])
    return scene


PNG_SIZE = (1920, 1080)


@main.command(short_help="Render CONFIG to a PNG file, or print it to this terminal.")
@config_argument
@click.option("-o", "--output", type=click.Path(path_type=Path),
              help="The PNG file to write.")
@click.option("--size", callback=_parse_size, metavar="WxH",
              help=f"Picture size in pixels (default {PNG_SIZE[0]}x{PNG_SIZE[1]}; printed, to "
              "fit the window).")
@click.option("--ansi", "printed", flag_value="ansi",
              help="Print the picture as half-block pixels instead, in colour even into a pipe.")
@click.option("--kitty", "printed", flag_value="kitty",
              help="Print it in the kitty graphics protocol.")
@click.option("--sixel", "printed", flag_value="sixel", help="Print it as sixel.")
@click.option("--iterm", "printed", flag_value="iterm", help="Print it as an iTerm2 image.")
@click.option("--colors", type=click.Choice(COLORS), default="auto", show_default=True,
              help="With --ansi: the colour codes; auto asks the terminal, if it is one, and "
              "the environment (COLORTERM).")
@pose_options
@view_options
@_refusals_exit_2
def snapshot(config: Path, output: Path | None, size: tuple[int, int] | None,
             printed: str | None, colors: str, length: float | None, flexion: float | None,
             **overrides: Any) -> None:
    """Render CONFIG to a PNG file, with no terminal needed, or print it to this one.

    --kitty, --sixel and --iterm print a picture that fits the window, in the terminal's own
    pixels, in that protocol: as wide as the terminal at 16:9, or as tall as the window
    where that would be taller (--ansi: as wide, in half-blocks); --size says otherwise.
    """
    from biceps.engine.cost import check_picture
    from biceps.engine.export import check_writable, write_png
    from biceps.engine.scene_renderer import SMALL_PICTURE, SceneRenderer, supersampling

    if printed is not None and output is not None:
        raise click.UsageError(f"give -o FILE.png or --{printed}, not both: a picture goes "
                               "to one place")
    if printed is None and output is None:
        raise click.UsageError("give -o FILE.png, or one of --ansi, --kitty, --sixel and "
                               "--iterm to print to the terminal")
    if output is not None:
        check_writable(output, ".png", read=config)
        size = size or PNG_SIZE  # printed, it is as wide as the terminal unless asked
    else:
        _writable_stdout(half_blocks=printed == "ansi")  # before any work
    scene = posed_scene(config, length, flexion, **overrides)
    if size is not None:
        width, height = size
        check_picture(width, height, supersampling(scene.render, height))  # before any work
    if _own_process():
        from biceps.engine.coldstart import prepare_kernels

        # Forks: see coldstart. Half-blocks in a terminal are most likely a small picture.
        height = size[1] if size else SMALL_PICTURE if printed == "ansi" else PNG_SIZE[1]
        prepare_kernels(scene.render.shading, supersampling(scene.render, height))
    with SceneRenderer() as renderer:  # its threads stopped when done
        frame = _snapshot_drawn(renderer, scene, size, printed, colors)
    if frame is None:
        return  # printed
    write_png(output, frame)
    click.echo(f"wrote {printable(output)} ({size[0]}x{size[1]})", err=True)


def _snapshot_drawn(renderer: SceneRenderer, scene: Scene, size: tuple[int, int] | None,
                    printed: str | None, colors: str) -> np.ndarray | None:
    """``snapshot``'s picture drawn by ``renderer``: printed to standard output in the
    form ``printed`` (None then), or the frame for the PNG, of ``size``."""

    def draw(width: int, height: int) -> np.ndarray:
        return renderer.render(scene, width, height)

    if printed == "ansi":
        from biceps.engine.config import rgb
        from biceps.terminal import choose, detect
        from biceps.terminal.ansi import print_picture

        answers = detect.ask() if colors == "auto" and sys.stdout.isatty() else None
        asked = scene.render.colors if colors == "auto" else colors
        system = choose.colours(asked, answers, detect.Place.here()).system
        with _stdout(half_blocks=True):
            print_picture(draw, rgb(scene.render.background), size, system)
        return None
    if printed is not None:
        from biceps.terminal.printed import print_image

        with _stdout():
            print_image(printed, draw, size)
        return None
    try:
        return draw(*size)
    except MemoryError:
        raise BicepsError(
            f"not enough memory to render {size[0]}x{size[1]} with {scene.render.ssaa}x"
            f"{scene.render.ssaa} supersampling; try a smaller --size or --ssaa"
        ) from None


@main.command(short_help="Write the flex cycle as a GIF, APNG, WebP or MP4 animation.")
@config_argument
@click.option("-o", "--output", required=True, type=click.Path(path_type=Path),
              help="The file to write: .gif, .apng, .webp or .mp4 (MP4 needs biceps[video]).")
@click.option("--size", default="640x360", show_default=True, callback=_parse_size,
              metavar="WxH", help="Picture size in pixels.")
@click.option("--from", "start", type=FINITE,
              help="Elbow flexion of the first frame, degrees (default: the least the arm "
              "allows).")
@click.option("--to", "stop", type=FINITE,
              help="Elbow flexion at the far end, degrees (default: the most the arm allows).")
@click.option("--frames", type=click.IntRange(2, 10_000), default=60, show_default=True,
              help="Frames in the file; a bounce needs an even number.")
@click.option("--fps", type=FINITE, default=25.0, show_default=True,
              help="Frames a second, 1 to 60 (a GIF: at most 50).")
@click.option("--loop/--bounce", "loop", default=False,
              help="Play from --from to --to and start again, or go there and back "
              "(default: bounce).")
@view_options
@_refusals_exit_2
def animate(config: Path, output: Path, size: tuple[int, int], start: float | None,
            stop: float | None, frames: int, fps: float, loop: bool, **overrides: Any) -> None:
    """Write the flex cycle of CONFIG as a GIF, APNG, WebP or MP4 animation."""
    from biceps.engine.animate import FlexCycle, check_cycle, render_cycle
    from biceps.engine.movie import check_animation, write_animation

    check_animation(output, *size, fps, read=config)
    scene = posed_scene(config, None, None, **overrides)
    cycle = FlexCycle(*_or_the_whole_range(scene.arm, start, stop), frames, bounce=not loop)
    check_cycle(scene, cycle, *size)
    if _own_process():
        from biceps.engine.coldstart import prepare_kernels

        prepare_kernels(scene.render.shading, scene.render.ssaa)  # forks: see coldstart
    try:
        with _progress_bar("rendering", len(cycle.poses())) as progress:
            pictures = render_cycle(scene, cycle, *size, progress=progress)
        with _progress_bar("encoding ", frames) as progress:
            write_animation(output, pictures, fps, progress=progress)
    except MemoryError:
        raise BicepsError(f"not enough memory for {frames} frames of {size[0]}x{size[1]}; "
                          "try fewer --frames, a smaller --size or --ssaa") from None
    click.echo(f"wrote {printable(output)} ({size[0]}x{size[1]}, {frames} frames at {fps:g} "
               "a second)", err=True)


SLOW_SWEEP = 2_000
"""Rows from which ``sweep`` shows its progress (a few seconds' work)."""


@contextmanager
def _progress_bar(label: str, total: int, at_least: int = 0) -> Iterator[Progress]:
    """A progress bar on stderr when it is a terminal, none when it is not (piped, or a
    log) or the job is shorter than ``at_least`` steps: the context gives the function to
    tell ``(done, total)``."""
    if total < at_least or sys.stderr is None or not sys.stderr.isatty():
        yield lambda done, total: None
        return
    with click.progressbar(length=total, label=label, file=sys.stderr, show_pos=True) as bar:
        yield lambda done, total: bar.update(done - bar.pos)


@main.command("export-mesh", short_help="Write the posed arm as a mesh: OBJ, STL, PLY or glTF.")
@config_argument
@click.option("-o", "--output", required=True, type=click.Path(path_type=Path),
              help="The file to write: .obj, .stl, .ply or .glb.")
@click.option("--segments", type=click.IntRange(SEGMENTS.low, SEGMENTS.high),
              help="Vertices around each axis.")
@pose_options
@_refusals_exit_2
def export_mesh(config: Path, output: Path, segments: int | None, length: float | None,
                flexion: float | None) -> None:
    """Write the arm in CONFIG as a mesh: muscle and bones as separate named parts, in cm."""
    from biceps.engine.config import load_config
    from biceps.engine.export import MESH_FORMATS, check_writable, write_mesh

    from biceps.engine.cost import check_model

    check_writable(output, *MESH_FORMATS, read=config)
    loaded = load_config(config)
    arm = posed(loaded.arm, length, flexion)
    render = loaded.render
    segments = segments or render.segments
    check_model([muscle.node_count for muscle in arm.muscles], segments)
    write_mesh(output, arm, segments, render.muscle_colour, render.bone_colour)
    click.echo(f"wrote {printable(output)}", err=True)


def _hold_standard_numbers() -> None:
    """Open /dev/null on stdin, stdout and stderr where they are closed (``>&-``).

    Python then leaves sys.stdout None (which :func:`_stdout` refuses), but the number is
    free, and the next file opened takes it: a PNG being written would get 1, and anything
    written to stdout below Python would land in it.
    """
    for number in (0, 1, 2):
        try:
            os.fstat(number)
        except OSError:
            held = os.open(os.devnull, os.O_RDWR)
            if held != number:  # a lower one was free too, and is held the next time round
                os.dup2(held, number)
                os.close(held)


OWN_PROCESS = "the biceps command's own process"
"""The context's ``obj`` when the process is the command's own and ends with it (see `run`),
rather than a caller's (a test's, say): only then may the command fork it or freeze its
heap."""


def _own_process() -> bool:
    return click.get_current_context().find_root().obj == OWN_PROCESS


@contextmanager
def _app_process(asides: Asides | None = None) -> Iterator[AppProcess]:
    """What the app is given in the command's own process (tui/app.py's AppProcess): the
    children ``asides`` compiling its first frame's kernels, one pool of threads for its
    renderers, shut down after, the heap frozen once it is up (`_freeze_heap`), and a
    cache of Textual's mended to let go of the lines of widgets gone; in a caller's
    process (a test's), nothing."""
    from biceps.tui.app import AppProcess

    if not _own_process():
        yield AppProcess()
        return
    from biceps.engine.raster.bands import band_pool
    from biceps.tui.textual_private import release_styles_caches

    release_styles_caches()

    with band_pool() as pool:
        yield AppProcess(asides, pool, _freeze_heap)


def _freeze_heap() -> None:
    """Every frame of the app makes thousands of short-lived segments, and every so often
    Python then collects the oldest generation too, walking all of Textual's and numba's
    objects, long enough to miss frames. Set apart what exists once the app is up
    (gc.freeze), so that those collections walk only what came after."""
    gc.collect()
    gc.freeze()


def run() -> None:
    """The ``biceps`` command: :func:`main`, then a quicker exit."""
    _hold_standard_numbers()
    if sys.stdout is not None:
        # A name a stdout of another encoding cannot take (PYTHONIOENCODING=ascii) is
        # written as escapes, \xe9, as stderr writes it, rather than ending in an error.
        sys.stdout.reconfigure(errors="backslashreplace")
    try:
        main(obj=OWN_PROCESS)
    finally:
        # At exit Python collects garbage again and again as it tears the modules down, and
        # each pass walks every object numba and LLVM have made, a large share of a short
        # command's time. Frozen objects are left for the OS to free.
        gc.freeze()


if __name__ == "__main__":
    run()
