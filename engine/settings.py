"""Runtime settings: how the model is viewed and how the picture is rendered, as frozen values
that check their rules when they are made.

Each rule (a bound, the words allowed) is written once, here, as a type pydantic validates
(the light's beside the light, ``engine/transforms.py``), and each default beside its field.
A file's ``[view]``, ``[light]`` and ``[render]`` tables validate straight into these values
(``engine/config.py``), whose messages name the file, the line and the field; made any other
way (a key, the command line, a script), a setting outside its rules raises
:class:`SettingError` naming the field, the value and what is allowed. Either way no such
setting exists.
"""

from __future__ import annotations

import functools
from dataclasses import fields
from typing import Annotated, Any, Literal, Mapping, get_args

from pydantic import ConfigDict, Field, PlainValidator, ValidationError, ValidationInfo
from pydantic.dataclasses import dataclass
from pydantic_core import PydanticCustomError

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

IN_A_FILE = {"in_a_file": True}
"""The validation context of a file's tables: a file may not name what only a run may set
(the "overdraw" shading)."""


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


def number(limits: Limits | None = None) -> PlainValidator:
    """A finite number (a bool is not one, nor "1.5") within ``limits``: the rule of
    ``engine/bounds.py``, so that a file, a dialog and a key refuse the same numbers in the
    same words."""
    return PlainValidator(lambda value: finite(value, limits))


def integer(limits: Limits) -> PlainValidator:
    """A whole number (not a bool, nor a float such as 2.0) within ``limits``."""
    return PlainValidator(lambda value: whole(value, limits))


class Wanted(str):
    """What a field allows, in words, where its type's own refusals say it piece by piece (a
    point's coordinate by coordinate): a refused setting's message says it whole."""


Coordinate = Annotated[float, number(COORDINATE)]
Point = Annotated[tuple[Coordinate, Coordinate, Coordinate],
                  Wanted(COORDINATE.of("three finite numbers (x, y, z)"))]
"""x, y and z (cm), each within :data:`~engine.bounds.COORDINATE`."""

COLOUR_WANTED = Wanted("a colour written #rrggbb")
Colour = Annotated[str, Field(pattern=f"^{COLOUR}$"), COLOUR_WANTED]


def _words(choices: tuple[str, ...]) -> str:
    *others, last = map(repr, choices)
    return f"{', '.join(others)} or {last}"


def _shading(value: Any, info: ValidationInfo) -> str:
    choices = get_args(Shading) if (info.context or {}).get("in_a_file") else SHADINGS
    if isinstance(value, str) and value in choices:
        return value
    # pydantic's own words for a Literal, as the other choices' refusals say it
    raise PydanticCustomError("literal_error", "Input should be {expected}",
                              {"expected": _words(choices)})


def setting(owner: str):
    """Make a class a frozen dataclass whose fields pydantic validates by their types; made in
    code rather than validated from a file, a value outside the rules raises
    :class:`SettingError`, named ``owner.field``. Unknown fields are refused: in a file, a
    misspelt key must not be a silent default."""

    def make(cls: type) -> type:
        cls = dataclass(frozen=True, config=ConfigDict(extra="forbid"))(cls)
        validated = cls.__init__

        @functools.wraps(validated)
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            try:
                validated(self, *args, **kwargs)
            except ValidationError as error:
                given = {**dict(zip((f.name for f in fields(cls)), args)), **kwargs}
                raise _refused(owner, cls, given, error) from None

        cls.__init__ = __init__
        return cls

    return make


def _refused(owner: str, cls: type, given: dict[str, Any], error: ValidationError) -> SettingError:
    """The first problem of ``error``, met making ``cls`` of the fields ``given``, in words."""
    problem = error.errors(include_url=False)[0]
    name = problem["loc"][0]
    field = cls.__pydantic_fields__.get(name)
    if field is None:
        allowed = ", ".join(cls.__pydantic_fields__)
        return SettingError(f"{owner} has no setting {name!r}: its settings are {allowed}")
    value = given.get(name, problem["input"])
    wanted = next((m for m in field.metadata if isinstance(m, Wanted)), None)
    refusal = problem.get("ctx", {}).get("error")
    if wanted is None and isinstance(refusal, OutOfBounds):
        wanted = refusal.wanted
    if wanted is None:
        wanted = problem.get("ctx", {}).get("expected", problem["msg"])
    return SettingError(f"{owner}.{name} is {quoted(value)}: it must be {wanted}")


FIELD_OF_VIEW = Limits(1, 170, exclusive=True, unit=" degrees")


@setting("view")
class View:
    """How the model is turned (degrees), scaled and moved (cm, after turning), and the
    camera's vertical field of view (degrees)."""

    yaw: Annotated[float, number(ANGLE)] = 0.0
    pitch: Annotated[float, number(ANGLE)] = 0.0
    roll: Annotated[float, number(ANGLE)] = 0.0
    scale: Annotated[float, number(SCALE)] = 1.0
    offset: Point = (0.0, 0.0, 0.0)
    fov: Annotated[float, number(FIELD_OF_VIEW)] = 35.0


SEGMENTS = Limits(3, 1024)
SUPERSAMPLING = Limits(1, 4)


@setting("render")
class RenderSettings:
    """How the picture is drawn: the vertices around each part's axis, the shading model,
    the supersampling factor (``ssaa`` x ``ssaa`` samples a pixel), the colours (the
    muscle's belly, its tendons, the bones, the background), how the app sends it to
    the terminal (``graphics``) and in which colours (``colors``), and whether each muscle
    shows its own colour, its strain or its activation (``colour_by``: "strain" is warm
    where a muscle is shorter than at rest, cool where longer; "activation" pale at rest,
    amber to red as it works)."""

    segments: Annotated[int, integer(SEGMENTS)] = 48
    shading: Annotated[str, PlainValidator(_shading)] = "gouraud"
    ssaa: Annotated[int, integer(SUPERSAMPLING)] = 1
    muscle_colour: Colour = "#b4483e"
    tendon_colour: Colour = "#e9e4ec"
    bone_colour: Colour = "#e3d9c0"
    background: Colour = "#12161c"
    graphics: Graphics = "halfblocks"
    colors: Colors = "auto"
    colour_by: ColourBy = "muscle"
