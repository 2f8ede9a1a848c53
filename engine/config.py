"""Configuration files: one TOML file describes the muscle, the skeleton, the view, the light
and how to render.

Reading uses ``tomllib`` and validates with pydantic, so every error names the file, the
line where it can be found, the field's path, what was found and what is allowed. Unknown
keys are errors: a typo must not be silently ignored. Saving edits the user's own document
with ``tomlkit`` (comments and layout survive) and replaces the file atomically.
"""

from __future__ import annotations

import codecs
import difflib
import os
import re
import tomllib
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Annotated, Any, Callable, Literal, get_args, get_origin

import numpy as np
import tomlkit
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from biceps.configs import DEFAULT as DEFAULT_CONFIG, FOLDER as BUNDLED
from biceps.engine.arm import Arm
from biceps.engine.arm26_forces import CURVES, PARAMETERS, default_parameters
from biceps.engine.bounds import (
    BONE,
    FIBRE,
    FORCE,
    GROWTH,
    LEAST_ACTIVATION,
    PENNATION,
    RADIUS,
    SHAPE,
    STRAIN,
    Limits,
    OutOfBounds,
    cm,
    exactly,
    quoted,
)
from biceps.engine.companion import Companion, reach_problem
from biceps.engine.cost import model_problem
from biceps.engine.errors import ConfigError, FileChanged, FileError, RefusedChange
from biceps.engine.files import read_regular_file, same_file, write_atomically
from biceps.engine.hill import HillParameters
from biceps.engine.muscle import Muscle, VolumeMode
from biceps.engine.names import printable
from biceps.engine.settings import (COLOUR_WANTED, IN_A_FILE, Colour, Coordinate, Point,
                                    RenderSettings, View, number)
from biceps.engine import arm26
from biceps.engine.path import MusclePath, PathDrive, ViaPath, Wrap, WrapSide
from biceps.engine.skeleton import (Attachment, Skeleton, SkeletonModel, attachment_problem,
                                    skeleton_problem)
from biceps.engine.transforms import Light


Positive = Annotated[float, number(Limits(0, exclusive=True, unit=" cm"))]
Degrees = Annotated[float, number(Limits(0, 180, unit=" degrees"))]
Radius = Annotated[float, number(RADIUS)]
Growth = Annotated[float, number(GROWTH)]
Bone = Annotated[float, number(BONE)]
MuscleName = Annotated[str, Field(pattern=r"^[A-Za-z0-9_\-]{1,40}$")]

COMPANION_COLOURS = ("#c8705a", "#a8503a", "#5a7fb4", "#4a6a9a", "#6a8ac8")
"""The colours companions take when their table names none, in order: warm for the
flexors, cool for the extensors of configs/elbow.toml's order."""


class _Table(BaseModel):
    # forbid: a misspelt key is an error, not a silent default; frozen: settings are values.
    model_config = ConfigDict(extra="forbid", frozen=True)


class _ProfileTable(_Table):
    """A muscle's shape: its volume mode, the length (or flexion) at which its nodes are
    its shape, and the nodes."""

    volume: VolumeMode = "closed"
    length: Positive | None = None
    flexion: Degrees | None = None
    nodes: list[tuple[Radius, Growth]] | None = None
    radius: list[Radius] | None = None
    growth: list[Growth] | None = None

    @model_validator(mode="after")
    def _one_way_each(self) -> _ProfileTable:
        if self.nodes is None and self.radius is None and self.growth is None:
            raise ValueError(
                "no nodes: give nodes = [[radius, growth], ...] or the two lists radius and growth"
            )
        if self.nodes is not None and (self.radius is not None or self.growth is not None):
            raise ValueError("give the nodes either as nodes or as radius and growth, not both")
        if self.nodes is None and (self.radius is None or self.growth is None):
            missing = "growth" if self.growth is None else "radius"
            raise ValueError(f"radius and growth go together: {missing} is missing")
        if self.radius is not None and len(self.radius) != len(self.growth):
            raise ValueError(
                f"radius has {len(self.radius)} values but growth has {len(self.growth)}: "
                "each node needs one of each"
            )
        if (self.length is None) == (self.flexion is None):
            raise ValueError("give exactly one of length (cm) and flexion (degrees)")
        return self

    def profile(self) -> tuple[list[float], list[float]]:
        if self.nodes is not None:
            return [r for r, _ in self.nodes], [m for _, m in self.nodes]
        return list(self.radius), list(self.growth)

    def nodes_key(self, problem: str) -> str:
        """The key a ``problem`` with the nodes is reported under."""
        if self.nodes is not None:
            return "nodes"
        return "growth" if "growth" in problem else "radius"


PathName = Literal["arm26"]
"""A path a muscle may take from a model: ``"arm26"``, the path arm26 gives the muscle of
its name (``engine/arm26.py``)."""


