"""The numbers the model takes: every bound written once, here, and said the same way
wherever a number comes from (a file, a dialog, a key, the command line, a script).

The model's bounds are what it can compute in float64 and draw: the volume takes cubes
of radii and squares of growth coefficients, so a radius of 1e-162 underflows to a volume
of 0 and one of 1e300 overflows to inf; a growth of 1e-160 has a square of 0, and no length
change can be solved from it; a light 1e308 cm away lights nothing. The bounds leave every
shape that makes sense, from a muscle of a micrometre to one of a hundred metres, many
orders of magnitude from where floating point fails.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Integral, Real
from typing import Any


@dataclass(frozen=True)
class Limits:
    """The numbers a setting allows: ``low`` or more, up to ``high`` if there is one; the
    ends themselves excluded when ``exclusive``."""

    low: float
    high: float | None = None
    exclusive: bool = False
    unit: str = ""

    def allows(self, value: float) -> bool:
        if self.exclusive:
            return value > self.low and (self.high is None or value < self.high)
        return value >= self.low and (self.high is None or value <= self.high)

    def __str__(self) -> str:
        return self.of("")

    def of(self, kind: str) -> str:
        """The allowed values in words, each one ``kind``: ``a finite number from 1 to 4``."""
        low, high, unit = self.low, self.high, self.unit
        if high is None:
            text = f"above {low:g}{unit}" if self.exclusive else f"{low:g}{unit} or more"
        elif self.exclusive:
            text = f"above {low:g} and below {high:g}{unit}"
        else:
            text = f"from {low:g} to {high:g}{unit}"
        return f"{kind} {text}" if kind else text


class OutOfBounds(ValueError):
    """A value that is not what is wanted: ``found`` shows the value, ``wanted`` says in
    words what is allowed, and the message puts the two together."""

    def __init__(self, found: str, wanted: str) -> None:
        super().__init__(f"must be {wanted}, not {found}")
        self.found = found
        self.wanted = wanted


def finite(value: Any, limits: Limits | None = None) -> float:
    """``value`` as a float: a finite real number (a bool is not one) within ``limits``;
    otherwise :class:`OutOfBounds`."""
    if isinstance(value, Real) and not isinstance(value, bool):
        try:
            number = float(value)
        except OverflowError:  # an integer too long for a float
            number = math.inf
        if math.isfinite(number) and (limits is None or limits.allows(number)):
            return number
    wanted = "a finite number" if limits is None else limits.of("a finite number")
    raise OutOfBounds(quoted(value), wanted)


def whole(value: Any, limits: Limits) -> int:
    """``value`` as an int: a whole number (not a bool, nor a float such as 2.0) within
    ``limits``; otherwise :class:`OutOfBounds`."""
    if isinstance(value, Integral) and not isinstance(value, bool) and limits.allows(value):
        return int(value)
    raise OutOfBounds(quoted(value), limits.of("a whole number"))


def exactly(value: float) -> str:
    """``value`` as short as it can be written and still read back as itself: ``130`` for
    130.0, every digit of 30.999 or of 60.000000001 (which ``:g`` shows as 31 and 60)."""
    short = f"{value:g}"
    return short if float(short) == value else repr(value)


def cm(value: float) -> str:
    """A length (cm) as a message gives one it was asked for: to two places (``30.14``),
    or where those would run to hundreds of digits (1e308), to three figures."""
    return f"{value:.2f}" if abs(value) < 1e6 else f"{value:.3g}"


def quoted(value: Any) -> str:
    """A value as a message quotes it: its repr, shortened; a long integer by its length."""
    text = repr(value)
    if isinstance(value, Integral) and not isinstance(value, bool) and len(text) > 20:
        return f"a {len(text.lstrip('-'))}-digit integer"
    return text if len(text) <= 60 else text[:57] + "..."


RADIUS = Limits(1e-6, 1e4, unit=" cm")
"""A node's radius: a micrometre to a hundred metres."""

GROWTH = Limits(0, 1e4)
"""A node's growth coefficient: 0 (a tendon) up to, like the radius it scales, 1e4."""

GROWING = 1e-6
"""The growth at least one node must have. The volume's quadratic term in the length change
is the sum of the squared growths: at 1e-160 it underflows to 0 and no length can be solved
(a node growing by less beside it is fine: a subdivided tendon grows by half its neighbour)."""

BONE = Limits(1e-6, 1e6, unit=" cm")
"""Each of the skeleton's four distances."""

