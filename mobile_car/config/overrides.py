"""Dimension overrides applied: validated once, written once, read by xacro.

Overrides (``--set NAME=VALUE``, ``--config FILE.yaml``) reach xacro as a generated
properties file that ``config.xacro`` includes through its ``config`` argument; since
xacro evaluates properties lazily, every derived value follows the overridden ones.
``config.xacro``'s own checks (``xacro.fatal`` messages starting ``config:``) guard the
cross-constraints; for overrides they become usage errors (exit 2) before anything is built.
The same written file serves the probe that evaluates the values and every build after it.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from ..errors import BuildError, UsageError
from ..load.robot import CONFIG_ARG
from ..packages.search import PackageSearch
from .spec import (
    XACRO_NS,
    ConfigSpec,
    Dimension,
    config_file,
    load_spec,
    parse_set_options,
    quoteattr,
    read_config_file,
)


@dataclass(frozen=True)
class Overrides:
    """Validated overrides, and the properties file that applies them."""

    spec: ConfigSpec
    values: dict[str, float]  # the overrides, in SI
    effective: dict[str, float]  # every dimension's value with them applied
    path: Path  # the generated properties file config.xacro includes

    @property
    def mappings(self) -> dict[str, str]:
        """The xacro argument that applies them."""
        return {CONFIG_ARG: str(self.path)}


@contextlib.contextmanager
def prepared_overrides(search: PackageSearch, sets, files) -> Iterator[Overrides | None]:
    """Read, validate and write ``--config`` files then ``--set`` words (they win); None
    when neither is given. The file lives as long as the context."""
    if not sets and not files:
        yield None
        return
    spec, values = read_overrides(search, sets, files)
    with applied_overrides(spec, values, search) as overrides:
        yield overrides


@contextlib.contextmanager
def applied_overrides(spec: ConfigSpec, values: dict[str, float],
                      search: PackageSearch) -> Iterator[Overrides | None]:
    """Validated ``values`` written and probed (config.xacro's cross-checks refuse what does
    not fit: UsageError); None when there are none. The file lives as long as the context."""
    if not values:  # a --config file that changes nothing ({}): as if none were given
        yield None
        return
    with override_mappings(values) as mappings:
        yield Overrides(spec, values, evaluate(spec, mappings, search), Path(mappings[CONFIG_ARG]))


def read_overrides(search: PackageSearch, sets, files) -> tuple[ConfigSpec, dict[str, float]]:
    """The package's config spec and the overrides the files and words give, validated."""
    spec = load_spec(config_file(search))
    overrides: dict[str, float] = {}
    for path in files:
        overrides.update(read_config_file(spec, Path(path)))
    overrides.update(parse_set_options(spec, list(sets)))
    return spec, overrides


def override_document(overrides: dict[str, float]) -> str:
    """The xacro properties file config.xacro includes to apply the overrides."""
    lines = ['<?xml version="1.0"?>',
             "<!-- Written by mcar: dimension overrides for config.xacro. -->",
             f'<robot xmlns:xacro="{XACRO_NS}">']
    lines += [f"  <xacro:property name={quoteattr(name)} value={quoteattr(repr(value))}/>"
              for name, value in overrides.items()]
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


@contextlib.contextmanager
def override_mappings(overrides: dict[str, float]):
    """Yield the xacro arguments that apply the overrides (none when there are none)."""
    if not overrides:
        yield {}
        return
    fd, path = tempfile.mkstemp(prefix="mcar-config-", suffix=".xacro")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(override_document(overrides))
        yield {CONFIG_ARG: path}
    finally:
        os.unlink(path)


