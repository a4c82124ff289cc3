"""The robot's dimensions in the viewer: a slider for each dimension of its config.xacro that
``--set`` may change, and the overrides they make, validated and built as ``--set`` does.

A robot gets them only when it is built from a config.xacro (its package's, or the mobile
car's): a robot of another package has no dimensions to move. Derived dimensions follow
the others and dimensions baked into a mesh cannot change, so neither has a slider.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

from ..config.overrides import applied_overrides
from ..config.spec import ConfigSpec, Dimension, config_file, load_spec, parse_set_options
from ..errors import McarError
from ..load.inputs import RobotInput
from ..load.robot import LoadOptions
from ..packages.search import PackageSearch
from .model import ViewModel, load_model


@dataclass(frozen=True)
class DimensionRange:
    """One dimension's slider: its plausible range (SI), step and default value."""

    name: str
    unit: str
    low: float
    high: float
    step: float
    default: float
    meaning: str

    @property
    def label(self) -> str:
        return self.name if self.unit in ("1", "count") else f"{self.name} ({self.unit})"


def slider_step(dimension: Dimension) -> float:
    """Whole counts; 0.5 mm for lengths (0.05 mm in a range under 5 cm, which would
    otherwise have a few dozen stops); else a round thousandth of the range."""
    low, high = dimension.range.low, dimension.range.high
    if dimension.unit == "count":
        return 1
    if dimension.unit == "m":
        return 0.0005 if high - low >= 0.05 else 0.00005
    return 10.0 ** math.floor(math.log10((high - low) / 1000)) if high > low else 1.0


class Dimensions:
    """The overridable dimensions of the config.xacro a robot is built from, and the
    overrides now applied (``values``, SI; what the page shows)."""

    def __init__(self, inp: RobotInput, options: LoadOptions, spec: ConfigSpec,
                 search: PackageSearch):
        self.inp, self.options, self.spec, self.search = inp, options, spec, search
        self.values: dict[str, float] = dict(options.overrides.values) \
            if options.overrides is not None else {}
        self.ranges = [DimensionRange(d.name, d.unit, d.range.low, d.range.high,
                                      slider_step(d), _default(d), d.meaning)
                       for d in spec.base() if d.range is not None and not d.baked]

    def value(self, name: str) -> float:
        return self.values.get(name, _default(self.spec.dimensions[name]))

    def with_value(self, name: str, value: float) -> dict[str, float]:
        """The overrides with ``name`` set to ``value``, validated as ``--set`` validates
        it (UsageError); a dimension back at its default is no override."""
        (checked,) = parse_set_options(self.spec, [f"{name}={value!r}"]).values()
        values = {key: v for key, v in self.values.items() if key != name}
        if checked != _default(self.spec.dimensions[name]):
            values[name] = checked
        return values

    def load(self, values: dict[str, float] | None = None) -> ViewModel:
        """Build and check the robot with ``values`` (the current overrides when None),
        probed as ``--set`` is: config.xacro's cross-checks refuse dimensions that do not
        fit together (UsageError). Once it is built, they are the current overrides."""
        values = dict(self.values if values is None else values)
        with applied_overrides(self.spec, values, self.search) as overrides:
            model = load_model(self.inp, dataclasses.replace(self.options, overrides=overrides))
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
