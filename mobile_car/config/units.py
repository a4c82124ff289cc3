"""Read a dimension given by a person ("65mm", "6.5 cm", "90deg", "0.0325") as SI.

One grammar for every way a value arrives (``--set``, a ``--config`` file, a range in
config.xacro): a bare number, which is already SI, or ONE number followed by a unit.
Anything else (``1/25``, ``4 0mm``, ``0x10``, ``1_000``) is refused by name rather than
handed to pint, whose parser evaluates expressions (``4 0mm`` is 4 * 0 mm to it). The unit
is converted with pint, imported only then (it is slow to import), and must have the
dimension the config entry expects: a length for ``m``, a mass for ``kg``, and so on.
The few units config.xacro's ranges and most overrides are written in (mm, cm, deg, ...)
are converted without pint, to the very float pint gives (tests/config/test_units.py
compares the two): importing pint and making its registry cost ~0.6 s of CPU, which every
`mcar config`, `--set` and `mcar sweep` paid before doing anything.
"""

from __future__ import annotations

import functools
import math
import re

from ..errors import UsageError

# Longer is no quantity a person writes, and pint's parser need not see it.
_MAX_TEXT = 100

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_BARE_NUMBER = re.compile(_NUMBER)
# A unit is words ("mm", "kg", "rpm", "°", "%") joined by *, /, · or spaces, each word
# maybe raised to an integer power (cm^3, m**2); a word never starts with a digit, so a
# second number ("4 0mm") or a hex prefix ("0x10") is no unit.
_UNIT_WORD = r"(?:[^\W\d_][^\W\d]*|°|%)(?:(?:\^|\*\*)-?\d+)?"
_QUANTITY = re.compile(rf"(?P<number>{_NUMBER})\s*"
                       rf"(?P<unit>{_UNIT_WORD}(?:\s*[*/·]\s*{_UNIT_WORD}|\s+{_UNIT_WORD})*)")
_NOT_FINITE = re.compile(r"[-+]?\.?(?:inf|infinity|nan)\b", re.I)
_EXPRESSION = re.compile(r"[\d.)]\s*[-+*/^%]\s*[\d.(]|[()]")
_EXAMPLES = "(e.g. 0.065, 65mm, 6.5 cm)"
# The config's unit spellings, as pint understands them.
_PINT_UNITS = {"m": "m", "kg": "kg", "kg/m^3": "kg/m**3", "rad/s": "rad/s", "N*m": "N*m",
               "Hz": "Hz", "1": "dimensionless", "count": "dimensionless", "rad": "rad"}


# Unit words read without pint: (the config unit they convert to, the factor pint uses).
# Any other word, or one of these where the config expects another unit, goes to pint.
FAST_UNITS = {"m": ("m", 1.0), "cm": ("m", 1e-2), "mm": ("m", 1e-3), "km": ("m", 1e3),
              "kg": ("kg", 1.0), "g": ("kg", 1e-3), "rad": ("rad", 1.0),
              "deg": ("rad", math.pi / 180), "rpm": ("rad/s", math.pi / 30),
              "Hz": ("Hz", 1.0)}


def _shown(text) -> str:
    from .bounded_yaml import short_repr

    return short_repr(text)


def is_bare_number(text) -> bool:
    """A number with no unit: SI as it stands (what a unit hint may be offered for)."""
    if isinstance(text, bool):
        return False
    return isinstance(text, (int, float)) or bool(_BARE_NUMBER.fullmatch(str(text).strip()))


@functools.lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry()


def parse_quantity(text: str | float | int, unit: str, name: str) -> float:
    """``text`` as a float in ``unit`` (an SI unit of the config); UsageError names ``name``."""
    if isinstance(text, bool):
        raise UsageError(f"{name}: expected a number in {unit}, got {text!r}")
    if isinstance(text, (int, float)):
        try:
            value = float(text)
        except OverflowError:  # an int of hundreds of digits
            value = math.inf
    else:
        raw = str(text).strip()
        if len(raw) > _MAX_TEXT:
            raise UsageError(f"{name}: {_shown(raw)} is too long for a number with a unit")
        if _BARE_NUMBER.fullmatch(raw):
            value = float(raw)
        else:
            value = _convert(raw, unit, name)
    if not math.isfinite(value):
        raise UsageError(f"{name}: {_shown(text)} is not a finite number")
    return value


def _convert(raw: str, unit: str, name: str) -> float:
    if _NOT_FINITE.match(raw):
        raise UsageError(f"{name}: {raw!r} is not a finite number")
    match = _QUANTITY.fullmatch(raw)
    if match is None:
        if _EXPRESSION.search(raw):
            raise UsageError(f"{name}: {raw!r} is an expression; give one number with an "
                             f"optional unit {_EXAMPLES}")
        raise UsageError(f"{name}: {raw!r} is neither a number nor a number with a unit "
                         f"{_EXAMPLES}")
    fast = FAST_UNITS.get(match["unit"])
    if fast is not None and fast[0] == unit:
        return float(match["number"]) * fast[1]
    import pint

    registry = _registry()
    try:
        units = registry.parse_units(match["unit"])
    except (pint.errors.PintError, ValueError, TypeError, AttributeError, SyntaxError,
            KeyError, AssertionError, ZeroDivisionError) as error:
        unknown = getattr(error, "unit_names", None) or (match["unit"],)
        word = unknown if isinstance(unknown, str) else unknown[0]
        raise UsageError(f"{name}: {raw!r} has an unknown unit {word!r}") from None
    quantity = registry.Quantity(float(match["number"]), units)
    target = _PINT_UNITS.get(unit, unit)
    try:
        return float(quantity.to(target).magnitude)
    except pint.errors.DimensionalityError:
        got = f"{units:~}" or "a plain number"
        raise UsageError(f"{name}: {raw!r} has the wrong unit: expected {unit}, "
                         f"got {got}") from None
    except OverflowError:
        return math.inf
