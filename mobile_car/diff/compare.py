"""Two robots' facts compared, matched by name: what was added, removed, renamed, changed.

A rename is a removal plus an addition whose content is the same (a joint's parent and
child read through the links' renames); it is reported once, as a rename. Numbers whose
difference is within the tolerance are equal; angles are compared modulo a full turn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .facts import RobotFacts, Value

# How far apart numbers of each kind are, in the units they are shown in (mm, degrees,
# grams...), so that changes can be ranked biggest first.
DISPLAY_SCALE = {"length": 1000.0, "angle": 180.0 / math.pi, "mass": 1000.0,
                 "inertia": 1e6, "ratio": 100.0, "number": 1.0}


@dataclass
class Change:
    section: str  # "joint", "link", "frame", "total" or "dimension"
    subject: str  # its name ("robot" for totals)
    field: str
    old: Value | None
    new: Value | None

    @property
    def kind(self) -> str:
        return (self.new or self.old).kind

    @property
    def deltas(self) -> tuple | None:
        """new - old for each number (angles wrapped to +-180 deg), or None."""
        if self.old is None or self.new is None or isinstance(self.old.data, str) \
                or isinstance(self.new.data, str) or len(self.old.data) != len(self.new.data):
            return None
        wrap = self.kind == "angle"
        pairs = zip(self.old.data, self.new.data, strict=True)
        return tuple(_difference(a, b, wrap) for a, b in pairs)

    @property
    def size(self) -> float:
        """The biggest difference, in display units (for ordering; inf for text)."""
        deltas = self.deltas
        if deltas is None:
            return math.inf
        kind = self.kind
        scale = DISPLAY_SCALE.get(kind, 1.0)
        if kind.startswith("unit:"):
            magnitude = max(abs(self.old.data[0]), abs(self.new.data[0]), 1e-300)
            return 100.0 * abs(deltas[0]) / magnitude  # per cent: units differ
        return max((abs(d) * scale for d in deltas), default=0.0)


@dataclass
class Rename:
    what: str  # "link" or "joint"
    old: str
    new: str


@dataclass
class RobotDiff:
    old: RobotFacts
    new: RobotFacts
    tolerance: float
    added: list[tuple[str, str]] = field(default_factory=list)  # (what, name)
    removed: list[tuple[str, str]] = field(default_factory=list)
    renamed: list[Rename] = field(default_factory=list)
    changes: list[Change] = field(default_factory=list)  # joints, links, frames
    totals: list[Change] = field(default_factory=list)  # every total, changed or not
    dimensions: list[Change] | None = None  # None: not both robots have a config.xacro
    specs: object = None  # with mcar diff --specs: the figures compared (diff/specs.py)

    @property
    def changed_totals(self) -> list[Change]:
        return [c for c in self.totals if not same(c.old, c.new, self.tolerance)]

    @property
    def changed(self) -> bool:
        """The robot itself changed. A dimension of config.xacro that changed without
        changing this robot (a part that does not use it) is not a change to it."""
        return bool(self.added or self.removed or self.renamed or self.changes
                    or self.changed_totals or self.old.name != self.new.name)

    def grouped(self, section: str) -> list[tuple[str, list[Change]]]:
        """The changes of one section by subject, the subject with the biggest first."""
        subjects: dict[str, list[Change]] = {}
        for change in self.changes:
            if change.section == section:
                subjects.setdefault(change.subject, []).append(change)
        return sorted(subjects.items(), key=lambda item: (-max(c.size for c in item[1]),
                                                          item[0]))

    @property
    def changed_links(self) -> set[str]:
        """Links whose own content changed, or that were added or renamed (new names)."""
        names = {c.subject for c in self.changes if c.section == "link"}
        names |= {name for what, name in self.added if what == "link"}
        names |= {r.new for r in self.renamed if r.what == "link"}
        return names


def _difference(a: float, b: float, wrap: bool) -> float:
    delta = b - a
    if wrap:
        delta = math.remainder(delta, 2.0 * math.pi)
    return delta


def same(a: Value | None, b: Value | None, tolerance: float) -> bool:
    if a is None or b is None:
        return a is b
    if a.kind != b.kind:
        return False
    if isinstance(a.data, str) or isinstance(b.data, str):
        return a.data == b.data
    if len(a.data) != len(b.data):
        return False
    wrap = a.kind == "angle"
    pairs = zip(a.data, b.data, strict=True)
    return all(abs(_difference(x, y, wrap)) <= tolerance for x, y in pairs)


def _same_facts(a: dict, b: dict, tolerance: float) -> bool:
    return a.keys() == b.keys() and all(same(a[k], b[k], tolerance) for k in a)


def _field_changes(section: str, subject: str, old: dict, new: dict,
                   tolerance: float) -> list[Change]:
    keys = list(old) + [k for k in new if k not in old]
    return [Change(section, subject, key, old.get(key), new.get(key)) for key in keys
            if not same(old.get(key), new.get(key), tolerance)]


def _renames(what: str, removed: list[str], added: list[str], old: dict, new: dict,
             tolerance: float, translate=lambda facts: facts) -> list[Rename]:
    found = []
    free = list(added)
    for name in removed:
        content = translate(old[name])
        match = next((a for a in free if _same_facts(content, new[a], tolerance)), None)
        if match is not None:
            free.remove(match)
            found.append(Rename(what, name, match))
    return found


def compare(old: RobotFacts, new: RobotFacts, tolerance: float = 1e-9) -> RobotDiff:
    result = RobotDiff(old, new, tolerance)
    link_map = _match(result, "link", old.links, new.links, tolerance)

    def translated(facts: dict) -> dict:
        moved = dict(facts)
        for key in ("parent", "child"):
            if key in moved:
                moved[key] = Value("text", link_map.get(moved[key].data, moved[key].data))
        return moved

    joint_map = _match(result, "joint", old.joints, new.joints, tolerance, translated)
    for name, new_name in joint_map.items():
        # A joint whose link was renamed is not changed by that: the rename says it.
        result.changes += _field_changes("joint", new_name, translated(old.joints[name]),
                                         new.joints[new_name], tolerance)
    for name, new_name in link_map.items():
        result.changes += _field_changes("link", new_name, old.links[name],
                                         new.links[new_name], tolerance)
        result.changes += _field_changes("frame", new_name, old.frames[name],
                                         new.frames[new_name], tolerance)
    names = list(old.totals) + [k for k in new.totals if k not in old.totals]
    result.totals = [Change("total", "robot", key, old.totals.get(key), new.totals.get(key))
                     for key in names]
    if old.dimensions is not None and new.dimensions is not None:
        result.dimensions = _field_changes("dimension", "config", old.dimensions,
                                           new.dimensions, tolerance)
    return result


def _match(result: RobotDiff, what: str, old: dict, new: dict, tolerance: float,
           translate=lambda facts: facts) -> dict[str, str]:
    """Old name -> new name of every element on both sides (renames included); the rest
    noted as added or removed."""
    removed = [name for name in old if name not in new]
    added = [name for name in new if name not in old]
    renames = _renames(what, removed, added, old, new, tolerance, translate)
    result.renamed += renames
    gone = {r.old for r in renames}
    came = {r.new for r in renames}
    result.removed += [(what, name) for name in removed if name not in gone]
    result.added += [(what, name) for name in added if name not in came]
    mapping = {name: name for name in old if name in new}
    mapping.update({r.old: r.new for r in renames})
    return mapping
