"""A scenario's outcome: its measured figures, each against its bound, the problems that
name a cause, and the raw measurements (SI units, degrees for angles) mcar sweep keeps."""

from __future__ import annotations

import math
from dataclasses import dataclass, field


@dataclass
class Figure:
    name: str
    value: float
    bound: float
    unit: str
    within: str = "max"  # value <= bound ("max") or value >= bound ("min")
    detail: str = ""

    @property
    def ok(self) -> bool:
        if not math.isfinite(self.value):
            return False
        return bool(self.value <= self.bound if self.within == "max" else
                    self.value >= self.bound)

    def as_json(self) -> dict:
        document = {"name": self.name, "value": _round(self.value), "bound": self.bound,
                    "unit": self.unit, "within": self.within, "ok": self.ok}
        if self.detail:
            document["detail"] = self.detail
        return document


@dataclass
class ScenarioResult:
    name: str
    figures: list[Figure] = field(default_factory=list)
    skipped: str | None = None   # why it did not run
    problems: list[str] = field(default_factory=list)  # what is wrong, for people
    seconds: float = 0.0         # simulated
    # Raw measurements behind the figures (SI units, degrees for angles), for mcar sweep's
    # rows: rest_height_m, speed_ratio, yaw_ratio, ...
    measured: dict[str, float] = field(default_factory=dict)
    # What was measured beside the bounds, one sentence each (a skid-steer robot's
    # effective track and multiplier, against its control config's).
    findings: list[str] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return self.skipped is None and not self.problems and all(f.ok for f in self.figures)

    @property
    def status(self) -> str:
        return "skipped" if self.skipped else "passed" if self.passed else "failed"

    def message(self) -> str:
        if self.skipped:
            return self.skipped
        failed = [f"{f.name} {show_value(f.value, f.unit)} (bound {show_bound(f)})"
                  for f in self.figures if not f.ok]
        return "; ".join(self.problems + failed) or "ok"

    def as_json(self) -> dict:
        document = {"name": self.name, "status": self.status, "message": self.message(),
                    "simulated_seconds": self.seconds,
                    "figures": [f.as_json() for f in self.figures]}
        if self.findings:
            document["findings"] = list(self.findings)
        return document


def _round(value: float) -> float | None:
    return float(f"{value:.6g}") if math.isfinite(value) else None


def show_value(value: float, unit: str) -> str:
    """Lengths under a metre in mm, as people measure a small robot."""
    if unit in ("m", "m/s") and abs(value) < 1:
        return f"{1000 * value:.2f} m{unit}"
    return f"{value:.2f} {unit}"


def show_bound(f: Figure) -> str:
    return f"{'<=' if f.within == 'max' else '>='} {show_value(f.bound, f.unit)}"
