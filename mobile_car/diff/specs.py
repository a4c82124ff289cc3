"""``mcar diff --specs``: what a change does to the figures ``mcar specs`` computes.

Two robots' Sections (mobile_car.specs.figures) are matched by figure key: a figure whose
value moved beyond the tolerance is a change ("tip-over left 24.1° → 19.3°"), one that
only one side has is added or removed, one that one side could not compute (value None)
says so with that side's reason (its source). The rule diagnostics the specs raise
(W5xx) are compared too: a warning that appears is what a reviewer most needs to see.
Written as text, markdown and JSON like the rest of ``mcar diff``; values keep the
figure's own unit (degrees, metres, kilograms...), JSON says which.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..names import shown

# Decimals a figure is shown with, by unit; more when old and new would print the same.
DECIMALS = {"deg": 1, "m": 3, "kg": 3, "N": 1, "N·m": 3, "m/s": 3, "": 3}
MAX_DECIMALS = 9
SYMBOL = {"deg": "°"}  # written against the number: 24.1°


@dataclass
class FigureChange:
    """One figure that differs: ``status`` changed, added (only new has it), removed
    (only old has it); ``old``/``new`` its values (None: not computed, or absent)."""

    key: str
    label: str
    unit: str
    status: str
    old: object = None
    new: object = None
    old_source: str = ""
    new_source: str = ""

    @property
    def delta(self) -> float | None:
        """new - old for a scalar figure both sides computed, else None."""
        if _scalar(self.old) and _scalar(self.new):
            return float(self.new) - float(self.old)
        return None


@dataclass
class SpecsDiff:
    old_label: str
    new_label: str
    tolerance: float
    changes: list[FigureChange] = field(default_factory=list)
    compared: int = 0  # figures both sides have
    new_diagnostics: list = field(default_factory=list)   # Diagnostic, only in new
    gone_diagnostics: list = field(default_factory=list)  # only in old

    @property
    def changed(self) -> bool:
        return bool(self.changes or self.new_diagnostics or self.gone_diagnostics)


def _scalar(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _same(old, new, tolerance: float) -> bool:
    """Values equal within ``tolerance`` (each number), lists of the same shape."""
    if _scalar(old) and _scalar(new):
        if math.isnan(old) or math.isnan(new):
            return math.isnan(old) and math.isnan(new)
        return abs(float(new) - float(old)) <= tolerance
    if isinstance(old, (list, tuple)) and isinstance(new, (list, tuple)):
        return len(old) == len(new) and all(_same(a, b, tolerance)
                                            for a, b in zip(old, new, strict=True))
    return old == new


def _figures(sections) -> dict:
    return {f.key: f for section in sections for f in section.figures}


def _diagnostics(sections) -> dict:
    return {(d.rule, d.message): d for section in sections for d in section.diagnostics}


def compare_specs(old_sections, new_sections, tolerance: float = 1e-9,
                  old_label: str = "old", new_label: str = "new") -> SpecsDiff:
    """Match two robots' Sections by figure key; changes in the new robot's key order
    (the order ``mcar specs`` prints), the removed figures last."""
    old, new = _figures(old_sections), _figures(new_sections)
    diff = SpecsDiff(old_label, new_label, tolerance)
    for key, figure in new.items():
        before = old.get(key)
        if before is None:
            diff.changes.append(FigureChange(key, figure.label, figure.unit, "added",
                                             new=figure.value, new_source=figure.source))
            continue
        diff.compared += 1
        if not _same(before.value, figure.value, tolerance):
            diff.changes.append(FigureChange(key, figure.label, figure.unit, "changed",
                                             before.value, figure.value, before.source,
                                             figure.source))
    for key, figure in old.items():
        if key not in new:
            diff.changes.append(FigureChange(key, figure.label, figure.unit, "removed",
                                             old=figure.value, old_source=figure.source))
    old_rules, new_rules = _diagnostics(old_sections), _diagnostics(new_sections)
    diff.new_diagnostics = [d for k, d in new_rules.items() if k not in old_rules]
    diff.gone_diagnostics = [d for k, d in old_rules.items() if k not in new_rules]
    return diff


def _number(value: float, decimals: int) -> str:
    text = f"{value:.{decimals}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _decimals(change: FigureChange) -> int:
    """The unit's decimals, or as many more as it takes for old and new to differ."""
    decimals = DECIMALS.get(change.unit, 3)
    if change.delta is None:
        return decimals
    while decimals < MAX_DECIMALS and _number(change.old, decimals) == \
            _number(change.new, decimals):
        decimals += 1
    return decimals


