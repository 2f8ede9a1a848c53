"""The ``biceps`` command: the app by default, and headless subcommands.

``biceps [CONFIG]`` opens the terminal app; ``biceps info``, ``snapshot`` and
``export-mesh`` work with no terminal at all. The app (and with it Textual) is imported
only inside its own command, so the headless commands stay light and start fast.

Every deliberate refusal (a bad config, an impossible length, a file that cannot be
written) ends the process with exit code 2 and one clear message on stderr.
"""

from __future__ import annotations

import functools
import json
import sys
from pathlib import Path
from typing import Any, Callable

import click

from engine.arm import Arm
from engine.config import DEFAULT_CONFIG, load_config
from engine.errors import BicepsError

USAGE_ERROR = 2


class _AppByDefault(click.Group):
    """A group whose bare invocation, or one naming a config, runs the ``app`` command."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        if not args or (args[0] not in self.commands and args[0] not in ("--help", "-h")):
            args = ["app", *args]
        return super().parse_args(ctx, args)


def _refusals_exit_2(command: Callable) -> Callable:
    """Turn a :class:`BicepsError` into its message on stderr and exit code 2."""

    @functools.wraps(command)
    def run(*args: Any, **kwargs: Any) -> Any:
        try:
            return command(*args, **kwargs)
        except BicepsError as error:
            click.echo(f"biceps: {error}", err=True)
            sys.exit(USAGE_ERROR)

    return run


config_argument = click.argument(
    "config",
    required=False,
    default=str(DEFAULT_CONFIG),
    type=click.Path(dir_okay=False, path_type=Path),
)


def pose_options(command: Callable) -> Callable:
    """``--length`` / ``--flexion``: the pose to show, instead of the config's own."""
    command = click.option("--flexion", type=float, help="Elbow flexion in degrees (0 = straight).")(command)
    command = click.option("--length", type=float, help="Muscle length in cm.")(command)
    return command


def posed_arm(config_path: Path, length: float | None, flexion: float | None) -> Arm:
    """The config's arm, moved to the asked length or flexion if any."""
    if length is not None and flexion is not None:
        raise click.UsageError("give --length or --flexion, not both")
    arm = load_config(config_path).arm
    if length is not None:
        return arm.at_length(length)
    if flexion is not None:
        return arm.at_flexion(flexion)
    return arm


@click.group(cls=_AppByDefault, context_settings={"help_option_names": ["-h", "--help"]})
def main() -> None:
    """A shaded 3D biceps that contracts and stretches at exactly constant volume.

    Run with no command (or just a CONFIG) to open the terminal app.
    """


@main.command()
@config_argument
@click.option(
    "--colors",
    type=click.Choice(["auto", "truecolor", "256"]),
    default="auto",
    show_default=True,
    help="Colour depth; auto honours TEXTUAL_COLOR_SYSTEM and COLORTERM.",
)
@_refusals_exit_2
def app(config: Path, colors: str) -> None:
    """Open the terminal app on CONFIG (default: configs/biceps.toml)."""
    loaded = load_config(config)  # fail here, before the terminal switches screens
    from tui.app import run_app

    run_app(loaded, colors=colors)


@main.command()
@config_argument
@pose_options
@click.option("--json", "as_json", is_flag=True, help="Print JSON for scripts.")
@_refusals_exit_2
def info(config: Path, length: float | None, flexion: float | None, as_json: bool) -> None:
    """Length, flexion, volume and radii of the muscle in CONFIG."""
    arm = posed_arm(config, length, flexion)
    facts = describe(arm)
    if as_json:
        click.echo(json.dumps(facts, indent=2))
        return
    low, high = facts["length_range_cm"]
    radii = " ".join(f"{r:.3f}" for r in facts["radii_cm"])
    click.echo(
        f"{config}\n"
        f"  length         {facts['length_cm']:.3f} cm (allowed {low:.2f} to {high:.2f})\n"
        f"  elbow flexion  {facts['flexion_deg']:.2f} degrees\n"
        f"  volume         {facts['volume_cm3']:.6f} cm^3 ({facts['volume_mode']}), "
        f"relative error {facts['volume_relative_error']:.1e}\n"
        f"  max radius     {facts['max_radius_cm']:.3f} cm, girth {facts['girth_cm']:.3f} cm\n"
        f"  nodes          {facts['nodes']}\n"
        f"  radii (cm)     {radii}"
    )


def describe(arm: Arm) -> dict[str, Any]:
    """The facts ``info`` prints, as plain data."""
    muscle = arm.muscle
    return {
        "length_cm": muscle.length,
        "length_range_cm": list(arm.length_range()),
        "flexion_deg": arm.flexion,
        "volume_mode": muscle.volume_mode,
        "volume_cm3": muscle.volume,
        "reference_volume_cm3": muscle.reference_volume,
        "volume_relative_error": muscle.volume_error,
        "max_radius_cm": muscle.max_radius,
        "girth_cm": muscle.girth,
        "nodes": muscle.node_count,
        "radii_cm": muscle.radii.tolist(),
        "growth": muscle.growth.tolist(),
    }


if __name__ == "__main__":
    main()
