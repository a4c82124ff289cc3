"""The robot's dimensions in the viewer: a slider for each dimension of its config.xacro that
``--set`` may change, and the overrides they make, validated and built as ``--set`` does.

A slider is in the unit config.xacro writes the dimension's range in, where both ends
share one (``motor_no_load_speed`` 10rpm..20000rpm: rpm), else in its SI unit. It spans
a plausible neighbourhood of the value, not the whole plausible range, which is wide for
many (5 mm..0.5 m for a wheel: a hundredfold, where a pixel of the slider was 1.5 mm and
a drag landed anywhere): half to twice the value (a range reaching zero or below: the
value give or take its size, or a twentieth of the range), where a linear scale is even
enough (viser's slider is linear, and its box shows the slider's own value: a logarithmic
slider would show a logarithm there). A value typed in the slider's box anywhere in the
plausible range is taken, and the slider then spans the neighbourhood of that value:
going a long way is typing it. A drag never re-spans it, even at an end, where the thumb
would jump under the pointer.

A robot gets them only when it is built from a config.xacro (its package's, or the mobile
car's): a robot of another package has no dimensions to move. Derived dimensions follow
the others and dimensions baked into a mesh cannot change, so neither has a slider.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

from ..config.overrides import applied_overrides
from ..config.spec import ConfigSpec, Dimension, config_file, load_spec, parse_set_options
from ..config.units import FAST_UNITS
from ..errors import McarError
from ..load.inputs import RobotInput
from ..load.robot import LoadOptions
from ..packages.search import PackageSearch
from .model import ViewModel, load_model

# Stops a slider has across its neighbourhood, at least: a drag lands on a round value.
STOPS = 200
_END_UNIT = re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(.*)$")


@dataclass(frozen=True)
class DimensionRange:
    """One dimension's slider: its plausible range and default value (SI), the unit it is
    shown in (``shown_unit``, ``factor`` of them make one SI unit's worth)."""

    name: str
    unit: str
    low: float
    high: float
    default: float
    meaning: str
    shown_unit: str
    factor: float
    plausible: str  # the range as a message gives it: "10 rpm..20000 rpm"

    @property
    def label(self) -> str:
        plain = self.shown_unit in ("1", "count")
        return self.name if plain else f"{self.name} ({self.shown_unit})"

    def shown(self, si: float) -> float:
        """``si`` in the slider's unit, to 12 digits (0.0325 m is 32.5 mm, not 32.500...1)."""
        value = float(f"{si / self.factor:.12g}")
        return int(value) if self.unit == "count" else value

    def bounds(self) -> tuple[float, float]:
        """The plausible range in the slider's unit: what its box may take."""
        return self.shown(self.low), self.shown(self.high)

    def neighbourhood(self, si: float) -> tuple[float, float, float]:
        """(min, max, step) of the slider around the value ``si``, in its unit."""
        value, (low, high) = self.shown(si), self.bounds()
        if low > 0:
            start, end = value / 2, value * 2
        else:
            reach = max(abs(value), (high - low) / 20)
            start, end = value - reach, value + reach
        step = _round_step((end - start) / STOPS)
        if self.unit == "count":
            step = max(1, int(step))
        digits = max(0, -math.floor(math.log10(step)))
        start = max(low, round(math.floor(start / step) * step, digits))
        end = min(high, round(math.ceil(end / step) * step, digits))
        if end <= start:  # (a value at an end of a narrow range)
            start, end = low, high
        if self.unit == "count":  # (a slider of whole numbers: viser keeps ints)
            return int(start), int(end), int(step)
        return start, end, step


def _round_step(size: float) -> float:
    """The largest of 1, 2 and 5 times a power of ten within ``size``."""
    if size <= 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(size))
    return max(m * power for m in (1, 2, 5) if m * power <= size * (1 + 1e-9))


def dimension_range(d: Dimension) -> DimensionRange:
    """The slider of a dimension with a range: in the unit both ends of the range are
    written in (rpm, mm, deg: those mcar converts itself), else its SI unit."""
    ends = [_END_UNIT.match(end).group(1) for end in d.range.text.split("..", 1)]
    shown_unit, factor = d.unit, 1.0
    if ends[0] == ends[1] and FAST_UNITS.get(ends[0], (None,))[0] == d.unit:
        shown_unit, factor = ends[0], FAST_UNITS[ends[0]][1]
    return DimensionRange(d.name, d.unit, d.range.low, d.range.high, _default(d), d.meaning,
                          shown_unit, factor, d.range.shown)


class Dimensions:
    """The overridable dimensions of the config.xacro a robot is built from, and the
    overrides now applied (``values``, SI; what the page shows)."""

    def __init__(self, inp: RobotInput, options: LoadOptions, spec: ConfigSpec,
                 search: PackageSearch):
        self.inp, self.options, self.spec, self.search = inp, options, spec, search
        self.values: dict[str, float] = dict(options.overrides.values) \
            if options.overrides is not None else {}
        self.ranges = [dimension_range(d) for d in spec.base()
                       if d.range is not None and not d.baked]

    def value(self, name: str) -> float:
        return self.values.get(name, _default(self.spec.dimensions[name]))

    def with_value(self, name: str, value: float) -> dict[str, float]:
        """The overrides with ``name`` set to ``value``, validated as ``--set`` validates
        it (UsageError); a dimension back at its default is no override."""
        (checked,) = parse_set_options(self.spec, [f"{name}={value!r}"]).values()
        values = {key: v for key, v in self.values.items() if key != name}
        # (a value shown in rpm comes back from the page a rounding away from its SI)
        if not math.isclose(checked, _default(self.spec.dimensions[name]), rel_tol=1e-11):
            values[name] = checked
        return values

    def load(self, values: dict[str, float] | None = None) -> ViewModel:
        """Build and check the robot with ``values`` (the current overrides when None),
        probed as ``--set`` is: config.xacro's cross-checks refuse dimensions that do not
        fit together (UsageError). Once it is built, they are the current overrides."""
        values = dict(self.values if values is None else values)
        with applied_overrides(self.spec, values, self.search) as overrides:
            model = load_model(self.inp, self.options.replace(overrides=overrides))
        self.values = values
        return model

    def yaml(self) -> str:
        """The current overrides as a file ``--config`` reads: ``name: value`` in SI."""
        import yaml

        return yaml.safe_dump(self.values, sort_keys=False) if self.values else "{}\n"


def robot_dimensions(inp: RobotInput, options: LoadOptions,
                     model: ViewModel) -> Dimensions | None:
    """The dimensions of the robot ``model`` shows, or None when it is not built from a
    config.xacro (a URDF, stdin, a robot of a package without one)."""
    if inp.path is None or not inp.is_xacro:
        return None
    search = PackageSearch(package_paths=list(options.package_paths), origin=inp.path)
    try:
        path = config_file(search)
        if path.resolve() not in {Path(file).resolve() for file in model.files}:
            return None
        spec = load_spec(path)
    except McarError:  # a config.xacro `mcar config` refuses: the robot, without sliders
        return None
    return Dimensions(inp, options, spec, search)


def _default(dimension: Dimension) -> float:
    value = float(dimension.expression)
    return int(value) if dimension.unit == "count" else value
