"""Figures read back out of the sections computed so far, by key: what the stack's
fragments (:mod:`.stack`) and the comparison of the package's YAML (:mod:`.stack_check`)
both start from; and where in the user's files an element was written, as the sources of
figures name it (:func:`written_at`)."""

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
    """sensor -> its blocked sectors in radians, in the scan's own angles (a 0..360° scan's
    stay in 0..2π, as its LaserScan's angles and the package's filter bounds run): from
    the sensors.<name>.blocked figures (degrees, from the lower to the upper angle)."""
    found = {}
    for section in sections:
        for figure in section.figures:
            if not (figure.key.startswith("sensors.") and figure.key.endswith(".blocked")):
                continue
            name = figure.key[len("sensors."):-len(".blocked")]
            sectors = [(math.radians(float(low)), math.radians(float(high)))
                       for low, high in figure.value or []]
            if sectors:
                found[name] = sectors
    return found


def written_at(checked, element) -> str:
    """``FILE:LINE`` where ``element`` of a checked robot was written (through the source
    map: the xacro line the user edits), ``FILE`` where no line is known."""
    file, line, _note = checked.where(element)
    return f"{file}:{line}" if line is not None else file
