"""Read a dimension given by a person ("65mm", "6.5 cm", "90deg", "0.0325") as SI.

A bare number is already SI. A number with a unit is converted with pint, which is
imported only then (it is slow to import), and must have the dimension the config
entry expects: a length for ``m``, a mass for ``kg``, and so on.
"""

from __future__ import annotations

import functools
import math
import re

from ..errors import UsageError

# Longer is no quantity a person writes, and pint's parser need not see it.
_MAX_TEXT = 100


def _shown(text) -> str:
    from .bounded_yaml import short_repr

    return short_repr(text)

_BARE_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")
# The config's unit spellings, as pint understands them.
_PINT_UNITS = {"m": "m", "kg": "kg", "kg/m^3": "kg/m**3", "rad/s": "rad/s", "N*m": "N*m",
               "Hz": "Hz", "1": "dimensionless", "rad": "rad"}


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
    import pint

    registry = _registry()
    try:
        quantity = registry.Quantity(raw)
    except (pint.errors.PintError, ValueError, TypeError, AttributeError, SyntaxError,
            KeyError, AssertionError, ZeroDivisionError):
        raise UsageError(f"{name}: {raw!r} is neither a number nor a number with a unit "
                         f"(e.g. 0.065, 65mm, 6.5 cm)") from None
    if not isinstance(quantity, registry.Quantity) or \
            not isinstance(quantity.magnitude, (int, float)):
        raise UsageError(f"{name}: {raw!r} is not a number with a unit")
    if not math.isfinite(quantity.magnitude):
        raise UsageError(f"{name}: {raw!r} is not a finite number")
    target = _PINT_UNITS.get(unit, unit)
    try:
        return float(quantity.to(target).magnitude)
    except pint.errors.DimensionalityError:
        raise UsageError(f"{name}: {raw!r} has the wrong unit: expected {unit}, "
                         f"got {quantity.units:~}") from None