COORDINATE = Limits(-1e8, 1e8, unit=" cm")
"""Each coordinate of a point in world space (the light) or of a move (the view's offset):
a hundred times the largest skeleton away, where the picture still computes in float32."""

SCALE = Limits(0.01, 100)
"""The view's zoom."""

NODES = 20_000
"""The most nodes a model may have, all its muscles together. Each node is a ring of the
mesh, made again at every length change: at 20,000 nodes that picture takes about 0.9 s
and the process 0.7 GB, at 100,000 about 6 s and 2.6 GB, against 5 ms and 0.16 GB at 15
(benchmarks/app_nodes.py). A picture has far fewer rows of pixels than that, so more nodes
could not be seen anyway."""

MUSCLES = 16
"""The most muscles a model may have, the driver among them: each one is laid on the bones
and round the muscles before it at every pose (the elbow's six; an arm has about a dozen
muscles that cross the elbow)."""

LAYING = 40_000
"""The most the muscles may cost to lay round each other: their number times their nodes
together. Each muscle's sections keep clear of every section laid before it, at every
pose, and its lean round the humerus is chosen over the elbow's range: 16 muscles of 156
nodes (39,936) take 9 s of CPU a snapshot and 12 s an export, 16 of 300 (76,800) took
40 s of a shared machine's wall time a snapshot (benchmarks/bad_files.py)."""

MESH_VERTICES = 1_000_000
"""The most vertices the muscles' meshes may have together: every muscle's nodes times the
segments round it (``[render] segments``), 20,000 nodes at 50 segments, which take 11 s of
CPU to export as OBJ and 0.7 GB. At 1,024 segments 20,000 nodes took 6 GB
(benchmarks/bad_files.py)."""

PICTURE_BYTES = 3 << 29
"""The most memory (1.5 GiB) a picture's buffers may take: a colour (3 bytes) and a depth
(4) per sample, ``ssaa`` x ``ssaa`` samples a pixel, and the picture averaged down (3 a
pixel). 8192 x 8192 pixels take 0.47 GB, with 2 x 2 supersampling 1.9 GB."""

ANIMATION_BYTES = 3 << 29
"""The most memory (1.5 GiB) an animation's frames may take while they are encoded: each
different frame kept (3 bytes a pixel) and its copy in the encoder (up to 4)."""

ANGLE = Limits(-360, 360, unit=" degrees")
"""How far the view is turned about each axis: a turn either way (the app keeps its turns
within half of one). At 1e308 degrees the sine is an accident of floating point."""

FLEXION_SPAN = 1.0
"""The narrowest range the elbow may have, in degrees: a muscle's fine step (0.1 cm) moves
the elbow about 1 degree."""

BONE_RATIO = 4.0
"""The most one bone (the upper arm, the forearm) may be longer than the other: an adult's
differ by 15 %; one a thousand times the other is no arm."""

ATTACHMENT_ALONG = (-0.25, 1.25)
"""Where along its bone a muscle may hold on, as fractions of the bone's length from the
elbow: from a quarter behind the elbow's centre (the olecranon, above it) to a quarter past
the far end (the shoulder blade, above the humeral head); on the forearm, not past the hand
(1.0)."""

ATTACHMENT_REACH = 0.5
"""How far from its bone's axis a muscle may hold on, as a fraction of the bone's length
(arm26's farthest, the triceps' long head on the shoulder blade, is 0.15 of the humerus)."""

FORCE = Limits(1e-3, 1e5, unit=" N")
"""A muscle's maximum isometric force (``engine/hill.py``): a millinewton to 100 kN, some
thirty times the strongest human muscle's."""

FIBRE = Limits(1e-3, 1e4, unit=" cm")
"""A muscle's optimal fibre length and its tendon's slack length."""

PENNATION = Limits(0, 84, unit=" degrees")
"""A muscle's pennation at its optimal fibre length: below the model's maximum pennation,
84.26 degrees, where a fibre can shorten no further."""

STRAIN = Limits(1e-3, 10)
"""The tendon's strain at the maximum isometric force, and the fibre's at which its passive
force reaches it."""

SHAPE = Limits(1e-2, 100)
"""The shapes of the active and passive force-length curves."""

LEAST_ACTIVATION = Limits(0.01, 1)
"""A muscle's minimum activation: OpenSim's Thelen2003Muscle allows no less than 0.01."""

ACTIVATION = Limits(0, 1)
"""An activation asked for: none to full."""

MASS = Limits(0, 1e3, unit=" kg")
"""A mass in the hand."""
