"""``mcar sweep --specs KEY,...``: figures of ``mcar specs`` as columns of each point's row.

A column is named by the figure's key (``statics.tip.left``, ``body.mass``): the name
``--colour`` and pandas use. Only a figure that is one number can be a column: a key known
to hold a list (a polygon, a pose, sectors) is refused before the sweep runs, and a value
that turns out not to be a number, or that a point cannot compute, leaves that point's
cell empty (NaN) with a note in its ``specs_notes`` column, one ``key: why`` per figure.
The figures are computed after the point's check passed, independently of its scenarios.
"""

from __future__ import annotations

import fnmatch
import math
import re

from ..errors import UsageError

NOTES = "specs_notes"
# Figures holding a list, never a column (docs/specs.md lists every key).
LIST_FIGURES = ("body.com", "body.footprint", "statics.support", "statics.tip.polar",
                "sensors.*.pose", "sensors.*.range", "sensors.*.fov", "sensors.*.blocked",
                "inertia.*")
_KEY = re.compile(r"[A-Za-z_][\w-]*(\.[\w-]+)+")


def parse_keys(text: str | None) -> tuple[str, ...]:
    """``--specs a.b,c.d`` as its keys, in order, once each; UsageError for a word that
    is no figure key or a figure that is not a number."""
    if not text:
        return ()
    keys = []
    for word in text.split(","):
        key = word.strip()
        if not _KEY.fullmatch(key):
            raise UsageError(f"--specs {text}: {key!r} is not a figure key (dotted, like "
                             "statics.tip.left or body.mass; the list: mcar specs --format json)")
        pattern = next((p for p in LIST_FIGURES if fnmatch.fnmatchcase(key, p)), None)
        if pattern is not None:
            raise UsageError(f"--specs {text}: {key} is a list, not a number; a column holds "
                             "one number per point (e.g. statics.tip.min, body.mass)")
        if key not in keys:
            keys.append(key)
    return tuple(keys)


def empty_cells(keys) -> dict:
    """A row's specs cells before anything is computed: NaN each, no note."""
    return {**{key: math.nan for key in keys}, NOTES: ""} if keys else {}


def cells(sections, keys) -> dict:
    """The row's cells for ``keys`` from a point's Sections: each figure's number, or NaN
    and a note saying why (absent, not computed and its source's reason, not a number)."""
    figures = {f.key: f for section in sections for f in section.figures}
    row = empty_cells(keys)
    notes = []
    for key in keys:
        figure = figures.get(key)
        if figure is None:
            notes.append(f"{key}: this robot has no such figure")
        elif figure.value is None:
            notes.append(f"{key}: not computed ({figure.source})" if figure.source
                         else f"{key}: not computed")
        elif isinstance(figure.value, bool) or not isinstance(figure.value, (int, float)):
            notes.append(f"{key}: not a number ({type(figure.value).__name__})")
        else:
            row[key] = float(figure.value)
    row[NOTES] = "; ".join(notes)
    return row


def not_computed(keys, why: str) -> dict:
    """Every cell empty, one note for all: ``specs not computed: why``."""
    row = empty_cells(keys)
    if keys:
        row[NOTES] = f"specs not computed: {why}"
    return row


def specs_sections(checked, options: dict | None = None) -> list:
    """The Sections ``mcar specs`` computes of a checked robot: default options, no
    MuJoCo proofs (they check a figure, never change it, and cost seconds)."""
    from ..specs.compute import compute

    return compute(checked, {"proof": False, **(options or {})})
