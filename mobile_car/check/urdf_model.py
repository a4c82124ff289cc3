"""Read URDF text the way urdfdom does: the XML, element names, numbers.

What urdfdom 3.0 (the parser behind ``check_urdf``, robot_state_publisher and rviz) reads
is what counts, so this module copies its rules where they differ from plain XML:

* element names are compared as written (``<u:robot>`` is not ``<robot>``; a default
  ``xmlns=`` does not matter);
* a number is what C++ ``istream >> double`` reads entirely: ``1``, ``-.5``, ``1e-3``, but
  not ``nan``, ``inf``, ``0x10``, ``1,5`` or ``1 `` (trailing space); a list of numbers
  (``xyz="0 0 1"``) is split on spaces only;
* only the first ``<origin>``, ``<limit>``, ... of an element is read.

The XML parser is lxml with entity expansion and network access off. The robot's links
and joints are read from the parsed tree by :mod:`mobile_car.check.urdf_reader`.
"""

from __future__ import annotations

import math
import re

from lxml import etree

# [0-9], not \d: Python's \d also matches Arabic-Indic and other digits C++ does not read.
_NUMBER_RE = re.compile(r"[ \t\n\r\f\v]*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z")


class XmlError(Exception):
    """The text is not XML that urdfdom could read; ``line`` is where lxml stopped."""

    def __init__(self, message: str, line: int | None):
        super().__init__(message)
        self.message = message
        self.line = line


def parse_xml(data: bytes) -> etree._Element:
    """The root element of ``data``; raises XmlError with the line of the first fault."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False,
                             load_dtd=False, collect_ids=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as exc:
        if "encoding" in (exc.msg or "") or "UTF-8" in (exc.msg or ""):
            from ..load.encoding import first_bad_offset, not_utf8

            start = first_bad_offset(data)
            if start is not None:
                raise XmlError(*not_utf8(data, start)) from None
        message = exc.msg or "not well-formed"
        # libxml2 appends ", line N, column M" to some messages; the line goes in front.
        message = re.sub(r", line \d+, column \d+$", "", message)
        raise XmlError(f"not well-formed XML: {message}", exc.lineno) from None
    if root is None:
        raise XmlError("not well-formed XML: no root element", 1)
    return root


class SourceLines:
    """Element -> line, working around libxml2's limit.

    libxml2 keeps an element's line in 16 bits: past line 65535 it finds the true line only
    from a neighbouring text node, so in a file with elements packed on long lines (no
    whitespace between them) it reports 65535. Such an element's line is then found from
    the raw text: the n-th element in document order starts at the n-th start tag.
    """

    CAP = 65535
    # Compiled by re at its first use: only a file past line 65535 needs it.
    _START_TAG = (rb"(?s)<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>"
                  rb"|<!DOCTYPE(?:[^\[>]|\[.*?\])*>|(<)(?![/!?])")

    def __init__(self, root, data: bytes):
        self.root = root
        self.data = data
        self._index: dict | None = None
        self._lines: list[int] = []

    def __call__(self, element) -> int:
        line = element.sourceline
        if line != self.CAP:
            return line
        if self._index is None:
            self._index = {e: i for i, e in enumerate(self.root.iter(etree.Element))}
            line, previous = 1, 0
            for match in re.finditer(self._START_TAG, self.data):
                if match.group(1):
                    line += self.data.count(b"\n", previous, match.start())
                    previous = match.start()
                    self._lines.append(line)
        position = self._index.get(element)
        if position is None or position >= len(self._lines):
            return line
        return self._lines[position]


def tag_name(element) -> str:
    """The element name as written in the file (``xacro:macro``, ``link``), as TinyXML sees it."""
    tag = element.tag
    if not isinstance(tag, str):  # a comment or processing instruction
        return ""
    if tag[0] != "{":
        return tag
    local = tag[tag.index("}") + 1:]
    return f"{element.prefix}:{local}" if element.prefix else local


# Robots repeat the same few values ("0 0 0", "1") thousands of times: parse each once.
_CACHE_LIMIT = 1_000_000
_number_cache: dict[str, float | None] = {}
_numbers_cache: dict[tuple[str, int], tuple[float, ...] | str] = {}


def parse_number(text: str | None) -> float | None:
    """The number urdfdom reads from ``text``, or None if it reads none."""
    if text is None:
        return None
    try:
        return _number_cache[text]
    except KeyError:
        pass
    value = float(text) if _NUMBER_RE.match(text) else None
    if value is not None and not math.isfinite(value):
        value = None  # 1e400: C++ sets failbit on overflow
    if len(_number_cache) < _CACHE_LIMIT:
        _number_cache[text] = value
    return value


def parse_numbers(text: str | None, count: int) -> tuple[float, ...] | str:
    """Exactly ``count`` space-separated numbers, or a message saying what is wrong."""
    if text is None:
        return "missing"
    key = (text, count)
    try:
        return _numbers_cache[key]
    except KeyError:
        pass
    result = _parse_numbers(text, count)
    if len(_numbers_cache) < _CACHE_LIMIT:
        _numbers_cache[key] = result
    return result


_PLAIN_NUMBER = r"([+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)"
# The usual spelling, "0 0.1 -2", read by one regex; anything else takes the long way.
# Compiled by re at their first use: float() reads most lists before they are needed.
_PLAIN_LISTS = {count: r" *" + " +".join([_PLAIN_NUMBER] * count) + r" *\Z" for count in (3, 4)}


def _parse_numbers(text: str, count: int) -> tuple[float, ...] | str:
    plain = _PLAIN_LISTS.get(count)
    match = re.match(plain, text) if plain is not None else None
    if match:
        values = tuple(map(float, match.groups()))
        if all(map(math.isfinite, values)):
            return values
    pieces = [p for p in text.split(" ") if p != ""]
    values = []
    for piece in pieces:
        value = parse_number(piece)
        if value is None:
            if any(c in piece for c in "\t\n\r"):
                return f"'{_show(piece)}' has a tab or line break between numbers " \
                       "(urdfdom separates numbers by spaces only)"
            return f"'{_show(piece)}' is not a number"
        values.append(value)
    if len(values) != count:
        return f"{len(values)} numbers where {count} are needed"
    return tuple(values)


def _show(text: str) -> str:
    return text.replace("\t", "\\t").replace("\n", "\\n").replace("\r", "\\r")


def first_child(element, name: str):
    """The first child element called ``name`` (urdfdom reads only that one), or None."""
    for child in element:
        if child.tag == name:
            return child
    return None


def origin_of(element) -> dict[str, tuple[float, ...]]:
    """``{"xyz": (...), "rpy": (...)}`` of an element's first ``<origin>``; zeros if unreadable."""
    origin = first_child(element, "origin")
    result = {}
    for key in ("xyz", "rpy"):
        value = parse_numbers(origin.get(key, "0 0 0"), 3) if origin is not None else None
        result[key] = value if isinstance(value, tuple) else (0.0, 0.0, 0.0)
    return result


def axis_of(joint) -> tuple[float, ...] | None:
    """The joint axis as urdfdom sets it; None for fixed and floating joints (no axis)."""
    if joint.type in ("fixed", "floating"):
        return None
    axis = first_child(joint.element, "axis")
    if axis is None:
        return (1.0, 0.0, 0.0)
    value = parse_numbers(axis.get("xyz"), 3)
    return value if isinstance(value, tuple) else (0.0, 0.0, 0.0)