class MuscleTable(_ProfileTable):
    """The driver: the muscle whose length sets the elbow's angle, and the pose shown."""

    name: MuscleName = "muscle"
    path: PathName | None = None
    pose_length: Positive | None = None
    pose_flexion: Degrees | None = None
    min_length: Positive | None = None
    max_length: Positive | None = None

    @model_validator(mode="after")
    def _one_pose(self) -> MuscleTable:
        if self.pose_length is not None and self.pose_flexion is not None:
            raise ValueError(
                "give at most one of pose_length (cm) and pose_flexion (degrees): the pose "
                "the muscle is shown in"
            )
        return self


class CompanionTable(_ProfileTable):
    """A muscle that follows the elbow (``engine/companion.py``): its shape, where it holds
    on (origin on the upper arm, insertion on the forearm: [along, forward, lateral] cm from
    the elbow's centre, as the [skeleton]'s attachments), whether it wraps round the elbow
    and on which side, and its colour."""

    path: PathName | None = None
    origin: Point | None = None
    insertion: Point | None = None
    wrap: WrapSide | None = None
    wrap_radius: Bone | None = None
    colour: Colour | None = None

    @model_validator(mode="after")
    def _one_path(self) -> CompanionTable:
        attached = [key for key in ("origin", "insertion", "wrap", "wrap_radius")
                    if getattr(self, key) is not None]
        if self.path is not None and attached:
            raise ValueError(
                f"path = \"{self.path}\" gives the muscle its attachments and wraps: remove "
                f"{' and '.join(attached)}")
        if self.path is None and (self.origin is None or self.insertion is None):
            missing = " and ".join(key for key in ("origin", "insertion")
                                   if getattr(self, key) is None)
            raise ValueError(f"{missing} missing: give origin and insertion ([along, "
                             "forward, lateral] cm from the elbow's centre), or path = "
                             "\"arm26\" for arm26's path of the muscle of this name")
        if (self.wrap is None) != (self.wrap_radius is None):
            raise ValueError(
                "wrap and wrap_radius go together: the side of the elbow the muscle passes "
                "(\"front\" or \"back\") and the wrapping cylinder's radius in cm")
        return self

    def own_path(self) -> MusclePath:
        """The path its origin, insertion and wrap give (when it takes no model's path)."""
        wrap = Wrap(self.wrap_radius, self.wrap) if self.wrap is not None else None
        return MusclePath(Attachment("upper_arm", *self.origin),
                          Attachment("forearm", *self.insertion), wrap)


class SkeletonTable(_Table):
    """The arm's bones and the muscle's attachments, as in :class:`Skeleton`, whose defaults
    these are; the joint's range as one pair."""

    upper_arm: Bone = Skeleton.upper_arm
    origin_to_elbow: Bone = Skeleton.origin_to_elbow
    origin_forward: Coordinate = Skeleton.origin_forward
    origin_lateral: Coordinate = Skeleton.origin_lateral
    elbow_to_insertion: Bone = Skeleton.elbow_to_insertion
    insertion_forward: Coordinate = Skeleton.insertion_forward
    insertion_lateral: Coordinate = Skeleton.insertion_lateral
    forearm: Bone = Skeleton.forearm
    flexion_range: tuple[Degrees, Degrees] = (Skeleton.min_flexion, Skeleton.max_flexion)
    model: SkeletonModel = Skeleton.model

    @model_validator(mode="after")
    def _arm26_whole(self) -> SkeletonTable:
        sized = sorted(self.model_fields_set - {"model", "flexion_range"})
        if self.model == "arm26" and sized:
            raise ValueError(f"model = \"arm26\" brings arm26's own bones and attachments: "
                             f"remove {', '.join(sized)} (flexion_range may stay)")
        return self

    @staticmethod
    def keys_of(skeleton: Skeleton) -> dict[str, Any]:
        """``skeleton`` by the table's keys, unchecked."""
        fields = asdict(skeleton)
        flexion_range = (fields.pop("min_flexion"), fields.pop("max_flexion"))
        if skeleton.model == "arm26":  # its bones are arm26's: the other fields do not apply
            return {"model": "arm26", "flexion_range": flexion_range}
        return {"flexion_range": flexion_range, **fields}

    def skeleton(self) -> Skeleton:
        fields = self.model_dump()
        low, high = fields.pop("flexion_range")
        return Skeleton(min_flexion=low, max_flexion=high, **fields)


class ForceTable(_Table):
    """A muscle's Hill-type parameters (``engine/hill.py``), as :class:`HillParameters`: N,
    cm and degrees. Each one left out is arm26's for a muscle named as one of arm26's six
    (``engine/arm26_forces.py``); another muscle must give the first four, and takes Thelen's
    curves as arm26 shapes them."""

    max_isometric_force: Annotated[float, number(FORCE)] | None = None
    optimal_fibre_length: Annotated[float, number(FIBRE)] | None = None
    tendon_slack_length: Annotated[float, number(FIBRE)] | None = None
    pennation: Annotated[float, number(PENNATION)] | None = None
    tendon_strain: Annotated[float, number(STRAIN)] | None = None
    passive_strain: Annotated[float, number(STRAIN)] | None = None
    active_shape: Annotated[float, number(SHAPE)] | None = None
    passive_shape: Annotated[float, number(SHAPE)] | None = None
    minimum_activation: Annotated[float, number(LEAST_ACTIVATION)] | None = None


