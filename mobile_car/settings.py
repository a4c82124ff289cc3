"""The MCAR_* environment variables that set limits, read and validated as options are:
a number, finite, within its range, or a usage error naming the variable (exit 2)."""

from __future__ import annotations

import math
import os

from .errors import UsageError


def env_number(name: str, default: float, low: float, high: float, unit: str) -> float:
    """The value of ``name`` (``default`` when unset or empty), checked to lie in
    ``low``..``high``."""
    raw = os.environ.get(name, "").strip()
    if not raw:
        return default
    shown = raw if len(raw) <= 40 else raw[:37] + "..."
    try:
        value = float(raw)
    except ValueError:
        raise UsageError(f"{name}={shown!r}: expected a number of {unit}") from None
    if not (math.isfinite(value) and low <= value <= high):
        raise UsageError(f"{name}={shown}: must be between {low:g} and {high:g} {unit}")
    return value
