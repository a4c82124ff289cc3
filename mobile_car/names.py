"""Names are data: how a file, robot, link or part name is shown, and which names can be made.

A file name may hold any byte but ``/`` and NUL, and a URDF attribute may hold C1 controls,
``&#13;`` or bidi overrides: printed raw, such a name retitles or recolours the terminal,
rewrites the line before it (``\\r``), reverses what follows (U+202E), breaks a one-line
message in two or crashes a caption drawn with Pillow. :func:`shown` is what every message,
table and picture caption prints instead: each such character escaped visibly, as Python
writes it (``\\n``, ``\\x1b``, ``\\u202e``), everything else untouched, so ordinary names
(and check_urdf-compatible output) stay byte-identical. Escaping is idempotent: a shown name
shown again is unchanged, so layers may each make sure.
"""

from __future__ import annotations

import os

# Invisible characters that reorder or hide the text around them (Trojan Source,
# CVE-2021-42574): the bidi embeddings, overrides and isolates, and the marks.
_BIDI = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")
_SHORT = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}
# Cc: C0, DEL and C1 controls; Zl/Zp: line and paragraph separators (U+2028/9), which
# end a line in many viewers; Cs: a byte that is not UTF-8, kept by Python's
# surrogateescape as U+DC80..U+DCFF (printing it raw raises UnicodeEncodeError).
_ESCAPED_CATEGORIES = frozenset(("Cc", "Zl", "Zp", "Cs"))


def _escaped(char: str) -> bool:
    if " " <= char <= "~":  # printable ASCII, the common case
        return False
    import unicodedata  # here: a name in ASCII, the usual case, needs none of its tables

    return char in _BIDI or unicodedata.category(char) in _ESCAPED_CATEGORIES


def _escape(char: str) -> str:
    if char in _SHORT:
        return _SHORT[char]
    code = ord(char)
    if 0xDC80 <= code <= 0xDCFF:  # surrogateescape: show the file name's own byte
        return f"\\x{code - 0xDC00:02x}"
    return f"\\x{code:02x}" if code <= 0xFF else f"\\u{code:04x}"


def shown(name) -> str:
    """``name`` (a str or path) fit to print on one line: control characters, line
    separators and bidi controls escaped (``\\n``, ``\\x1b``, ``\\u202e``), the rest as is."""
    text = os.fspath(name) if isinstance(name, os.PathLike) else str(name)
    if text.isascii() and text.isprintable():  # nothing to escape: the usual name
        return text
    return "".join(_escape(c) if _escaped(c) else c for c in text)


def shown_lines(text: str) -> str:
    """Text of several lines (a report's body): each line as :func:`shown`, the line
    breaks kept."""
    return "\n".join(shown(line) for line in str(text).split("\n"))


def json_safe(text: str) -> str:
    """JSON text (``json.dumps(..., ensure_ascii=False)``) with each character
    :func:`shown` would escape written as JSON's ``\\uXXXX`` instead: the same data for a
    parser, nothing raw for a terminal. (JSON escapes C0 controls in strings itself, so
    what is left stands inside strings, where the escape means the same character; the
    line breaks of its indentation are kept.)"""
    if text.isascii():
        return text
    return "".join(f"\\u{ord(c):04x}" if c != "\n" and _escaped(c) else c for c in text)


# The longest name one path component may have (Linux, macOS, Windows: 255 bytes on
# ext4, XFS, btrfs, APFS; 255 UTF-16 units on NTFS, never fewer than 255 bytes' worth).
NAME_MAX = 255


def component_problem(component: str) -> str | None:
    """Why ``component`` cannot be one file or folder name, or None if it can."""
    if component in ("", ".", ".."):
        return "it is empty, '.' or '..'" if component else "it is empty"
    if "/" in component or "\0" in component:
        return "it holds '/' or a NUL byte"
    try:
        size = len(os.fsencode(component))
    except UnicodeError:
        return "it cannot be encoded as a file name"
    if size > NAME_MAX:
        return f"it is {size} bytes long, and a file name holds at most {NAME_MAX} bytes"
    return None