class ConfigFile(_Table):
    muscle: MuscleTable
    muscles: dict[MuscleName, CompanionTable] = {}
    forces: dict[MuscleName, ForceTable] = {}
    skeleton: SkeletonTable = SkeletonTable()
    view: View = View()
    light: Light = Light()
    render: RenderSettings = RenderSettings()


def rgb(colour: str) -> tuple[int, int, int]:
    """``"#rrggbb"`` as three 0-255 integers."""
    return int(colour[1:3], 16), int(colour[3:5], 16), int(colour[5:7], 16)


@dataclass(frozen=True)
class Config:
    """Everything one file describes, ready to use; ``source`` is the text it was read from."""

    path: Path
    arm: Arm
    view: View
    light: Light
    render: RenderSettings
    source: str
    forces: dict[str, HillParameters] = field(default_factory=dict)
    """Each muscle's Hill-type parameters, by name, for the muscles that have them."""

    def force_parameters(self) -> tuple[HillParameters, ...]:
        """Every muscle's Hill-type parameters, in the order of ``arm.names``; raises
        :class:`ConfigError` naming a muscle that has none."""
        missing = [name for name in self.arm.names if name not in self.forces]
        if missing:
            name = missing[0]
            raise ConfigError(
                f"{printable(self.path)}: the muscle {printable(repr(name))} has no force "
                f"parameters: arm26 has no muscle of that name ({', '.join(PARAMETERS)}), so "
                f"give them in a [forces.{printable(name)}] table: max_isometric_force (N), "
                "optimal_fibre_length and tendon_slack_length (cm), pennation (degrees)")
        return tuple(self.forces[name] for name in self.arm.names)


LARGEST_FILE = 1 << 20
"""Bytes a configuration may have: the most nodes a model may have, one to a line with a
comment each, take about half as many. TOML is read in Python: a file of 2.4 MB of small
tables took 5 s to read, only to be refused."""

DEEPEST = 64
"""Arrays and tables nested deeper than this are refused before they are parsed (the
deepest a configuration needs is 2, ``nodes = [[radius, growth], ...]``): tomllib parses
them by recursion, and a few thousand levels exhaust Python's stack."""


def load_config(path: str | os.PathLike) -> Config:
    """Read and validate a configuration file; raises :class:`ConfigError` (or
    :class:`FileError`, for a file that cannot be read) saying why not."""
    path = Path(path)
    return _parsed(path, _read_text(path))


def _parsed(path: Path, source: str) -> Config:
    """The configuration that ``source``, read from ``path``, describes."""
    _check_nesting(path, source)
    try:
        data = tomllib.loads(source)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{printable(path)}: not valid TOML: {printable(str(error))}") from None
    except RecursionError:  # nesting that the check above did not see as such
        raise ConfigError(f"{printable(path)}: arrays or tables nested too deep to read; a "
                          "configuration needs at most 2 levels") from None
    _check_cost(path, source, data)
    try:
        table = ConfigFile.model_validate(data, context=IN_A_FILE)
    except ValidationError as error:
        raise ConfigError(_describe(path, source, error)) from None
    arm = _build_arm(path, source, table)
    return Config(path, arm, table.view, table.light, table.render, source,
                  _forces(path, source, table, arm))


def _read_text(path: Path) -> str:
    raw = read_regular_file(path, LARGEST_FILE)
    if raw.startswith(codecs.BOM_UTF8):
        raise ConfigError(
            f"{printable(path)}: starts with a byte-order mark (bytes EF BB BF), which TOML "
            "does not allow: save it as UTF-8 without a byte-order mark"
        )
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ConfigError(
            f"{printable(path)}: not a text file (byte {error.start} is not UTF-8); "
            "a configuration is a TOML text file"
        ) from None


def _check_nesting(path: Path, source: str) -> None:
    """Refuse arrays and tables nested deeper than :data:`DEEPEST`, naming where."""
    if source.count("[") + source.count("{") <= DEEPEST:
        return  # too few brackets to nest that deep: the common case, at no cost
    depth = 0
    for match in _NESTING.finditer(source):
        bracket = match.group()
        if bracket in "[{":
            depth += 1
            if depth > DEEPEST:
                line = source.count("\n", 0, match.start()) + 1
                key = _key_before(source, line)
                field = f"{key}: " if key else ""
                raise ConfigError(
                    f"{printable(path)}:{line}: {field}arrays or tables nested more than "
                    f"{DEEPEST} deep; a configuration needs at most 2 (nodes = [[radius, "
                    "growth], ...])"
                )
        elif bracket in "]}":
            depth = max(depth - 1, 0)


