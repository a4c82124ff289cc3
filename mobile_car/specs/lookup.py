"""Figures read back out of the sections computed so far, by key: what the stack's
fragments (:mod:`.stack`) and the comparison of the package's YAML (:mod:`.stack_check`)
both start from."""

from __future__ import annotations

import math


def figure_value(sections, key: str):
    """The value of the figure ``key`` in any of ``sections``, None where none has it."""
    for section in sections:
        found = section.figure(key)
        if found is not None:
            return found.value
    return None


def blocked_sectors(sections) -> dict[str, list[tuple[float, float]]]:
    """sensor -> its blocked sectors in radians, each within [-pi, pi] as a LaserScan's
    angles run (a sector across the rear is split in two): from the sensors.<name>.blocked
    figures (degrees, counter-clockwise from its first to its second angle)."""
    found = {}
    for section in sections:
        for figure in section.figures:
            if not (figure.key.startswith("sensors.") and figure.key.endswith(".blocked")):
                continue
            name = figure.key[len("sensors."):-len(".blocked")]
            sectors = []
            for start, end in figure.value or []:
                sectors += _split(float(start), float(end))
            if sectors:
                found[name] = sectors
    return found


def _split(start: float, end: float) -> list[tuple[float, float]]:
    start = (start + 180.0) % 360.0 - 180.0          # in [-180, 180)
    width = (end - start) % 360.0 or 360.0
    end = start + width
    pieces = [(start, min(end, 180.0))] + ([(-180.0, end - 360.0)] if end > 180.0 else [])
    return [(math.radians(a), math.radians(b)) for a, b in pieces]
