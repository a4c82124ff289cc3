"""Bytes that are not UTF-8, described for a person: where, and what the file probably is.

URDF and xacro are UTF-8 unless their XML declaration says otherwise; a file saved by a
Windows editor is often Windows-1252, one saved as "Unicode" UTF-16. Python and libxml2
say "'utf-8' codec can't decode byte 0xbe in position 16" or "Invalid bytes in character
encoding"; this names the byte, its offset, line and column, and the way out.
"""

from __future__ import annotations

import codecs


def first_bad_offset(data: bytes) -> int | None:
    """The offset of the first byte that is not UTF-8, or None if all of it is."""
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as error:
        return error.start
    return None


def not_utf8(data: bytes, start: int) -> tuple[str, int]:
    """(message, line) for ``data`` that stops being UTF-8 at byte ``start``."""
    line = data.count(b"\n", 0, start) + 1
    column = start - (data.rfind(b"\n", 0, start) + 1) + 1
    return (f"not UTF-8: byte 0x{data[start]:02x} at offset {start} (line {line}, column "
            f"{column}); {_way_out(data)}", line)


def _way_out(data: bytes) -> str:
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return "it looks like UTF-16: convert it with `iconv -f UTF-16 -t UTF-8`"
    try:
        data.decode("cp1252")
    except UnicodeDecodeError:
        return "save it as UTF-8, or name its encoding in <?xml version=\"1.0\" encoding=...?>"
    return ("it reads as Windows-1252 (Latin-1): convert it with "
            "`iconv -f WINDOWS-1252 -t UTF-8`, or declare encoding=\"windows-1252\"")
