"""Which points a sweep visits: ``--vary`` words read against config.xacro's units, as a
grid or as seeded random samples.

A word is ``NAME=LO..HI:N`` (N values, both ends included), ``NAME=A,B,C`` (those values)
or, with ``--samples``, ``NAME=LO..HI`` (uniform between the ends). Every value is read as
``--set`` reads one (``25mm``, ``0.14``, ``90deg``). Values outside a dimension's plausible
range are not refused here: the points that hold them become rejected rows, which is how a
sweep shows where the constraints bite. Only what can never make a point (an unknown or
derived name, a malformed word) is a usage error.
"""

from __future__ import annotations

import itertools
import random
from dataclasses import dataclass

from ..config.spec import ConfigSpec, settable_dimension
from ..config.units import parse_quantity
from ..errors import UsageError

MAX_POINTS = 1_000_000  # a typo (":9000" for ":9") must not queue a day of work
MAX_VALUES = 100_000


@dataclass(frozen=True)
class Axis:
    """One varied dimension: a list of values, or (for samples) the interval they come from."""

    name: str
    unit: str
    values: tuple[float, ...] = ()
    interval: tuple[float, float] | None = None


@dataclass(frozen=True)
class Point:
    index: int
    values: dict[str, float]

    def key(self) -> tuple[float, ...]:
        """What identifies the point in a results file (for --resume)."""
        return tuple(self.values.values())


def clean(value: float) -> float:
    """12 significant digits: 0.025 + 7 * 0.0025 is 0.0425, not 0.042499999999999996."""
    return float(f"{value:.12g}")


def parse_vary(spec: ConfigSpec, word: str, sampling: bool) -> Axis:
    name, sep, text = word.partition("=")
    name, text = name.strip(), text.strip()
    origin = f"--vary {word}"
    if not sep or not name or not text:
        raise UsageError(f"{origin}: expected NAME=LO..HI:N or NAME=A,B,C, "
                         "e.g. wheel_radius=25mm..45mm:9")
    dimension = _dimension(spec, name, origin)

    def number(part: str) -> float:
        value = parse_quantity(part.strip(), dimension.unit, f"{origin}: {name}")
        return float(round(value)) if dimension.unit == "count" else value

    if ".." not in text:
        values = [number(part) for part in text.split(",")]
        return Axis(name, dimension.unit, tuple(dict.fromkeys(clean(v) for v in values)))
    span, colon, count_text = text.rpartition(":") if ":" in text else (text, "", "")
    low_text, _, high_text = span.partition("..")
    if not low_text.strip() or not high_text.strip():
        raise UsageError(f"{origin}: a range is LO..HI, both ends given")
    low, high = number(low_text), number(high_text)
    if low > high:
        raise UsageError(f"{origin}: the range is empty ({low:g} > {high:g} {dimension.unit})")
    if not colon:
        if not sampling:
            raise UsageError(f"{origin}: a grid needs the number of values, "
                             f"e.g. {name}={span}:5 (or sample it with --samples N)")
        return Axis(name, dimension.unit, interval=(low, high))
    count = _count(count_text, origin)
    if count == 1 and low != high:
        raise UsageError(f"{origin}: one value cannot span {low:g}..{high:g}; give :2 or more")
    values = [low + (high - low) * i / (count - 1) for i in range(count)] if count > 1 else [low]
    if dimension.unit == "count":
        values = [float(round(v)) for v in values]
    return Axis(name, dimension.unit, tuple(dict.fromkeys(clean(v) for v in values)),
                interval=(low, high))


def _dimension(spec: ConfigSpec, name: str, origin: str):
    dimension = settable_dimension(spec, name, origin, verb="vary")
    if dimension.baked:
        raise UsageError(f"{origin}: {name} is baked into a mesh (scripts/make_meshes.py) "
                         "and cannot vary")
    return dimension


def _count(text: str, origin: str) -> int:
    try:
        count = int(text.strip())
    except ValueError:
        raise UsageError(f"{origin}: the number of values after ':' must be a whole number, "
                         f"not {text.strip()!r}") from None
    if not 1 <= count <= MAX_VALUES:
        raise UsageError(f"{origin}: the number of values must be 1..{MAX_VALUES}, not {count}")
    return count


def read_axes(spec: ConfigSpec, words, sampling: bool) -> list[Axis]:
    if not words:
        raise UsageError("nothing to sweep: give --vary NAME=LO..HI:N (e.g. "
                         "--vary wheel_radius=25mm..45mm:9), repeatable")
    axes = [parse_vary(spec, word, sampling) for word in words]
    names = [axis.name for axis in axes]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise UsageError(f"--vary names {', '.join(twice)} more than once")
    return axes


def grid(axes: list[Axis]) -> list[Point]:
    """Every combination; the first --vary changes slowest."""
    total = 1
    for axis in axes:
        total *= len(axis.values)
    if total > MAX_POINTS:
        raise UsageError(f"the grid has {total:,} points, more than {MAX_POINTS:,}: "
                         "fewer values per --vary, or --samples N")
    names = [axis.name for axis in axes]
    return [Point(i, dict(zip(names, combo, strict=True)))
            for i, combo in enumerate(itertools.product(*(axis.values for axis in axes)))]


def samples(axes: list[Axis], count: int, seed: int) -> list[Point]:
    """``count`` points drawn with ``random.Random(seed)``: uniform over each interval (whole
    numbers for a count) for ``LO..HI``, else one of the axis's values; the same seed, the
    same points."""
    if not 1 <= count <= MAX_POINTS:
        raise UsageError(f"--samples must be 1..{MAX_POINTS:,}, not {count}")
    rng = random.Random(seed)
    points = []
    for i in range(count):
        values = {}
        for axis in axes:
            if axis.values:  # a list, or LO..HI:N: one of those values
                values[axis.name] = rng.choice(axis.values)
            elif axis.unit == "count":
                values[axis.name] = float(rng.randint(int(axis.interval[0]),
                                                      int(axis.interval[1])))
            else:
                values[axis.name] = clean(rng.uniform(*axis.interval))
        points.append(Point(i, values))
    return points
