"""The robot's dimensions: read from ``urdf/config.xacro``, overridden, validated.

``config.xacro`` is the one source of truth. Each dimension is a ``<xacro:property>`` with a
comment on its line, ``UNIT[ LO..HI][ (FLAG)]; SOURCE: meaning``; LO..HI is its plausible
range (:mod:`mobile_car.config.ranges`); SOURCE ``derived`` marks a value computed from the
others by an xacro expression, which has no range of its own. Values are never re-computed
here: they are evaluated by xacro itself, by building a small probe that includes
``config.xacro``.

This module reads the spec and validates override values one by one (unit, range, whole
counts, known name); :mod:`mobile_car.config.overrides` applies them.
"""

from __future__ import annotations

import difflib
import functools
import math
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import BuildError, InputError, UsageError
from ..load.input_limit import display_path
from ..packages.bundled import PACKAGE_NAME
from ..packages.search import PackageSearch
from .ranges import KINDS, Range, meant_unit, outside_message, parse_range

XACRO_NS = "http://www.ros.org/wiki/xacro"
# "m 0..20mm (mesh); listing: hub boss length" -> unit, optional range, optional flag,
# source, meaning. A comment without a range (a package made before ranges) keeps the old
# bounds: > 0, or the flag's ">=0" / "any sign".
COMMENT_RE = re.compile(
    r"^ (?P<unit>m|kg|kg/m\^3|rad/s|rad|N\*m|Hz|count|1)(?: (?P<range>[^\s;()]+))?"
    r"(?: \((?P<flag>>=0|any sign|mesh)\))?; "
    r"(?P<source>datasheet|listing|estimate|design|derived): (?P<meaning>\S.*\S) $")
_KIND = {"m": "a length", "kg": "a mass"}


def quoteattr(value: str) -> str:
    """A double-quoted XML attribute value (xml.sax.saxutils would import urllib: slow)."""
    return '"' + (value.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")
                  .replace("\n", "&#10;")) + '"'


@dataclass(frozen=True)
class Dimension:
    """One property of config.xacro and what its comment says about it."""

    name: str
    expression: str
    unit: str
    bound: str  # ">0" (the default), ">=0" or "any sign"; used only without a range
    baked: bool  # baked into a generated mesh: not overridable
    source: str
    meaning: str
    file: Path
    line: int
    range: Range | None = None  # the plausible values; None in configs made before ranges

    @property
    def kind(self) -> str:
        return KINDS.get(self.unit, "value")

    @property
    def derived(self) -> bool:
        return self.source == "derived"


@dataclass
class ConfigSpec:
    path: Path
    dimensions: dict[str, Dimension]

    def base(self) -> list[Dimension]:
        return [d for d in self.dimensions.values() if not d.derived]

    def derived(self) -> list[Dimension]:
        return [d for d in self.dimensions.values() if d.derived]


def config_file(search: PackageSearch) -> Path:
    """The config.xacro that holds the dimensions: that of the package being worked on
    (the one holding the search's origin) when it has ``urdf/config.xacro``, else the
    mobile car's."""
    from ..packages.search import enclosing_package

    own = enclosing_package(search.origin) if search.origin is not None else None
    if own is not None and (own[1] / "urdf" / "config.xacro").is_file():
        return own[1] / "urdf" / "config.xacro"
    return search.find(PACKAGE_NAME) / "urdf" / "config.xacro"


def load_spec(path: Path) -> ConfigSpec:
    """Every documented property of a config.xacro, in file order."""
    from lxml import etree

    try:
        root = etree.parse(str(path), etree.XMLParser(resolve_entities=False,
                                                      no_network=True)).getroot()
    except (OSError, etree.XMLSyntaxError) as error:
        raise InputError(f"cannot read the dimension config: {error}", file=str(path)) from None
    dimensions: dict[str, Dimension] = {}
    for prop, match in _documented(root):
        if match is None:
            raise InputError(f"property '{prop.get('name')}' has no 'UNIT LO..HI; SOURCE: meaning' "
                             "comment on its line", file=str(path), line=prop.sourceline)
        dimensions[prop.get("name")] = Dimension(
            name=prop.get("name"), expression=prop.get("value", ""), unit=match["unit"],
            bound=match["flag"] if match["flag"] in (">=0", "any sign") else ">0",
            baked=match["flag"] == "mesh", source=match["source"], meaning=match["meaning"],
            file=path, line=prop.sourceline, range=_range_of(prop, match, path))
    return ConfigSpec(path=path, dimensions=dimensions)