def _with_unit(text: str, unit: str) -> str:
    if unit in SYMBOL:
        return text + SYMBOL[unit]
    return f"{text} {unit}" if unit else text


def _flat(value) -> list | None:
    if _scalar(value):
        return [value]
    if isinstance(value, (list, tuple)) and all(_scalar(v) for v in value):
        return list(value)
    return None


def value_text(value, unit: str, decimals: int, source: str = "") -> str:
    """A value for people: ``24.1°``, ``[0.03, 0, 0.1] m``, ``12 items``, ``not computed
    (why)``."""
    if value is None:
        return f"not computed ({shown(source)})" if source else "not computed"
    flat = _flat(value)
    if flat is not None:
        numbers = [_number(float(v), decimals) for v in flat]
        text = numbers[0] if _scalar(value) else "[" + ", ".join(numbers) + "]"
        return _with_unit(text, unit)
    if isinstance(value, (list, tuple)):
        return f"{len(value)} items"
    return shown(str(value))


def _biggest_move(old, new) -> float | None:
    """The largest change of any number of two nested lists of the same shape."""
    if _scalar(old) and _scalar(new):
        return abs(float(new) - float(old))
    if isinstance(old, (list, tuple)) and isinstance(new, (list, tuple)) \
            and len(old) == len(new):
        moves = [_biggest_move(a, b) for a, b in zip(old, new, strict=True)]
        if all(m is not None for m in moves):
            return max(moves, default=0.0)
    return None


def delta_text(change: FigureChange, decimals: int) -> str:
    """``-4.8°`` for a scalar, ``+0, +0.01, +0.03 m`` for a point, ``each number moved up
    to 0.012 m`` for a polygon or sectors of the same shape; else ""."""
    if change.delta is not None:
        # 9.9434° → 9.9723° shows as 9.9° → 10°: its change is +0.03°, not +0°
        while decimals < MAX_DECIMALS and _number(change.delta, decimals) == "0":
            decimals += 1
        sign = "+" if change.delta > 0 else ""
        return _with_unit(sign + _number(change.delta, decimals), change.unit)
    old, new = _flat(change.old), _flat(change.new)
    if change.status == "changed" and old and new and len(old) == len(new):
        signed = [("+" if b - a > 0 else "") + _number(b - a, decimals)
                  for a, b in zip(old, new, strict=True)]
        return _with_unit(", ".join(signed), change.unit)
    if change.status == "changed" and old is None:
        move = _biggest_move(change.old, change.new)
        if move is not None:
            return "each number moved up to " + _with_unit(_number(move, decimals),
                                                           change.unit)
    return ""


def row(change: FigureChange) -> str:
    """One change in words: ``tip-over left 24.1° → 19.3° (-4.8°)``; what the robot
    names (a sensor in a label, a link in a source) shown escaped (mobile_car.names), so
    it cannot break the line or forge another."""
    decimals = _decimals(change)
    label = shown(change.label)
    if change.status == "added":
        return f"added {label}: " + value_text(change.new, change.unit, decimals,
                                                  change.new_source)
    if change.status == "removed":
        return f"removed {label} (was " + value_text(change.old, change.unit, decimals,
                                                        change.old_source) + ")"
    moved = delta_text(change, decimals)
    text = (f"{label} {value_text(change.old, change.unit, decimals, change.old_source)}"
            f" → {value_text(change.new, change.unit, decimals, change.new_source)}")
    return f"{text} ({moved})" if moved else text