def _check_cost(path: Path, source: str, data: dict) -> None:
    """Refuse a file whose muscles, nodes or mesh cost more than the bounds allow, from the
    parsed TOML, before each value is validated: 10,000 muscles, or 240,000 nodes, took 12 s
    to validate only to be refused."""
    tables = [data.get("muscle"), *_values(data.get("muscles"))]
    nodes = [len(_node_list(table)) for table in tables if isinstance(table, dict)]
    render = data.get("render")
    segments = render.get("segments") if isinstance(render, dict) else None
    if not isinstance(segments, int) or isinstance(segments, bool):
        segments = RenderSettings.segments  # or wrong, which validating says
    problem = model_problem(nodes, segments)
    if problem is not None:
        over, reason = problem
        where = {"muscles": ("muscles",), "segments": ("render", "segments")}.get(over)
        if where is None:
            driver = data.get("muscle")
            where = ("muscle", "radius" if isinstance(driver, dict) and "nodes" not in driver
                     else "nodes")
        raise ConfigError(_located(path, source, where, reason))


def _values(table: Any) -> list:
    return list(table.values()) if isinstance(table, dict) else []


def _node_list(table: dict) -> list:
    nodes = table.get("nodes", table.get("radius"))
    return nodes if isinstance(nodes, list) else []


# Brackets outside strings and comments: strings and comments are matched whole and skipped.
_NESTING = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*|[\[\]{}]')


def _build_arm(path: Path, source: str, table: ConfigFile) -> Arm:
    muscle_table, skeleton_table = table.muscle, table.skeleton
    skeleton = skeleton_table.skeleton()

    def fail(location: tuple, message: str) -> ConfigError:
        return ConfigError(_located(path, source, location, message))

    problem = skeleton_problem(skeleton)
    if problem is not None:
        field, reason = problem
        raise fail(("skeleton", field), reason)
    driver_path = _driver_path(muscle_table, skeleton, fail)
    drive = skeleton if driver_path is None else PathDrive(
        driver_path, skeleton.min_flexion, skeleton.max_flexion)
    length = _length_of(muscle_table.length, muscle_table.flexion, "flexion", drive, skeleton,
                        fail)
    radii, growth = muscle_table.profile()
    try:
        muscle = Muscle.of(radii, growth, length, muscle_table.volume)
    except RefusedChange as error:
        raise fail(("muscle", muscle_table.nodes_key(str(error))), str(error)) from None
    companions = _companions(table, skeleton, driver_path, fail)
    # The companions follow the elbow from the start: each at its path's length there.
    companions = tuple(companion.at_flexion(drive.flexion(length)) for companion in companions)
    arm = Arm(muscle, skeleton, muscle_table.min_length, muscle_table.max_length,
              muscle_table.name, companions, driver_path)
    low, high = arm.length_range()
    if low > high:
        raise fail(
            ("muscle", "min_length"),
            f"the limits leave no length: min_length, max_length and the joint's range "
            f"intersect to nothing ({exactly(low)} > {exactly(high)} cm)",
        )
    _check_reach(arm, length, "flexion" if muscle_table.flexion is not None else "length", fail)
    pose = _length_of(muscle_table.pose_length, muscle_table.pose_flexion, "pose_flexion",
                      drive, skeleton, fail)
    if pose is None or pose == length:
        return arm
    pose = _check_reach(
        arm, pose, "pose_flexion" if muscle_table.pose_flexion is not None else "pose_length",
        fail,
    )
    return arm.at_length(pose)


def _driver_path(muscle_table: MuscleTable, skeleton: Skeleton,
                 fail: Callable[[tuple, str], ConfigError]) -> ViaPath | None:
    """The driver's own path, if it takes one (arm26's); checked to shorten all the way as
    the elbow bends, so that its length gives one flexion."""
    if muscle_table.path is None:
        if skeleton.model == "arm26":
            raise fail(("muscle",), "with skeleton.model = \"arm26\" the [muscle] takes arm26's "
                                    "path: add path = \"arm26\" (its name one of "
                                    f"{', '.join(arm26.MUSCLES)})")
        return None
    path = _model_path(muscle_table.name, skeleton, ("muscle",), fail)
    low, high = skeleton.min_flexion, skeleton.max_flexion
    for flexion in np.linspace(low, high, max(2, round(high - low) + 1)):
        if path.moment_arm_at(float(flexion)) <= 0.0:
            raise fail(("muscle", "path"), (
                f"{muscle_table.name} lengthens as the elbow bends at {flexion:.0f} degrees: "
                "the [muscle] drives the elbow by its length, so it must be a flexor"))
    return path


