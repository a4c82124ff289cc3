"""The plausible range of a dimension, as config.xacro's comment states it: ``LO..HI``.

Each end is written as ``--set`` takes a value (``5mm..0.5m``, ``0..20mm``,
``-0.5m..0.5m``, ``1..100000``), with no spaces, and both ends are included. A range says
what a small kit robot plausibly has, so that a slip ("40" meant as 40 mm) is caught; it is
not a check that the numbers fit together (config.xacro's xacro.fatal checks do that).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ..errors import UsageError
from .units import is_bare_number, parse_quantity

# What a value of each unit is, for messages and `mcar config --format json`.
KINDS = {"m": "length", "kg": "mass", "rad": "angle", "count": "count", "Hz": "rate",
         "rad/s": "rate", "kg/m^3": "density", "N*m": "torque", "1": "ratio"}
# Units a person often means when typing a bare number, most likely first: the hint for a
# bare number outside the range names the first that brings it inside.
_HINT_UNITS = {"m": ("mm", "cm"), "kg": ("g",), "rad": ("deg",), "rad/s": ("rpm",),
               "kg/m^3": ("g/cm^3",)}
_DIMENSIONLESS = ("1", "count")
_NUMBER_THEN_UNIT = re.compile(r"^([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?=\D)")


@dataclass(frozen=True)
class Range:
    """LO..HI in the dimension's SI unit, and the text it was written as."""

    low: float
    high: float
    text: str
    unit: str

    def __contains__(self, value: float) -> bool:
        return self.low <= value <= self.high

    @property
    def shown(self) -> str:
        """The range for a message: "5 mm..0.5 m", a bare end given its SI unit."""
        return "..".join(self._end(end) for end in self.text.split("..", 1))

    def _end(self, end: str) -> str:
        if is_bare_number(end):
            return end if self.unit in _DIMENSIONLESS else f"{end} {self.unit}"
        return _NUMBER_THEN_UNIT.sub(r"\1 ", end)


def parse_range(text: str, unit: str) -> Range:
    """``LO..HI`` in ``unit``; ValueError says what is wrong with it."""
    low_text, sep, high_text = text.partition("..")
    if not sep or not low_text or not high_text:
        raise ValueError(f"range {text!r} is not LO..HI (e.g. 5mm..0.5m)")
    try:
        low = parse_quantity(low_text, unit, "its low end")
        high = parse_quantity(high_text, unit, "its high end")
    except UsageError as error:
        raise ValueError(f"range {text!r}: {error.message}") from None
    if low > high:
        raise ValueError(f"range {text!r} is empty: {low:g} > {high:g} {unit}")
    if unit == "count" and not (low.is_integer() and high.is_integer()):
        raise ValueError(f"range {text!r}: a count's range has whole ends")
    if unit == "count":  # shown as 1..100000 in JSON too, not 1.0
        low, high = int(low), int(high)
    return Range(low, high, text, unit)


def outside_message(name: str, raw, value: float, unit: str, plausible: Range) -> str:
    """``name = VALUE is outside LO..HI``, with a unit hint for a bare number."""
    si = f"{value:g}" if unit in _DIMENSIONLESS else f"{value:g} {unit}"
    given = si if is_bare_number(raw) else f"{str(raw).strip()} ({si})"
    return f"{name} = {given} is outside {plausible.shown}{unit_hint(raw, unit, plausible)}"


def unit_hint(raw, unit: str, plausible: Range) -> str:
    """"; did you mean 40mm?" when a bare number read in a common unit fits the range."""
    candidate = meant_unit(raw, unit, plausible)
    return f"; did you mean {str(raw).strip()}{candidate}?" if candidate else ""


def _just_outside(value: float, plausible: Range) -> bool:
    """A value less than twice past an end of the range was meant as written and is a bit
    too big or small (a 0.6 m wheel for at most 0.5 m), not a unit slip: a number in mm,
    cm, g, deg or rpm read as SI is 10 to 1000 times off, so a slip lands far outside.
    Ranges reaching zero or below are only judged at their far ends."""
    if value > plausible.high:
        return plausible.high > 0 and value <= 2 * plausible.high
    if value < plausible.low:
        if plausible.low > 0:
            return value >= plausible.low / 2
        return plausible.low < 0 and value >= 2 * plausible.low
    return False


def meant_unit(raw, unit: str, plausible: Range) -> str | None:
    """The first common unit (mm, g, deg...) that, read for a bare number, brings it inside
    the range; None for a number with a unit, or when none does."""
    if not is_bare_number(raw):
        return None
    number = str(raw).strip()
    if _just_outside(float(number), plausible):
        return None
    for candidate in _HINT_UNITS.get(unit, ()):
        try:
            if parse_quantity(f"{number}{candidate}", unit, "hint") in plausible:
                return candidate
        except UsageError:
            return None
    return None