def _documented(root):
    """Each ``<xacro:property>`` of config.xacro's root, with the match of the comment on
    its line (None when it has none, or one not in the documented form)."""
    from lxml import etree

    for prop in root.findall(f"{{{XACRO_NS}}}property"):
        comment = prop.getnext()
        match = None
        if isinstance(comment, etree._Comment) and comment.sourceline == prop.sourceline:
            match = COMMENT_RE.match(comment.text or "")
        yield prop, match


def check_own_ranges(path: Path) -> None:
    """Refuse a config.xacro whose own values break the ranges its comments state, as
    ``mcar config`` does: every command that loads a robot including it calls this, so a
    value typed in the wrong unit (32.5 for 32.5 mm) stops every command, located at its
    line (BuildError, exit 1). Only ranged properties are judged: a config.xacro not
    written in mcar's documented form is someone else's convention, left alone here.
    Reads one small file with lxml, no xacro (memoised while the file is unchanged)."""
    import os

    try:
        stat = os.stat(path)
    except OSError:
        return  # xacro read it a moment ago; gone now: the build that follows will say
    _check_own_ranges(str(path), stat.st_mtime_ns, stat.st_size)


@functools.lru_cache(maxsize=16)
def _check_own_ranges(path: str, _mtime: int, _size: int) -> None:
    from lxml import etree

    try:
        root = etree.parse(path, etree.XMLParser(resolve_entities=False,
                                                 no_network=True)).getroot()
    except (OSError, etree.XMLSyntaxError):
        return  # xacro has just read it; a file it cannot read is its own error
    for prop, match in _documented(root):
        if match is not None and match["range"] is not None \
                and not _clearly_inside(prop.get("value", ""), match):
            _range_of(prop, match, Path(path))  # the exact verdict, and its message


# Units ranges are written in, and what one is in the config's SI unit: enough to judge
# most values without pint, whose import (~0.25 s) every command would otherwise pay.
_QUICK_UNITS = {"mm": ("m", 1e-3), "cm": ("m", 1e-2), "m": ("m", 1.0), "g": ("kg", 1e-3),
                "kg": ("kg", 1.0), "rpm": ("rad/s", math.pi / 30), "deg": ("rad", math.pi / 180)}
_QUICK_END = re.compile(r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)([a-z]*)")


def _clearly_inside(value_text: str, match) -> bool:
    """True when a value is inside its range by more than any rounding of a unit's
    conversion could move an end; False when unsure, or when something else may be wrong
    (then :func:`_range_of` judges exactly, with pint, and says what)."""
    if match["source"] == "derived" or match["flag"] in (">=0", "any sign"):
        return False
    ends = []
    for end in match["range"].split(".."):
        found = _QUICK_END.fullmatch(end)
        if found is None:
            return False
        number, suffix = float(found[1]), found[2]
        if suffix:
            unit, factor = _QUICK_UNITS.get(suffix, (None, 0.0))
            if unit != match["unit"]:
                return False
            number *= factor
        elif match["unit"] == "count" and not number.is_integer():
            return False
        ends.append(number)
    if len(ends) != 2 or ends[0] > ends[1]:
        return False
    try:
        value = float(value_text)
    except ValueError:
        return True  # an expression: its range holds for what it is computed from
    margin = 1e-9 * max(abs(ends[0]), abs(ends[1]), abs(value), 1e-300)
    return ends[0] + margin < value < ends[1] - margin


def _range_of(prop, match, path: Path) -> Range | None:
    """The property's range, checked against its own flag and default value."""
    if match["range"] is None:
        return None
    name, line = prop.get("name"), prop.sourceline

    def refuse(problem: str):
        return InputError(f"property '{name}': {problem}", file=str(path), line=line)

    if match["source"] == "derived":
        raise refuse("a derived value has no range: give ranges to what it is computed from")
    if match["flag"] in (">=0", "any sign"):
        raise refuse(f"the range {match['range']} already bounds it; drop ({match['flag']})")
    try:
        plausible = parse_range(match["range"], match["unit"])
    except ValueError as error:
        raise refuse(str(error)) from None
    try:
        default = float(prop.get("value", ""))
    except ValueError:
        return plausible
    if default not in plausible:  # a slip in the robot's own description: problems, 1
        hint = _written_hint(prop.get("value"), match["unit"], plausible)
        raise BuildError(f"property '{name}': its value {default:g} is outside its own range "
                         f"{plausible.shown}{hint}", file=display_path(path), line=line)
    return plausible


def _written_hint(raw: str, unit: str, plausible: Range) -> str:
    """"; did you mean 32.5 mm (written 0.0325)?": config.xacro holds bare SI numbers, so
    the hint says what to write, not a unit it cannot take."""
    from .units import parse_quantity

    candidate = meant_unit(raw, unit, plausible)
    if candidate is None:
        return ""
    number = raw.strip()
    value = parse_quantity(f"{number}{candidate}", unit, "hint")
    return f"; did you mean {number} {candidate} (written {value:g})?"