def _model_path(name: str, skeleton: Skeleton, where: tuple,
                fail: Callable[[tuple, str], ConfigError]) -> ViaPath:
    """arm26's path of the muscle ``name``, for the table at ``where``."""
    if skeleton.model != "arm26":
        raise fail((*where, "path"), "path = \"arm26\" needs arm26's bones: add model = "
                                      "\"arm26\" under [skeleton]")
    if name not in arm26.MUSCLES:
        raise fail((*where, "path"), (f"arm26 has no muscle {name!r}: a muscle on arm26's path "
                                      f"is named as arm26 names it, one of "
                                      f"{', '.join(arm26.MUSCLES)}"))
    return arm26.path(name)


REQUIRED_FORCES = ("max_isometric_force", "optimal_fibre_length", "tendon_slack_length",
                   "pennation")
"""The parameters a muscle not named as one of arm26's must give; the rest are Thelen's
curves, which default to arm26's (the same for its six)."""


def _forces(path: Path, source: str, table: ConfigFile, arm: Arm) -> dict[str, HillParameters]:
    """Each muscle's Hill-type parameters, the ``[forces.NAME]`` tables over arm26's, for
    every muscle that has them."""
    for name in table.forces:
        if name not in arm.names:
            raise ConfigError(_located(path, source, ("forces", name), (
                f"no muscle is named {name!r} in this file; its muscles are "
                f"{', '.join(arm.names)}")))
    forces = {}
    for name in arm.names:
        given = table.forces.get(name, ForceTable()).model_dump(exclude_none=True)
        default = default_parameters(name)
        if default is None and not given:
            continue
        if default is None:
            missing = [key for key in REQUIRED_FORCES if key not in given]
            if missing:
                keys = " and ".join(filter(None, (", ".join(missing[:-1]), missing[-1])))
                raise ConfigError(_located(path, source, ("forces", name), (
                    f"{keys} {'are' if len(missing) > 1 else 'is'} required: arm26 has no "
                    f"muscle named {name!r} to take {'them' if len(missing) > 1 else 'it'} "
                    f"from (its six: {', '.join(PARAMETERS)})")))
            default = HillParameters(**{key: given[key] for key in REQUIRED_FORCES}, **CURVES)
        forces[name] = HillParameters(**{**asdict(default), **given})
    return forces


def _companions(table: ConfigFile, skeleton: Skeleton, driver_path: ViaPath | None,
                fail: Callable[[tuple, str], ConfigError]) -> tuple[Companion, ...]:
    """The ``[muscles.NAME]`` tables as companions at rest, checked to follow the elbow over
    the joint's whole range."""
    companions = []
    paths = {table.muscle.name: driver_path or MusclePath(skeleton.origin, skeleton.insertion)}
    for index, (name, companion_table) in enumerate(table.muscles.items()):
        where = ("muscles", name)
        if name == table.muscle.name:
            raise fail(where, f"{name!r} is the [muscle]'s name already: give each muscle "
                              "its own")
        if companion_table.path is not None:
            path = _model_path(name, skeleton, where, fail)
        else:
            path = companion_table.own_path()
        # The path first: a muscle with nowhere to lie cannot be given a length.
        problem = _path_problem(path, skeleton, paths)
        if problem is not None:
            raise fail((*where, problem[0]), problem[1])
        paths[name] = path
        length = companion_table.length
        if companion_table.flexion is not None:
            _check_flexion(companion_table.flexion, skeleton, (*where, "flexion"), fail)
            length = path.length_at(companion_table.flexion)
        radii, growth = companion_table.profile()
        try:
            muscle = Muscle.of(radii, growth, length, companion_table.volume)
        except RefusedChange as error:
            raise fail((*where, companion_table.nodes_key(str(error))), str(error)) from None
        colour = companion_table.colour or COMPANION_COLOURS[index % len(COMPANION_COLOURS)]
        companion = Companion(name, muscle, path, colour)
        problem = reach_problem(companion, skeleton.min_flexion, skeleton.max_flexion)
        if problem is not None:
            raise fail((*where, companion_table.nodes_key("growth")), problem)
        companions.append(companion)
    return tuple(companions)


def _path_problem(path: MusclePath | ViaPath, skeleton: Skeleton,
                  others: dict[str, MusclePath | ViaPath]) -> tuple[str, str] | None:
    """The key to blame and why, if ``path``'s attachments cannot hold a muscle over the
    joint's range (off their bones, where one of the ``others`` by name already runs,
    meeting, inside the wrapping cylinder); None if they can."""
    for key, attachment in (("origin", path.origin), ("insertion", path.insertion)):
        problem = attachment_problem(attachment, skeleton)
        if problem is not None:
            return key, problem[1]
    for name, other in others.items():
        if all(np.allclose(mine.in_frame(), theirs.in_frame(), rtol=0.0, atol=SAME_PLACE)
               for mine, theirs in ((path.origin, other.origin),
                                    (path.insertion, other.insertion))):
            return "origin", (f"runs where {name} runs, from the same origin to the same "
                              "insertion: give each muscle its own path")
    for flexion in (skeleton.min_flexion, skeleton.max_flexion):
        start, end = path.ends(flexion)
        if np.linalg.norm(end - start) < 0.5:
            return "insertion", (f"origin and insertion come within 0.5 cm of each other at "
                                 f"{flexion:g} degrees of flexion: a muscle needs room")
    if isinstance(path, MusclePath) and path.wrap is not None:
        for key, attachment in (("origin", path.origin), ("insertion", path.insertion)):
            reach = float(np.hypot(*attachment.in_frame()[:2]))
            if reach <= path.wrap.radius:
                return key, (f"lies {reach:.2f} cm from the elbow's axis, inside the wrapping "
                             f"cylinder of wrap_radius {path.wrap.radius:g} cm: it must lie "
                             "outside it")
    return None


