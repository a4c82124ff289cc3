"""Document rules: the ``<robot>`` root, its name and version, DTDs, leftover xacro, and
whitespace that lxml hides but urdfdom's TinyXML does not.
"""

from __future__ import annotations

import bisect
import re
import sys

from .context import Reporter, has_xacro_expression, shorten
from .urdf_model import tag_name

# The patterns a sound robot rarely needs are compiled by re at their first use (and kept
# in its cache): a check that never needs them does not pay for compiling them.
_VERSION = r"[ \t\n\r\f\v]*\+?([0-9]+)\.[ \t\n\r\f\v]*\+?([0-9]+)\Z"
NUMERIC_ATTRS = ("xyz", "rpy", "size", "scale", "rgba", "radius", "length", "value", "ixx",
                 "ixy", "ixz", "iyy", "iyz", "izz", "lower", "upper", "effort", "velocity",
                 "soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity", "rising",
                 "falling", "damping", "friction", "multiplier", "offset")
# XML turns a tab or line break inside an attribute value into a space (lxml does);
# TinyXML keeps it, and urdfdom then cannot read the numbers. Only the raw text shows it.
_RAW_WHITESPACE = (rb"[\s\"'](" + "|".join(NUMERIC_ATTRS).encode() + rb")\s*=\s*"
                   rb"(?:\"([^\"\t\n\r<]*[\t\n\r][^\"]*)\"|'([^'\t\n\r<]*[\t\n\r][^']*)')")
# Attributes that hold one number: Reporter.number reads them as lxml gives them (a tab or
# line break turned into a space), which urdfdom reads as it reads TinyXML's text: a
# number may follow whitespace, nothing may follow it.
_LIST_ATTRS = frozenset(("xyz", "rpy", "size", "scale", "rgba"))
_DOCTYPE_SUBSET_RE = re.compile(rb"<!DOCTYPE[^>\[]*\[")
# A line break followed, on its line, by a quote that ends a value: a value spans lines.
# Faster than _RAW_WHITESPACE, which runs only when this finds something. From Python
# 3.11 its runs are possessive (*+): the run before the quote cannot hold a quote, so
# giving its characters back one by one, as re does after each of a file's line breaks
# (an indentation, then "<"), can never make a match; the indentation's spaces are taken
# first by the quicker run of one character. The same matches, in 40% of the time.
_LINE_BREAK_IN_VALUE_RE = re.compile(
    rb"\n *+[^\"'\n<>]*+[\"'](?=[\s/>])" if sys.version_info >= (3, 11)
    else rb"\n[^\"'\n<>]*[\"'](?=[\s/>])")
XACRO_HINT = "build it first: `mcar build FILE.xacro -o FILE.urdf`, or check the .xacro itself"


def normalise_default_namespace(root) -> None:
    """Give elements in a default ``xmlns="..."`` their plain names, as TinyXML sees them."""
    if None not in root.nsmap:
        return
    for element in root.iter():
        tag = element.tag
        if isinstance(tag, str) and tag[0] == "{" and not element.prefix:
            element.tag = tag[tag.index("}") + 1:]


def check_doctype(data: bytes, report: Reporter) -> None:
    """E104: TinyXML reads ``<!DOCTYPE robot>``, but stops at an internal subset ``[...]``."""
    # A "!" is looked for first: memchr finds that none is there ten times faster than the
    # pattern can (a file with no comment and no DOCTYPE has none).
    match = b"!" in data and _DOCTYPE_SUBSET_RE.search(data)
    if match:
        report.add("E104", data.count(b"\n", 0, match.start()) + 1,
                   "DOCTYPE with an internal subset ([...] entity declarations): urdfdom's "
                   "TinyXML cannot read past it")


