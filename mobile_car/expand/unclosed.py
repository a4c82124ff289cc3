"""Where an XML nesting mistake was made, not only where expat noticed it.

A tag left open (``<xacro:property …>`` without its ``/``) is noticed by expat at the end
tag that does not match it, often the file's last line; the user needs the line of the
element left open. This parses the file again, keeping the stack of open elements, and
reads off the innermost one when the parser stops.
"""

from __future__ import annotations

import re
import xml.parsers.expat
from dataclasses import dataclass

from ..errors import McarError
from ..load.bounded import read_head

# The files xacro already parsed fit in memory; this bound only stops a re-read of a file
# that changed into something huge between the two reads.
_MAX_BYTES = 64 * 1024 * 1024
_END_TAG_RE = re.compile(r"[^\s>/]+")
_NESTING_CODES = {xml.parsers.expat.errors.codes[xml.parsers.expat.errors.XML_ERROR_TAG_MISMATCH],
                  xml.parsers.expat.errors.codes[xml.parsers.expat.errors.XML_ERROR_NO_ELEMENTS]}


@dataclass(frozen=True)
class Unclosed:
    """The element left open (``name`` opened at ``line``), or a stray end tag."""

    name: str
    line: int
    stray_end: str | None = None  # "</robt>": an end tag that closes nothing open


def find_unclosed(path: str, exc: xml.parsers.expat.ExpatError) -> Unclosed | None:
    """The innermost element still open where ``exc`` stopped the parse of ``path``;
    None when the error is not a nesting mistake or the file cannot be read again."""
    if exc.code not in _NESTING_CODES:
        return None
    try:
        data = read_head(path, _MAX_BYTES)
    except (OSError, McarError):
        return None
    stack: list[tuple[str, int]] = []
    parser = xml.parsers.expat.ParserCreate()
    # A default handler keeps internal entities unexpanded: this second reading must not
    # be the one a "billion laughs" file blows up in (external ones are never fetched).
    parser.DefaultHandler = lambda _data: None
    parser.StartElementHandler = lambda name, _attrs: stack.append(
        (name, parser.CurrentLineNumber))
    parser.EndElementHandler = lambda _name: stack.pop()
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as again:
        if (again.code, again.lineno) != (exc.code, exc.lineno) or not stack:
            return None  # not the same failure (the file changed): say only what expat said
    else:
        return None
    name, line = stack[-1]
    end = _end_tag_at(data, exc.lineno, exc.offset)
    if end is not None and end not in (open_name for open_name, _ in stack):
        return Unclosed(name, line, stray_end=end)  # a misspelt end tag: its line is right
    return Unclosed(name, line)


def _end_tag_at(data: bytes, lineno: int, offset: int) -> str | None:
    """The name of the end tag at expat's error position: expat points just after its
    ``</`` (the offset is in bytes)."""
    lines = data.split(b"\n")
    if not 1 <= lineno <= len(lines):
        return None
    line = lines[lineno - 1]
    if line[max(offset - 2, 0):offset] != b"</":
        return None
    match = _END_TAG_RE.match(line[offset:].decode("utf-8", "replace"))
    return match.group(0) if match else None
