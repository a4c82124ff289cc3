"""One robot's specs and their three spellings: a text table per section, one JSON
document (figures by key), Markdown for a pull request. The library builds the strings;
the command line prints them. Its exit code: 1 for a figure that disagrees with its
proof or a rule error (E5xx), else 0."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..errors import EXIT_OK, EXIT_PROBLEMS
from ..names import shown

UNITS = {"deg": "°"}  # printed so; JSON keeps the unit's name
# What starts Markdown (GitHub's: tables, links, emphasis, strike-through) or HTML
MARKUP = frozenset("\\`*_[]<>|&!#~")
LISTED = 2            # a list of points longer than this is summed up in text


@dataclass
class SpecsReport:
    file: str
    robot: str | None
    sections: list = field(default_factory=list)  # .figures.Section, body first

    @property
    def figures(self) -> list:
        return [f for s in self.sections for f in s.figures]

    @property
    def diagnostics(self) -> list:
        return [d for s in self.sections for d in s.diagnostics]

    @property
    def disagreements(self) -> list:
        return [f for f in self.figures if f.proof is not None and not f.proof.agrees]

    @property
    def exit_code(self) -> int:
        if self.disagreements or any(d.is_error for d in self.diagnostics):
            return EXIT_PROBLEMS
        return EXIT_OK


def disagreement_lines(report: SpecsReport) -> list[str]:
    """One line per figure its proof contradicts: what was computed, what MuJoCo
    measured, within what."""
    return [f"{f.key} ({f.label}): {show(f.value, f.unit)} computed, MuJoCo measured "
            f"{show(f.proof.measured, f.unit)} (tolerance {f.proof.tolerance})"
            + (f": {f.proof.detail}" if f.proof.detail else "") for f in report.disagreements]


def show(value, unit: str) -> str:
    """A figure's value as text: 4 significant digits and its unit; a point in
    parentheses; a short list of points listed, a long one summed up."""
    mark = UNITS.get(unit, f" {unit}" if unit else "")
    if value is None:
        return "—"
    if isinstance(value, bool) or not isinstance(value, (int, float, list, tuple)):
        return str(value)
    if isinstance(value, (int, float)):
        return f"{_number(value)}{mark}"
    if not value:
        return "none"
    if all(isinstance(v, (int, float)) for v in value):
        return f"({', '.join(_number(v) for v in value)}){mark}"
    if len(value) <= LISTED:
        return ", ".join(show(v, unit) for v in value)
    spans = [f"{min(p[i] for p in value):.3g}..{max(p[i] for p in value):.3g}"
             for i in range(min(len(p) for p in value))]
    return f"{len(value)} points ({' × '.join(spans)}){mark}"


def _number(value) -> str:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return f"{value:.4g}"


def _proof_text(proof, unit: str) -> str:
    """``MuJoCo 23.4° ✓``, ``MuJoCo 19° ✗ disagrees``; "" for a figure without a proof."""
    if proof is None:
        return ""
    if proof.measured is None:
        measured = proof.instead or "not measured"
    else:
        measured = show(proof.measured, unit)
    return f"MuJoCo {measured} " + ("✓" if proof.agrees else "✗ disagrees")


def text_table(report: SpecsReport) -> list[str]:
    """The robot, then per section a table: label, value and unit, source (and MuJoCo's
    proof where a figure has one); what a figure assumes on the line below it."""
    lines = [f"{report.file} ({report.robot})"]
    for section in report.sections:
        if not section.figures:
            continue
        proved = any(f.proof is not None for f in section.figures)
        rows = [(f.label, show(f.value, f.unit), _proof_text(f.proof, f.unit) if proved else None,
                 f.source, f.assumption) for f in section.figures]
        label_width = max(len(r[0]) for r in rows)
        value_width = max(len(r[1]) for r in rows)
        proof_width = max(len(r[2]) for r in rows) if proved else 0
        lines.append(f"  {section.name}")
        for label, value, proof, source, assumption in rows:
            proof_cell = f"  {proof:<{proof_width}}" if proved else ""
            lines.append(f"    {label:<{label_width}}  {value:>{value_width}}{proof_cell}  "
                         f"{source}".rstrip())
            if assumption:
                lines.append(f"    {'':<{label_width}}  assumes: {assumption}")
    return lines


def markdown(report: SpecsReport) -> list[str]:
    """The same tables in Markdown, for a pull request: one heading per section, the
    notes and rule diagnostics listed under it."""
    lines = [f"## mcar specs: {_cell(report.robot or '')} ({_cell(report.file)})", ""]
    for section in report.sections:
        lines += [f"### {section.name}", ""]
        if section.figures:
            proved = any(f.proof is not None for f in section.figures)
            lines += ["| figure | key | value | source | assumes |" + " MuJoCo |" * proved,
                      "|---|---|---|---|---|" + "---|" * proved]
            lines += [f"| {_cell(f.label)} | {_cell(f.key)} | {_cell(show(f.value, f.unit))} | "
                      f"{_cell(f.source)} | {_cell(f.assumption)} |"
                      + (f" {_cell(_proof_text(f.proof, f.unit))} |" if proved else "")
                      for f in section.figures]
            lines.append("")
        notes = [d.text() for d in section.diagnostics] + section.notes
        if notes:
            lines += [f"- {_cell(note)}" for note in notes] + [""]
    return lines


def _cell(text: str) -> str:
    """Text fit for one Markdown table cell: controls escaped (a name's line break shows
    as ``\\n``), and each character that could start Markdown or HTML (a link, emphasis,
    a tag, a cell's end) backslash-escaped: a name is data, not markup."""
    return "".join(f"\\{c}" if c in MARKUP else c for c in " ".join(shown(text).split()))


def as_json(report: SpecsReport) -> dict:
    """Figures by key (value, unit, label, source, assumption, proof, section); each
    section's notes and diagnostics; the exit code."""
    figures = {}
    for section in report.sections:
        for f in section.figures:
            figures[f.key] = {"section": section.name, "label": f.label,
                              "value": _plain(f.value), "unit": f.unit, "source": f.source,
                              "assumption": f.assumption, "proof": _proof_json(f.proof)}
    return {"file": report.file, "robot": report.robot, "figures": figures,
            "sections": [{"name": s.name, "notes": list(s.notes),
                          "diagnostics": [d.as_json() for d in s.diagnostics]}
                         for s in report.sections],
            "exit_code": report.exit_code}


def _proof_json(proof) -> dict | None:
    if proof is None:
        return None
    return {"measured": _plain(proof.measured), "agrees": proof.agrees,
            "tolerance": proof.tolerance, "detail": proof.detail}


def _plain(value):
    """Numbers rounded to 1e-9 (a nanometre: the geometry's rounding, not a figure), -0
    as 0, what JSON cannot hold (NaN, infinity) as None; lists element by element."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, bool) or not isinstance(value, float):
        return value
    if not math.isfinite(value):
        return None
    return round(value, 9) + 0.0
