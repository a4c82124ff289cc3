"""A robot comparison written for people (text for a terminal, markdown for a pull
request) and for scripts (JSON). Lengths are shown in mm, angles in degrees, masses in kg;
JSON keeps SI units and says which.
"""

from __future__ import annotations

import math

from .compare import Change, RobotDiff
from .geometry import angle_between, rpy_matrix

SHOWN = {"length": (1000.0, "mm"), "angle": (180.0 / math.pi, "deg"), "mass": (1.0, "kg"),
         "inertia": (1.0, "kg m^2"), "ratio": (1.0, ""), "number": (1.0, ""), "text": (1.0, "")}
SI_UNIT = {"length": "m", "angle": "rad", "mass": "kg", "inertia": "kg m^2"}
SECTIONS = (("joint", "Joints"), ("link", "Links"))
FRAMES_TITLE = "Frames at joint zero (world pose)"


def _scale_unit(kind: str) -> tuple[float, str]:
    if kind.startswith("unit:"):
        return 1.0, kind[len("unit:"):]
    return SHOWN.get(kind, (1.0, ""))


def number(value: float, kind: str = "number") -> str:
    """A number the way a reviewer reads it: mm and degrees to 4 decimals, no noise."""
    if kind in ("length", "angle"):
        shown = f"{value:.4f}".rstrip("0").rstrip(".")
    else:
        shown = f"{value:.6g}"
    return "0" if shown in ("-0", "") else shown


def show(value, kind: str | None = None) -> str:
    """A fact's value in display units, without its unit."""
    if value is None:
        return "(none)"
    if isinstance(value.data, str):
        return value.data or "(empty)"
    scale, _ = _scale_unit(value.kind)
    return " ".join(number(v * scale, value.kind) for v in value.data)


def label(change: Change) -> str:
    _, unit = _scale_unit(change.kind)
    return f"{change.field} ({unit})" if unit else change.field


def delta(change: Change) -> str:
    """How much it changed: signed per number, and the distance or angle it amounts to."""
    deltas = change.deltas
    if deltas is None:
        return ""
    scale, unit = _scale_unit(change.kind)
    parts = " ".join(("+" if d > 0 else "") + number(d * scale, change.kind) for d in deltas)
    # A position's change is a distance; a size's is not (two boxes 11 mm longer and
    # 11 mm taller are not "15.6 mm" bigger): its numbers, axis by axis, say it all.
    if change.kind == "length" and len(deltas) == 3 and not _is_size(change.field):
        parts += f"; {number(math.hypot(*deltas) * scale, 'length')} {unit}"
    elif change.kind == "angle" and len(deltas) == 3:
        turned = angle_between(rpy_matrix(change.old.data), rpy_matrix(change.new.data))
        parts += f"; turned {number(math.degrees(turned), 'angle')} deg"
    return parts


def _is_size(field: str) -> bool:
    """A box's ``size`` and the robot's overall ``size`` are extents, not positions."""
    return field == "size" or field.endswith(" size")


def counted(count: int, noun: str) -> str:
    """``1 link``, ``2 links``: the nouns these reports count take a plain -s."""
    return f"{count} {noun}" + ("" if count == 1 else "s")


def summary(diff: RobotDiff) -> str:
    """One line: what kinds of change there are, and the total mass."""
    if not diff.changed:
        return "no change to the robot"
    bits = []
    for what, items in (("renamed", diff.renamed), ("added", diff.added),
                        ("removed", diff.removed)):
        if items:
            bits.append(f"{len(items)} {what}")
    for section, noun, verb in (("joint", "joint", "changed"), ("link", "link", "changed"),
                                ("frame", "frame", "moved")):
        count = len(diff.grouped(section))
        if count:
            bits.append(f"{counted(count, noun)} {verb}")
    if diff.dimensions:
        bits.append(f"{counted(len(diff.dimensions), 'dimension')} changed")
    mass = next((c for c in diff.totals if c.field == "mass"), None)
    if mass is not None:
        moved = mass in diff.changed_totals
        bits.append(f"total mass {show(mass.old)} -> {show(mass.new)} kg" if moved
                    else f"total mass unchanged ({show(mass.new)} kg)")
    return ", ".join(bits)


def _structure_lines(diff: RobotDiff) -> list[tuple[str, str]]:
    rows = [(r.what, f"renamed {r.what} {r.old} -> {r.new} (same content)")
            for r in diff.renamed]
    rows += [(what, f"removed {what} {name}") for what, name in diff.removed]
    rows += [(what, f"added {what} {name}") for what, name in diff.added]
    if diff.old.name != diff.new.name:
        rows.insert(0, ("robot", f"robot renamed {diff.old.name} -> {diff.new.name}"))
    return rows


