"""The Gazebo helper's answer, checked field by field before anything of it is used.

The helper parses a URDF that may come from an untrusted xacro with libsdformat, in C++: a
crafted file could make it answer anything. So its answer is read as data only: UTF-8, one
JSON object (no NaN, no key twice, nesting past the stack an error), exactly the fields of
format :data:`INTERFACE` (``helpers/mcar-sdformat.cc`` writes them; docs/gazebo.md lists
them), each of its type: libsdformat's version a version string (it is printed in every
report), names and messages strings without NUL of at most 64 KB, lists of
at most 100,000 items, numbers finite (or null where libsdformat's value is not), counts
non-negative integers, joint types from libsdformat's list. Anything else is one
:class:`MalformedReport` saying what was wrong, and nothing of it is used.

Units: masses in kg, lengths in m, angles in rad, inertias in kg m^2.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ..expand.wire import strict_json

INTERFACE = 2  # 2: errors are libsdformat's Errors list only; console_errors added
MAX_STRING_CHARS = 64 * 1024
MAX_LIST_ITEMS = 100_000
_VERSION = re.compile(r"[0-9][0-9A-Za-z.~+-]{0,63}")
JOINT_TYPES = frozenset({"ball", "continuous", "fixed", "gearbox", "prismatic", "revolute",
                         "revolute2", "screw", "universal", "invalid"})


class MalformedReport(Exception):
    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


class OtherInterface(Exception):
    """A well-formed answer of another format: a helper built from another mcar."""

    def __init__(self, interface):
        super().__init__(interface)
        self.interface = interface


@dataclass(frozen=True)
class Message:
    where: str  # libsdformat's source line ("parser_urdf.cc:3226"), "urdfdom", "error code N"
    text: str


@dataclass(frozen=True)
class GazeboLink:
    name: str
    mass: float | None
    centre_of_mass: tuple  # in the link frame, m
    inertia: tuple         # ixx iyy izz ixy ixz iyz about the centre of mass, kg m^2
    pose: tuple            # x y z roll pitch yaw in the model frame
    collisions: int
    visuals: int
    sensors: int


@dataclass(frozen=True)
class GazeboJoint:
    name: str
    type: str
    parent: str
    child: str


@dataclass(frozen=True)
class GazeboFrame:
    name: str
    attached_to: str
    body: str  # the link that carries it ("" if libsdformat could not tell)


@dataclass(frozen=True)
class GazeboModel:
    name: str
    canonical_link: str  # "" when implicit (the first link)
    links: tuple[GazeboLink, ...]
    joints: tuple[GazeboJoint, ...]
    frames: tuple[GazeboFrame, ...]

    @property
    def mass(self) -> float:
        return math.fsum(link.mass or 0.0 for link in self.links)


@dataclass(frozen=True)
class GazeboReport:
    sdformat: str                        # libsdformat's version (the helper's build)
    errors: tuple[Message, ...]          # its verdict: the Errors list its load returned
    console_errors: tuple[Message, ...]  # printed at Error level, not in that list
    warnings: tuple[Message, ...]        # printed at Warning level
    lumped: tuple[tuple[str, str], ...]  # (link, the link it was lumped into), in order
    dropped: tuple[tuple[str, str], ...]  # (link, libsdformat's words) left out for no mass
    model: GazeboModel | None
    sdf: str | None = None               # with --sdf: the SDF libsdformat writes


def read_report(data: bytes, with_sdf: bool = False) -> GazeboReport:
    """The checked report in ``data``; MalformedReport or OtherInterface."""
    try:
        document = strict_json(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        raise MalformedReport(f"not JSON: {type(error).__name__}") from None
    if not isinstance(document, dict):
        raise MalformedReport("not a JSON object")
    interface = document.get("interface")
    if type(interface) is not int:
        raise MalformedReport("no format number")
    if interface != INTERFACE:
        raise OtherInterface(interface)
    fields = {"interface": int, "sdformat": str, "errors": list, "console_errors": list,
              "warnings": list, "lumped": list, "dropped": list, "model": (dict, type(None))}
    if with_sdf:
        fields["sdf"] = str
    _fields(document, "answer", fields)
    if not _VERSION.fullmatch(document["sdformat"]):  # it is printed in every report
        raise MalformedReport("a libsdformat version that is not one (a digit, then at "
                              "most 63 of letters, digits and .~+-)")
    return GazeboReport(
        sdformat=document["sdformat"],
        errors=_items(document["errors"], "errors", _message),
        console_errors=_items(document["console_errors"], "console_errors", _message),
        warnings=_items(document["warnings"], "warnings", _message),
        lumped=_items(document["lumped"], "lumped", lambda item, where: _pair(
            item, where, "link", "into")),
        dropped=_items(document["dropped"], "dropped", lambda item, where: _pair(
            item, where, "link", "text")),
        model=None if document["model"] is None else _model(document["model"]),
        sdf=_text(document["sdf"], "sdf", limit=None) if with_sdf else None)


def _fields(obj, where: str, kinds: dict) -> dict:
    """``obj`` is a dict with exactly these keys, each value of its type."""
    if not isinstance(obj, dict):
        raise MalformedReport(f"{where} is not an object")
    if set(obj) != set(kinds):
        odd = ", ".join(sorted(set(obj) ^ set(kinds)))[:200]
        raise MalformedReport(f"{where} has the wrong fields ({odd})")
    for key, kind in kinds.items():
        value = obj[key]
        # bool is an int to isinstance; no field here is a bool
        if isinstance(value, bool) or not isinstance(value, kind):
            raise MalformedReport(f"{where}: '{key}' is not of its type")
    return obj


def _text(value, where: str, limit: int | None = MAX_STRING_CHARS) -> str:
    if not isinstance(value, str) or "\0" in value or (limit and len(value) > limit):
        raise MalformedReport(f"{where} is not a string of at most {limit} characters "
                              "without NUL")
    return value


def _items(values: list, where: str, read) -> tuple:
    if len(values) > MAX_LIST_ITEMS:
        raise MalformedReport(f"{where} has more than {MAX_LIST_ITEMS} items")
    return tuple(read(item, f"{where}[{index}]") for index, item in enumerate(values))


def _message(item, where: str) -> Message:
    _fields(item, where, {"where": str, "text": str})
    return Message(_text(item["where"], where), _text(item["text"], where))


def _pair(item, where: str, first: str, second: str) -> tuple[str, str]:
    _fields(item, where, {first: str, second: str})
    return _text(item[first], where), _text(item[second], where)


def _number(value, where: str) -> float | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not math.isfinite(value):
        raise MalformedReport(f"{where} is not a number")
    return float(value)


def _numbers(value, count: int, where: str) -> tuple:
    if not isinstance(value, list) or len(value) != count:
        raise MalformedReport(f"{where} is not {count} numbers")
    return tuple(_number(v, where) for v in value)


def _count(value, where: str) -> int:
    if type(value) is not int or not 0 <= value < 1 << 31:
        raise MalformedReport(f"{where} is not a count")
    return value


def _link(item, where: str) -> GazeboLink:
    _fields(item, where, {"name": str, "mass": (int, float, type(None)),
                          "centre_of_mass": list, "inertia": list, "pose": list,
                          "collisions": int, "visuals": int, "sensors": int})
    return GazeboLink(_text(item["name"], where), _number(item["mass"], f"{where}.mass"),
                      _numbers(item["centre_of_mass"], 3, f"{where}.centre_of_mass"),
                      _numbers(item["inertia"], 6, f"{where}.inertia"),
                      _numbers(item["pose"], 6, f"{where}.pose"),
                      _count(item["collisions"], where), _count(item["visuals"], where),
                      _count(item["sensors"], where))


def _joint(item, where: str) -> GazeboJoint:
    _fields(item, where, {"name": str, "type": str, "parent": str, "child": str})
    if item["type"] not in JOINT_TYPES:
        raise MalformedReport(f"{where} has no joint type libsdformat knows")
    return GazeboJoint(*(_text(item[key], where) for key in ("name", "type", "parent",
                                                            "child")))


def _frame(item, where: str) -> GazeboFrame:
    _fields(item, where, {"name": str, "attached_to": str, "body": str})
    return GazeboFrame(*(_text(item[key], where) for key in ("name", "attached_to", "body")))


def _model(item) -> GazeboModel:
    _fields(item, "model", {"name": str, "canonical_link": str, "links": list,
                            "joints": list, "frames": list})
    return GazeboModel(_text(item["name"], "model name"),
                       _text(item["canonical_link"], "canonical link"),
                       _items(item["links"], "links", _link),
                       _items(item["joints"], "joints", _joint),
                       _items(item["frames"], "frames", _frame))
