"""Runtime settings: how the model is viewed and how the picture is rendered, as frozen values
that check their rules when they are made.

A setting outside its rules cannot exist, whichever way it comes (a file, a key, the command
line, a script): making one raises :class:`SettingError` naming the field, the value and what
is allowed. The third setting, the light, is :class:`~engine.transforms.Light`, beside the
camera the renderer takes with it; it checks itself by the rules here.

Each default and each bound is written once, here (the light's beside the light); the file's
tables in ``engine/config.py`` take theirs from these, and convert to and from these values.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields
from typing import Any, Callable, Literal, Mapping, get_args

from biceps.engine.bounds import (ANGLE, COORDINATE, SCALE, Limits, OutOfBounds, finite, quoted,
                                  whole)
from biceps.engine.errors import SettingError

Shading = Literal["gouraud", "phong"]
"""The shadings a file may name."""

SHADINGS = (*get_args(Shading), "overdraw")
"""Every shading the renderer draws (``engine/render.py``): also "overdraw", a debugging view
that counts the triangles on each pixel, which a file cannot name and so cannot be saved."""

Graphics = Literal["halfblocks", "auto", "kitty", "sixel", "iterm", "sextants", "quadrants"]
"""How the picture reaches the terminal (``terminal/choose.py``): half-block characters, which
every terminal shows; one of the protocols for real pixels; finer text cells, sextants or
quadrants; or ``auto``, the best the terminal answers that it has."""

Colors = Literal["auto", "truecolor", "256"]
"""The colours the picture goes out in: 24-bit, xterm's 256, or ``auto``, what the terminal
answers that it keeps (``terminal/choose.py``)."""

ColourBy = Literal["muscle", "strain", "activation"]
"""What colours each muscle's belly: its own colour, how far it is from its rest length, or
how active it is."""

COLOUR = "#[0-9a-fA-F]{6}"
"""A whole colour, ``#rrggbb``, as a regular expression."""


THREADS_VARIABLE = "BICEPS_THREADS"
"""The environment variable that sets how many threads draw a frame: a setting of the
machine rather than of the model, whose file travels between machines."""


def drawing_threads(environ: Mapping[str, str]) -> int | None:
    """The threads a frame is drawn on, as :data:`THREADS_VARIABLE` in ``environ`` asks, or
    None where it is unset or empty (then every core, ``engine/raster/bands.py``)."""
    value = environ.get(THREADS_VARIABLE, "").strip()
    if not value:
        return None
    if value.isdigit() and int(value) >= 1:  # no sign, no point, no exponent
        return int(value)
    raise SettingError(f"{THREADS_VARIABLE} is {quoted(value)}: it takes a whole number of "
                       "threads from 1 (1 draws on one core), or unset for every core")


Rule = Callable[[str, Any], Any]
"""Checks the value of the field it is told the name of: returns the value to keep, or raises
:class:`SettingError`."""


def settle(setting: Any, owner: str, **rules: Rule) -> None:
    """Check every field of the frozen dataclass ``setting`` by its rule (named like the field),
    and keep what the rule returns: a float for a number, a tuple for a point, so that equal
    settings compare equal however they were written."""
    for field in fields(setting):
        value = rules[field.name](f"{owner}.{field.name}", getattr(setting, field.name))
        object.__setattr__(setting, field.name, value)


def number(limits: Limits | None = None) -> Rule:
    """A finite number (a bool is not one) within ``limits``."""

    def check(where: str, value: Any) -> float:
        try:
            return finite(value, limits)
        except OutOfBounds as error:
            raise _refused(where, value, error.wanted) from None

    return check


def integer(limits: Limits) -> Rule:
    """A whole number (not a bool, nor a float such as 2.0) within ``limits``."""

    def check(where: str, value: Any) -> int:
        try:
            return whole(value, limits)
        except OutOfBounds as error:
            raise _refused(where, value, error.wanted) from None

    return check


def point(where: str, value: Any) -> tuple[float, float, float]:
    """Three finite numbers, x, y and z, each within :data:`~engine.bounds.COORDINATE`."""
    try:
        if not isinstance(value, (tuple, list)) or len(value) != 3:
            raise ValueError
        return tuple(finite(v, COORDINATE) for v in value)
    except ValueError:
        raise _refused(where, value, COORDINATE.of("three finite numbers (x, y, z)")) from None


def one_of(choices: tuple[str, ...]) -> Rule:
    """One of the words ``choices``."""

    def check(where: str, value: Any) -> str:
        if not isinstance(value, str) or value not in choices:
            *others, last = map(repr, choices)
            raise _refused(where, value, f"{', '.join(others)} or {last}")
        return value

    return check


def colour(where: str, value: Any) -> str:
    """A colour written ``#rrggbb``."""
    if not isinstance(value, str) or not re.fullmatch(COLOUR, value):
        raise _refused(where, value, "a colour written #rrggbb")
    return value


def _refused(where: str, value: Any, wanted: str) -> SettingError:
    return SettingError(f"{where} is {quoted(value)}: it must be {wanted}")


FIELD_OF_VIEW = Limits(1, 170, exclusive=True, unit=" degrees")


@dataclass(frozen=True)
class View:
    """How the model is turned (degrees), scaled and moved (cm, after turning), and the
    camera's vertical field of view (degrees)."""

    yaw: float = 0.0
    pitch: float = 0.0
    roll: float = 0.0
    scale: float = 1.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    fov: float = 35.0

    def __post_init__(self) -> None:
        settle(self, "view", yaw=number(ANGLE), pitch=number(ANGLE), roll=number(ANGLE),
               scale=number(SCALE), offset=point, fov=number(FIELD_OF_VIEW))


SEGMENTS = Limits(3, 1024)
SUPERSAMPLING = Limits(1, 4)


@dataclass(frozen=True)
class RenderSettings:
    """How the picture is drawn: the vertices around each part's axis, the shading model,
    the supersampling factor (``ssaa`` x ``ssaa`` samples a pixel), the colours (the
    muscle's belly, its tendons, the bones, the background), how the app sends it to
    the terminal (``graphics``) and in which colours (``colors``), and whether each muscle
    shows its own colour, its strain or its activation (``colour_by``: "strain" is warm
    where a muscle is shorter than at rest, cool where longer; "activation" pale at rest,
    amber to red as it works)."""

    segments: int = 48
    shading: str = "gouraud"
    ssaa: int = 1
    muscle_colour: str = "#b4483e"
    tendon_colour: str = "#e9e4ec"
    bone_colour: str = "#e3d9c0"
    background: str = "#12161c"
    graphics: str = "halfblocks"
    colors: str = "auto"
    colour_by: str = "muscle"

    def __post_init__(self) -> None:
        settle(self, "render", segments=integer(SEGMENTS), shading=one_of(SHADINGS),
               ssaa=integer(SUPERSAMPLING), muscle_colour=colour, tendon_colour=colour,
               bone_colour=colour, background=colour, graphics=one_of(get_args(Graphics)),
               colors=one_of(get_args(Colors)), colour_by=one_of(get_args(ColourBy)))