def _length_of(length: float | None, flexion: float | None, flexion_key: str,
               drive: Skeleton | PathDrive, skeleton: Skeleton,
               fail: Callable[[tuple, str], ConfigError]) -> float | None:
    """The muscle length (cm) that ``length`` gives, or ``flexion`` (degrees) under
    ``muscle.flexion_key`` through the ``drive``, if either."""
    if flexion is None:
        return length
    _check_flexion(flexion, skeleton, ("muscle", flexion_key), fail)
    return drive.length_at(flexion)


def _check_flexion(flexion: float, skeleton: Skeleton, location: tuple,
                   fail: Callable[[tuple, str], ConfigError]) -> None:
    """Refuse ``flexion`` (degrees), found at ``location``, outside the joint's range."""
    if not skeleton.min_flexion <= flexion <= skeleton.max_flexion:
        raise fail(location, f"{flexion:g} degrees is outside skeleton.flexion_range, "
                             f"{skeleton.min_flexion:g} to {skeleton.max_flexion:g}")


def _check_reach(arm: Arm, length: float, key: str,
                 fail: Callable[[tuple, str], ConfigError]) -> float:
    """``length``, which ``muscle.key`` gave, if the arm can reach it; a hair outside the
    range (a flexion's rounding) is taken as the limit."""
    low, high = arm.length_range()
    if not low - 1e-9 <= length <= high + 1e-9:
        raise fail(
            ("muscle", key),
            f"length {cm(length)} cm is outside what the skeleton and limits allow: "
            f"{low:.2f} to {high:.2f} cm",
        )
    return min(max(length, low), high)


SAME_PLACE = 0.01
"""cm: attachments closer than this are one place."""

MOST_PROBLEMS = 5
"""Problems a message lists; a file with thousands of bad nodes gets the first few and a count."""


def _describe(path: Path, source: str, error: ValidationError, within: tuple = ()) -> str:
    """One line per problem: ``file:line: field.path: what is wrong (found ...)``; ``within``
    is the path of the table validated, when it is not the whole file."""
    problems = error.errors(include_url=False)
    lines = [_located(path, source, (*within, *problem["loc"]), _problem(within, problem))
             for problem in problems[:MOST_PROBLEMS]]
    if len(problems) > MOST_PROBLEMS:
        lines.append(f"{printable(path)}: and {len(problems) - MOST_PROBLEMS:,} more problems "
                     "like these")
    return "\n".join(lines)


def _problem(within: tuple, problem: dict) -> str:
    location, kind, found = (*within, *problem["loc"]), problem["type"], problem["input"]
    refusal = problem.get("ctx", {}).get("error")
    if isinstance(refusal, OutOfBounds):
        return f"must be {refusal.wanted} (found {printable(refusal.found)})"
    if kind in ("extra_forbidden", "unexpected_keyword_argument"):  # a model's, a dataclass's
        return _unknown_key_message(location)
    if kind == "missing" and len(location) == 1:
        return f"the [{location[0]}] table is required, but missing"
    if kind == "missing":
        return "required, but missing"
    if kind == "string_pattern_mismatch" and location[-1] in ("[key]", "name"):  # a muscle's
        return (f"a muscle's name is 1 to 40 letters, digits, '_' or '-' "
                f"(found {printable(quoted(found))})")
    if kind == "string_pattern_mismatch":  # the other patterns are colours
        return f"should be {COLOUR_WANTED} (found {printable(quoted(found))})"
    message = problem["msg"].removeprefix("Value error, ")
    if kind == "value_error":
        return message
    if isinstance(found, dict):  # a table where a value belongs, as a dotted key makes
        return f"{message} (found a table)"
    return f"{message} (found {printable(quoted(found))})"