def check_root(root, report: Reporter) -> bool:
    """Robot, name, version; False if the document is not a robot at all."""
    if tag_name(root) != "robot":
        report.add("E101", root, f"the root element is <{tag_name(root)}>, not <robot>")
        return False
    name = root.get("name")
    if name is None:
        hint = "" if root.find("link") is not None else \
            " (and no link: a xacro macro library? check the robot files that include it)"
        report.add("E102", root, f"<robot> has no name=\"...\"{hint}")
    elif not name.strip():
        report.add("E102", root, "<robot> has an empty name")
    version = root.get("version")
    if version is not None:
        match = re.match(_VERSION, version)
        if not match:
            report.add("E103", root, f"version=\"{shorten(version)}\" is not of the form "
                                     "MAJOR.MINOR; urdfdom 3.0 reads only 1.0")
        elif (int(match.group(1)), int(match.group(2))) != (1, 0):
            report.add("E103", root, f"version=\"{shorten(version)}\": urdfdom 3.0 reads only "
                                     "URDF 1.0")
    return True


def _is_xacro(element) -> bool:
    tag = element.tag
    return isinstance(tag, str) and (tag_name(element).startswith("xacro:")
                                     or (tag[0] == "{" and "xacro" in tag[1:tag.index("}")]))


def check_xacro_leftovers(root, data: bytes, report: Reporter) -> bool:
    """E105 once for xacro elements, once for ``${..}``/``$(..)``; True if elements found."""
    if b"xacro" in data:
        found = [e for e in root.iter() if _is_xacro(e)]
        if found:
            more = f" and {len(found) - 1} more" if len(found) > 1 else ""
            report.add("E105", found[0], f"unexpanded xacro: <{tag_name(found[0])}>{more}; "
                                         f"this is a xacro file, {XACRO_HINT}")
            return True
    # A lone "$" is rare in a URDF: one quick search for it usually saves two slower ones.
    if b"$" in data and (b"${" in data or b"$(" in data):
        places = [(element, attr, value) for element in root.iter()
                  if isinstance(element.tag, str)
                  for attr, value in element.attrib.items() if has_xacro_expression(value)]
        if places:
            element, attr, value = places[0]
            more = f" (and {len(places) - 1} more)" if len(places) > 1 else ""
            report.add("E105", element, f"unexpanded xacro expression {attr}=\"{shorten(value)}\""
                                        f"{more}; {XACRO_HINT}")
    return False


def _urdfdom_refuses(raw: bytes) -> bool:
    """Whether urdfdom fails on the tabs or line breaks of a list of numbers: it splits the
    text on spaces, and reads each piece with ``istream >> double``, which skips whitespace
    before a number, and wants nothing after it ("0 0\n0.1" fails, "\n0 0 0.1" is read)."""
    return any(any(c in piece.lstrip(b"\t\n\r") for c in (b"\t", b"\n", b"\r"))
               or not piece.strip(b"\t\n\r") for piece in raw.split(b" ") if piece)


def check_raw_whitespace(root, data: bytes, report: Reporter) -> None:
    """E114 for numbers separated by tabs or line breaks in the raw text (lost by lxml)."""
    if b"\t" not in data and b"\r" not in data and not _LINE_BREAK_IN_VALUE_RE.search(data):
        return
    hits = [(data.count(b"\n", 0, m.start(1)) + 1, m.group(1).decode())
            for m in re.finditer(_RAW_WHITESPACE, data)
            if m.group(1).decode() in _LIST_ATTRS and _urdfdom_refuses(m.group(2) or m.group(3))]
    if not hits:
        return
    by_line = {}
    for element in root.iter():
        if isinstance(element.tag, str):
            by_line.setdefault(element.sourceline, element)
    lines = sorted(by_line)
    for line, attr in hits:
        # libxml2 gives an element the line its start tag ends on, so the tag holding the
        # attribute is the first one ending at or after the attribute's line.
        index = bisect.bisect_left(lines, line)
        element = by_line[lines[index]] if index < len(lines) else line
        report.add("E114", element, f"{attr}=\"...\" has a tab or line break between numbers; "
                                    "urdfdom separates numbers by spaces only")