def summary(diff: SpecsDiff) -> str:
    if not diff.changed:
        return f"no figure changed ({diff.compared} compared)"
    counts = {status: sum(c.status == status for c in diff.changes)
              for status in ("changed", "added", "removed")}
    bits = [f"{count} {status}" for status, count in counts.items() if count]
    if counts["changed"]:
        bits[0] = f"{counts['changed']} of {diff.compared} figures changed"
    if diff.new_diagnostics:
        bits.append(f"{len(diff.new_diagnostics)} new warning"
                    + ("" if len(diff.new_diagnostics) == 1 else "s"))
    if diff.gone_diagnostics:
        bits.append(f"{len(diff.gone_diagnostics)} warning"
                    + ("" if len(diff.gone_diagnostics) == 1 else "s") + " gone")
    return ", ".join(bits)


def _diagnostic_rows(diff: SpecsDiff) -> list[str]:
    return ([f"new {d.rule}: {shown(d.message)}" for d in diff.new_diagnostics]
            + [f"gone {d.rule}: {shown(d.message)}" for d in diff.gone_diagnostics])


def text(diff: SpecsDiff) -> str:
    """The figures' changes for a terminal, one per line, keys in brackets."""
    lines = [f"Specs {shown(diff.old_label)} → {shown(diff.new_label)}: {summary(diff)}"]
    lines += [f"  {row(c)}  [{shown(c.key)}]" for c in diff.changes]
    lines += [f"  {line}" for line in _diagnostic_rows(diff)]
    return "\n".join(lines) + "\n"


def _cell(value: str) -> str:
    return value.replace("|", "\\|").replace("\n", " ") if value else " "


def markdown(diff: SpecsDiff) -> str:
    """The figures' changes for a pull request: a table of figure, old, new, change."""
    lines = [f"#### Specs: {summary(diff)}", ""]
    if diff.changes:
        lines += ["| Figure | Old | New | Change |", "|---|---|---|---|"]
        for c in diff.changes:
            decimals = _decimals(c)
            old = "(absent)" if c.status == "added" else value_text(c.old, c.unit, decimals,
                                                              c.old_source)
            new = "(absent)" if c.status == "removed" else value_text(c.new, c.unit, decimals,
                                                                c.new_source)
            lines.append("| " + " | ".join(_cell(v) for v in (
                f"{shown(c.label)} `{shown(c.key)}`", old, new,
                c.status if c.status != "changed" else delta_text(c, decimals))) + " |")
        lines.append("")
    lines += [f"- {line}" for line in _diagnostic_rows(diff)]
    return "\n".join(lines).rstrip("\n") + "\n"


def _plain(value):
    """A figure's value as JSON can hold it (tuples as lists, NaN as None)."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def as_json(diff: SpecsDiff) -> dict:
    return {
        "old": diff.old_label, "new": diff.new_label, "changed": diff.changed,
        "tolerance": diff.tolerance, "compared": diff.compared,
        "figures": [{"key": c.key, "label": c.label, "unit": c.unit, "status": c.status,
                     "old": _plain(c.old), "new": _plain(c.new), "delta": c.delta,
                     "old_source": c.old_source, "new_source": c.new_source}
                    for c in diff.changes],
        "diagnostics": {"new": [{"rule": d.rule, "message": d.message}
                                for d in diff.new_diagnostics],
                        "gone": [{"rule": d.rule, "message": d.message}
                                 for d in diff.gone_diagnostics]},
    }


def specs_sections(loaded, options: dict | None = None) -> list:
    """The Sections ``mcar specs`` computes for a loaded robot that passed mcar check:
    default options, no MuJoCo proofs (they check a figure, never change it, and cost
    seconds)."""
    from ..check.checker import check_loaded
    from ..specs.compute import compute

    return compute(check_loaded(loaded), {"proof": False, **(options or {})})