def _unknown_key_message(location: tuple) -> str:
    *parents, key = location
    model: Any = ConfigFile
    for part in parents:
        if isinstance(model, _NamedTables):  # part is the table's name
            model = model.table
            continue
        field = model.__pydantic_fields__.get(part) if isinstance(part, str) else None
        annotation = getattr(field, "annotation", None)
        if get_origin(annotation) is dict:  # [muscles.NAME]: any name, each one table
            model = _NamedTables(get_args(annotation)[1])
        elif hasattr(annotation, "__pydantic_fields__"):  # a table: a model or a setting
            model = annotation
        else:
            model = None
            break
    allowed = list(model.__pydantic_fields__) if isinstance(model, type) else []
    message = f"unknown key {printable(quoted(str(key)))}"
    close = difflib.get_close_matches(str(key), allowed, n=1)
    if parents and key in ConfigFile.model_fields:
        # Rather than a near name by its letters (skeleton is not pose_flexion misspelt).
        message += f" ([{key}] is a table of its own: write its keys under a [{key}] header)"
    elif close:
        message += f" (did you mean {close[0]!r}?)"
    if allowed:
        message += f"; allowed here: {', '.join(allowed)}"
    return message


@dataclass(frozen=True)
class _NamedTables:
    """A table of tables by any name (``[muscles.NAME]``), each a ``table``."""

    table: type


def _located(path: Path, source: str, location: tuple, message: str) -> str:
    # pydantic marks a problem with a table's name (a key of [muscles]) as its "[key]".
    location = tuple(part for part in location if part != "[key]")
    # A key of thousands of letters is shown by its start: the message quotes it whole.
    dotted = ".".join(printable(part if len(part) <= 40 else f"{part[:37]}...")
                      for part in location if isinstance(part, str))
    for part in location:
        if isinstance(part, int):
            dotted += f"[{part}]"
    line = _line_of(source, location)
    where = f"{printable(path)}:{line}" if line else printable(path)
    return f"{where}: {dotted}: {message}" if dotted else f"{where}: {message}"


# A header is alone on its line, so a node written [0.35, 0.0], inside a list is not one.
# Matched against the stripped line, and possessively (*+, ++): a key's characters include
# the space, and with the lazy key between optional spaces of the patterns before these, a
# line of 2,000 spaces cost seconds to match (n^3), one of 100,000 for ever.
_KEY = r"[A-Za-z0-9_\-.\"' ]"
_TABLE_HEADER = re.compile(rf"\[\[?({_KEY}*+)\]\]?\s*+(?:#.*)?")
_ASSIGNMENT = re.compile(rf"({_KEY}++)\s*+=")


def _keys_by_line(source: str):
    """Each table header and each assignment of ``source``: (line, the full dotted path of
    what it names, as a tuple of keys), dotted keys and quoted keys taken apart."""
    table: tuple[str, ...] = ()
    for number, line in enumerate(source.splitlines(), start=1):
        line = line.strip()
        header = _TABLE_HEADER.fullmatch(line)
        if header and header.group(1).strip():
            table = _dotted(header.group(1))
            yield number, table
            continue
        assignment = _ASSIGNMENT.match(line)
        if assignment and assignment.group(1).strip():
            yield number, table + _dotted(assignment.group(1))


def _dotted(key: str) -> tuple[str, ...]:
    return tuple(part.strip().strip("\"'") for part in key.split("."))


def _line_of(source: str, location: tuple) -> int | None:
    """The 1-based line where the key at ``location`` is written, when it can be found.

    pydantic knows field paths but not TOML lines, so this finds the header or assignment
    that names the key, or a dotted key inside it (``nodes.x = 1`` makes ``nodes`` a
    table); good enough for the layouts people write.
    """
    keys = tuple(part for part in location if isinstance(part, str))
    if not keys:
        return None
    for number, path in _keys_by_line(source):
        if path[:len(keys)] == keys:
            return number
    return None


def _key_before(source: str, line: int) -> str:
    """The dotted key last assigned (or table opened) at or before ``line``."""
    named = ""
    for number, path in _keys_by_line(source):
        if number > line:
            break
        named = ".".join(printable(part) for part in path)
    return named


def save_config(config: Config, arm: Arm, view: View, light: Light, render: RenderSettings,
                path: str | os.PathLike | None = None, *, overwrite: bool = False) -> Config:
    """Write ``arm`` and the settings into ``config``'s document and replace the file atomically.

    Only values that differ from what the file says (or implies by default) are written, so
    the user's comments, order and layout survive. ``path`` saves a copy elsewhere ("save
    as"). The new text is read back as :func:`load_config` would read it before anything is
    written, so a save never leaves a file that does not load. Saving over the file the
    configuration was read from raises :class:`FileChanged` if someone changed that file
    since, unless ``overwrite``. Returns the configuration as now on disk; raises
    :class:`ConfigError` (the new text would not load) or :class:`FileError` (it cannot be
    written) and then leaves every file as it was.
    """
    target = Path(path) if path is not None else config.path
    document = tomlkit.parse(config.source)
    try:
        _write_muscle(document, arm, config.arm)
        _write_changes(target, document, {"skeleton": arm.skeleton, "view": view,
                                          "light": light, "render": render})
        text = tomlkit.dumps(document)
        saved = _parsed(target, text)
    except ConfigError as error:
        raise ConfigError(f"not saved (nothing was written): {error}") from None
    if not overwrite and same_file(target, config.path) and _changed_on_disk(config):
        raise FileChanged(f"{printable(target)}: changed on disk since it was read; saving "
                          "would lose those changes, so nothing was written")
    write_atomically(target, text.encode("utf-8"))
    return saved