def text(diff: RobotDiff, dimensions: bool = True) -> str:
    """The comparison for a terminal; ``dimensions``: list config.xacro's changed
    dimensions (False: an earlier robot of the same run listed the same ones)."""
    lines = [f"{diff.old.label} -> {diff.new.label}: {summary(diff)}"]
    if not diff.changed:
        return lines[0] + "\n"
    structure = _structure_lines(diff)
    if structure:
        lines += ["", "Links and joints:"] + [f"  {line}" for _, line in structure]
    for section, title in (*SECTIONS, ("frame", FRAMES_TITLE)):
        groups = diff.grouped(section)
        if groups:
            lines += ["", f"{title}, biggest change first:"]
            for subject, changes in groups:
                lines.append(f"  {subject}")
                lines += [_text_row(change, 4) for change in changes]
    if diff.dimensions and dimensions:
        lines += ["", "Dimensions (config.xacro):"]
        lines += [_text_row(c, 2, c.field) for c in sorted(diff.dimensions, key=lambda c: -c.size)]
    elif diff.dimensions:
        lines += ["", "Dimensions (config.xacro): the same changes as above"]
    lines += ["", "Totals:"]
    for change in diff.totals:
        if change in diff.changed_totals:
            lines.append(_text_row(change, 2))
        else:
            lines.append(f"  {label(change):<28} {show(change.new)}  (unchanged)")
    for note in diff.old.notes + diff.new.notes:
        lines.append(f"note: {note}")
    return "\n".join(lines) + "\n"


def _text_row(change: Change, indent: int, name: str | None = None) -> str:
    moved = delta(change)
    head = f"{' ' * indent}{name or label(change):<{30 - indent}} "
    unit = _scale_unit(change.kind)[1] if name else ""
    tail = f" {unit}" if unit else ""
    row = f"{head}{show(change.old)}{tail}  ->  {show(change.new)}{tail}"
    return f"{row}   ({moved})" if moved else row


def _cell(value: str) -> str:
    return value.replace("|", "\\|").replace("\n", " ") if value else " "


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return lines


def markdown(diff: RobotDiff, dimensions: bool = True) -> str:
    """The comparison for a pull request; ``dimensions`` as for :func:`text`."""
    lines = [f"### `{diff.old.label}` → `{diff.new.label}`", "", f"**{summary(diff)}**", ""]
    if not diff.changed:
        return "\n".join(lines)
    rows = [[what, "", line, "", "", ""] for what, line in _structure_lines(diff)]
    for section, _ in SECTIONS:
        for subject, changes in diff.grouped(section):
            rows += [[section, f"`{subject}`", label(c), show(c.old), show(c.new), delta(c)]
                     for c in changes]
    if diff.dimensions and not dimensions:
        rows.append(["dimension", "", "the same changes as above", "", "", ""])
    for c in sorted((diff.dimensions or ()) if dimensions else (), key=lambda c: -c.size):
        rows.append(["dimension", f"`{c.field}`", _scale_unit(c.kind)[1], show(c.old),
                     show(c.new), delta(c)])
    if rows:
        lines += _table(["", "Name", "What", "Old", "New", "Change"], rows) + [""]
    frames = diff.grouped("frame")
    if frames:
        lines += [f"<details><summary>{FRAMES_TITLE}: {len(frames)} moved</summary>", ""]
        lines += _table(["Frame", "What", "Old", "New", "Change"],
                        [[f"`{subject}`", label(c), show(c.old), show(c.new), delta(c)]
                         for subject, changes in frames for c in changes])
        lines += ["", "</details>", ""]
    lines += ["<details><summary>Totals</summary>", ""]
    lines += _table(["What", "Old", "New", "Change"],
                    [[label(c), show(c.old), show(c.new),
                      delta(c) if c in diff.changed_totals else "unchanged"]
                     for c in diff.totals])
    lines += ["", "</details>", ""]
    lines += [f"> note: {note}" for note in diff.old.notes + diff.new.notes]
    return "\n".join(lines).rstrip("\n") + "\n"


def _json_value(value):
    if value is None:
        return None
    return value.data if isinstance(value.data, str) else list(value.data)


def _json_change(change: Change) -> dict:
    kind = change.kind
    unit = kind[len("unit:"):] if kind.startswith("unit:") else SI_UNIT.get(kind, "")
    item = {"section": change.section, "name": change.subject, "field": change.field,
            "unit": unit, "old": _json_value(change.old), "new": _json_value(change.new)}
    if change.deltas is not None:
        item["delta"] = list(change.deltas)
    return item


def as_json(diff: RobotDiff) -> dict:
    return {
        "old": {"file": diff.old.label, "robot": diff.old.name},
        "new": {"file": diff.new.label, "robot": diff.new.name},
        "changed": diff.changed, "tolerance": diff.tolerance,
        "renamed": [{"what": r.what, "old": r.old, "new": r.new} for r in diff.renamed],
        "added": [{"what": what, "name": name} for what, name in diff.added],
        "removed": [{"what": what, "name": name} for what, name in diff.removed],
        "changes": [_json_change(c) for c in diff.changes],
        "totals": [{**_json_change(c), "changed": c in diff.changed_totals}
                   for c in diff.totals],
        "dimensions": None if diff.dimensions is None
        else [_json_change(c) for c in diff.dimensions],
        "notes": diff.old.notes + diff.new.notes,
    }
