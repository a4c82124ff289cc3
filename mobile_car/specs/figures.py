"""What ``mcar specs`` computes, in the shapes every part of it shares: a figure is a value
with its unit, where it comes from and what it assumes, and, where physics can show it, the
figure MuJoCo measured and whether the two agree. A figure that disagrees with its proof is
reported as such, never hidden.

Keys are stable (``--format json``, ``mcar diff`` and ``mcar sweep`` name figures by them):
``body.mass``, ``body.com``, ``statics.tip.left``, ``sensors.<sensor>.blocked``,
``joints.<joint>.gravity``... (the list: docs/specs.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(eq=False)
class Proof:
    """What MuJoCo measured of a figure: ``measured`` in the figure's unit (None when the
    run could not measure it), ``agrees`` within ``tolerance``, and how (one line);
    ``instead``: where nothing was measured, what happened instead, in a few words for
    the table ("slid first at 43.8°")."""

    measured: object
    agrees: bool
    tolerance: str
    detail: str = ""
    instead: str = ""


@dataclass(eq=False)
class Figure:
    """One figure: ``value`` a number, a list of numbers (a point, a polygon, sectors) or
    None where it cannot be computed (``source`` then says why); ``unit`` as printed
    ("kg", "m", "deg", "N", "N·m", "m/s", "" for a share or a count); ``source`` where the
    value comes from, in words a builder checks ("collision geometry", "<limit effort> of
    joint wheel_left (urdf/motor.xacro:12)", "default friction 1.0"); ``assumption`` what
    it takes for granted, "" for none."""

    key: str
    label: str
    value: object
    unit: str
    source: str
    assumption: str = ""
    proof: Proof | None = None


@dataclass(eq=False)
class Section:
    """A part of the answer ("body", "statics", "joints", "sensors", "stack", "inertia"):
    its figures, the rule diagnostics it raises (mobile_car.check.diagnostics.Diagnostic,
    rules W5xx/E5xx), and notes (one line each: what could not be computed and why)."""

    name: str
    figures: list[Figure] = field(default_factory=list)
    diagnostics: list = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def figure(self, key: str) -> Figure | None:
        return next((f for f in self.figures if f.key == key), None)