def _changed_on_disk(config: Config) -> bool:
    try:
        return read_regular_file(config.path, LARGEST_FILE) != config.source.encode("utf-8")
    except FileError:  # gone, or no longer a file: writing it will say what is wrong
        return False


def _write_muscle(document: tomlkit.TOMLDocument, arm: Arm, before: Arm) -> None:
    """The shape as authored and the pose apart: the nodes are the reference (rest) shape at
    the reference length, and ``pose_length`` (or ``pose_flexion``) the length shown. A
    contraction changes the pose alone; a node edit makes the shape at the current length
    the new reference (SPEC 2.2), and so rewrites the nodes and the length. ``before`` is
    the arm the document describes as it stands.

    Values are changed in place where the node count is the same, so the comments beside
    the nodes survive; a different count rewrites the list.
    """
    muscle = arm.muscle
    table = document["muscle"]
    _write_shape(table, muscle, before.muscle,
                 lambda: arm.drive.flexion(muscle.reference_length))
    for companion, earlier in zip(arm.companions, before.companions):
        # A companion's shape is redefined where it is, so at the arm's flexion.
        _write_shape(document["muscles"][companion.name], companion.muscle, earlier.muscle,
                     lambda: arm.flexion)
    if "pose_flexion" in table:
        if muscle.length != before.length:
            _update_value(table, "pose_flexion", arm.flexion)
    elif "pose_length" in table:
        _update_value(table, "pose_length", muscle.length)
    elif muscle.length != muscle.reference_length:
        pose = tomlkit.item(muscle.length)
        pose.comment("cm as shown: the shape above, contracted or stretched at constant volume")
        pose.trivia.comment_ws = "  "
        table["pose_length"] = pose


def _write_shape(table: Any, muscle: Muscle, before: Muscle, flexion: Callable[[], float]) -> None:
    """A muscle's nodes, reference length (or the ``flexion()`` it is at, if the table gives
    a flexion) and volume mode into its ``table``, where they differ from ``before``."""
    # Plain floats print their shortest exact form, so load -> save -> load is exact.
    radii = muscle.reference_radii.tolist()
    growth = muscle.growth.tolist()
    if "nodes" in table:
        _update_list(table, "nodes", [[r, m] for r, m in zip(radii, growth)])
    else:
        _update_list(table, "radius", radii)
        _update_list(table, "growth", growth)
    if muscle.reference_length != before.reference_length:
        if "flexion" in table:
            _update_value(table, "flexion", flexion())
        else:
            _update_value(table, "length", muscle.reference_length)
    if table.get("volume", "closed") != muscle.volume_mode:
        table["volume"] = muscle.volume_mode


def _update_list(table: Any, key: str, values: list) -> None:
    current = table[key]
    if len(current) != len(values):
        array = tomlkit.array()
        array.extend(values)
        table[key] = array.multiline("\n" in current.as_string())
        return
    for index, value in enumerate(values):
        if isinstance(value, list):
            for inner, item in enumerate(value):
                _update_value(current[index], inner, item)
        else:
            _update_value(current, index, value)


def _update_value(container: Any, key: Any, value: float) -> None:
    if container[key] != value:
        container[key] = value


def _write_changes(path: Path, document: tomlkit.TOMLDocument, settings: dict[str, Any]) -> None:
    """Write the fields of each setting (``{table name: setting}``) that differ from its table
    in ``document``, once every one is checked as the file's table: a value that bypassed its
    own checks, or that a file may not name (the "overdraw" shading), is refused."""
    given = {name: _keys_of(setting) for name, setting in settings.items()}
    try:
        checked = _Saved.model_validate(given, context=IN_A_FILE)
    except ValidationError as error:
        raise ConfigError(_describe(path, "", error)) from None
    for name in settings:
        new = _keys_of(getattr(checked, name))
        default = _keys_of(ConfigFile.model_fields[name].default)
        existing = document.get(name)
        for key, value in new.items():
            current = existing.get(key, default[key]) if existing else default[key]
            if _same(current, value):
                continue
            if existing is None:
                existing = document[name] = tomlkit.table()
            existing[key] = list(value) if isinstance(value, tuple) else value


class _Saved(_Table):
    """The tables a save writes besides the muscles'."""

    skeleton: SkeletonTable
    view: View
    light: Light
    render: RenderSettings


def _keys_of(setting: Any) -> dict[str, Any]:
    """A setting's fields, or a skeleton's, by the keys of its table in a file."""
    if isinstance(setting, Skeleton):
        return SkeletonTable.keys_of(setting)
    if isinstance(setting, BaseModel):
        return setting.model_dump()
    return asdict(setting)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
        return list(a) == list(b)
    return a == b