def evaluate(spec: ConfigSpec, mappings: dict[str, str],
             search: PackageSearch) -> dict[str, float]:
    """Every dimension's value with the overrides ``mappings`` apply, computed by xacro itself.

    A violated cross-constraint of config.xacro raises UsageError when overrides caused
    it (the user's numbers are the problem) and BuildError when config.xacro alone does.
    """
    from lxml import etree

    from ..expand.xacro_build import build_file

    names = list(spec.dimensions)
    values = " ".join(f"{name}={quoteattr('${' + name + '}')}" for name in names)
    with tempfile.TemporaryDirectory(prefix="mcar-probe-") as tmp:
        probe = Path(tmp) / "config_probe.urdf.xacro"
        probe.write_text(f'<robot name="config_probe" xmlns:xacro="{XACRO_NS}">'
                         f'<xacro:include filename={quoteattr(str(spec.path))}/>'
                         f"<values {values}/></robot>", encoding="utf-8")
        probe_search = PackageSearch(package_paths=search.package_paths, origin=spec.path,
                                     environ=search.environ)
        try:
            result = build_file(probe, mappings, probe_search)
        except BuildError as error:
            _hide_probe(error, probe, spec.path)
            if mappings and error.message.startswith("config:"):
                raise UsageError(f"the dimensions do not fit together: "
                                 f"{error.message[len('config:'):].strip()}") from None
            raise
    element = etree.fromstring(result.xml.encode()).find("values")
    values = {name: float(element.get(name)) for name in names}
    _refuse_non_finite(spec, values, bool(mappings))
    return {name: int(value) if spec.dimensions[name].unit == "count" and value.is_integer()
            else value for name, value in values.items()}


def _hide_probe(error: BuildError, probe: Path, config: Path) -> None:
    """The probe is mcar's own temporary file: an error in config.xacro names only the
    user's files (the probe's "included from" line would show a path that no longer exists)."""
    if error.file is not None and Path(error.file).name == probe.name:
        error.file, error.line = str(config), None
    error.details = [line for line in error.details
                     if not line.endswith(probe.name) and str(probe.parent) not in line]


def _refuse_non_finite(spec: ConfigSpec, values: dict[str, float], overridden: bool) -> None:
    """Finite inputs can still overflow an expression (a product of huge sizes): an "inf"
    or "nan" would go into the URDF as text, so it stops here, naming the expression."""
    import math

    for name, value in values.items():
        if not math.isfinite(value):
            dimension = spec.dimensions[name]
            expression = dimension.expression.strip().removeprefix("${").removesuffix("}")
            message = f"{name} = {expression} comes out as {value}, not a finite number"
            if overridden:
                raise UsageError(f"the dimensions do not fit together: {message}")
            raise BuildError(f"config: {message}", file=str(spec.path), line=dimension.line)


def resolve_overrides(search: PackageSearch, sets, files
                      ) -> tuple[ConfigSpec, dict[str, float], dict[str, float]]:
    """The spec, the validated overrides in SI, and every dimension's effective value
    (also with no overrides: what ``mcar config`` shows)."""
    spec, overrides = read_overrides(search, sets, files)
    with override_mappings(overrides) as mappings:
        return spec, overrides, evaluate(spec, mappings, search)


def _default_of(dimension: Dimension) -> float | str:
    """A dimension's default as config.xacro writes it: its number, or the expression a
    dimension with a range may hold (``${...}``: the default is that text)."""
    try:
        return float(dimension.expression)
    except ValueError:
        return dimension.expression.strip()


def config_table(spec: ConfigSpec, values: dict[str, float],
                 overrides: dict[str, float]) -> dict:
    """The effective configuration as plain data (for JSON/YAML, and the text table).

    Its ``dimensions`` part is a valid ``--config`` file: the output round-trips.
    """
    def entry(dimension: Dimension) -> dict:
        item = {"value": values[dimension.name], "unit": dimension.unit,
                "kind": dimension.kind, "source": dimension.source,
                "meaning": dimension.meaning, "defined": f"{dimension.file}:{dimension.line}"}
        if dimension.range is not None:
            item["range"] = [dimension.range.low, dimension.range.high]
            item["range_text"] = dimension.range.text
        if dimension.derived:
            item["expression"] = dimension.expression.strip()[2:-1]
        elif dimension.name in overrides and \
                overrides[dimension.name] != _default_of(dimension):
            item["overridden"] = True
            item["default"] = _default_of(dimension)
        return item

    return {"config": str(spec.path),
            "dimensions": {d.name: entry(d) for d in spec.base()},
            "derived": {d.name: entry(d) for d in spec.derived()}}