def check_bound(dimension: Dimension, value: float, origin: str) -> None:
    kind = _KIND.get(dimension.unit, "the value")
    if dimension.bound == ">0" and value <= 0:
        raise UsageError(f"{origin}: {dimension.name} = {value:g} {dimension.unit}: "
                         f"{kind} must be > 0")
    if dimension.bound == ">=0" and value < 0:
        raise UsageError(f"{origin}: {dimension.name} = {value:g} {dimension.unit}: "
                         f"{kind} must be >= 0")


def settable_dimension(spec: ConfigSpec, name: str, origin: str,
                       verb: str = "change") -> Dimension:
    """The dimension ``name`` names, or a UsageError: unknown (with the closest name) or
    derived (``verb`` what it is computed from instead)."""
    from .bounded_yaml import short_repr

    dimension = spec.dimensions.get(name)
    if dimension is None:
        close = difflib.get_close_matches(name, list(spec.dimensions), n=1) \
            if len(name) <= 100 else []
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        raise UsageError(f"{origin}: unknown dimension {short_repr(name)}{hint}; "
                         "`mcar config` lists them")
    if dimension.derived:
        raise UsageError(f"{origin}: {name} is derived ({dimension.expression.strip('${}')}), "
                         f"not set: {verb} what it is computed from")
    return dimension


def _override(spec: ConfigSpec, name: str, raw, origin: str) -> float:
    from .units import parse_quantity

    dimension = settable_dimension(spec, name, origin)
    value = parse_quantity(raw, dimension.unit, f"{origin}: {name}")
    if dimension.unit == "count" and not value.is_integer():
        raise UsageError(f"{origin}: {name} = {value:g}: a count is a whole number")
    if dimension.baked and value != float(dimension.expression):
        raise UsageError(f"{origin}: {name} is baked into a mesh (scripts/make_meshes.py); "
                         "change it in config.xacro and regenerate the meshes instead")
    if dimension.range is None:
        check_bound(dimension, value, origin)
    elif value not in dimension.range:
        raise UsageError(f"{origin}: "
                         f"{outside_message(name, raw, value, dimension.unit, dimension.range)}")
    # A count is written as an integer: xacro and Gazebo read "360.0" samples as text.
    return int(value) if dimension.unit == "count" else value


def parse_set_options(spec: ConfigSpec, words: list[str]) -> dict[str, float]:
    """``--set NAME=VALUE`` words as SI overrides."""
    overrides = {}
    for word in words:
        name, sep, raw = word.partition("=")
        if not sep or not name.strip() or not raw.strip():
            raise UsageError(f"--set {word}: expected NAME=VALUE, e.g. wheel_radius=0.04")
        overrides[name.strip()] = _override(spec, name.strip(), raw.strip(), f"--set {word}")
    return overrides


def read_config_file(spec: ConfigSpec, path: Path) -> dict[str, float]:
    """A partial config file: ``name: value`` pairs, or the JSON/YAML `mcar config` writes."""
    import yaml

    from ..load.bounded import read_input
    from .bounded_yaml import DuplicateKey, TooLarge, compose_and_load, short_repr

    shown = str(path)
    try:
        # Numbers stay text: each value is read by parse_quantity, as --set reads it.
        node, data = compose_and_load(read_input(path, shown).decode("utf-8"),
                                      numbers_as_text=True)
    except FileNotFoundError:
        raise InputError("no such file", file=shown) from None
    except IsADirectoryError:
        raise InputError("is a directory, not a config file", file=shown) from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read: {error}", file=shown) from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or "not valid YAML"
        if not isinstance(error, (TooLarge, DuplicateKey)):
            problem = f"not valid YAML: {problem}"
        raise UsageError(problem, file=shown,
                         line=mark.line + 1 if mark else None) from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise UsageError("expected a mapping of dimension names to values", file=shown)
    lines = {}
    if isinstance(node, yaml.MappingNode):
        lines = {k.value: k.start_mark.line + 1 for k, _v in node.value}
    if isinstance(data.get("dimensions"), dict):  # the document `mcar config` prints
        data = {name: (entry.get("value") if isinstance(entry, dict) else entry)
                for name, entry in data["dimensions"].items()}
    overrides = {}
    for name, raw in data.items():
        origin = f"{shown}:{lines[name]}" if name in lines else shown
        if not isinstance(raw, (int, float, str)) or isinstance(raw, bool):
            raise UsageError(f"{origin}: {name}: expected a number, got {short_repr(raw)}")
        overrides[str(name)] = _override(spec, str(name), raw, origin)
    return overrides
