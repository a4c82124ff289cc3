"""Whether a file not named ``.xacro`` is a xacro all the same, and the note that says so.

TurtleBot3's released ROS 2 files are named ``.urdf`` but declare
``<xacro:arg name="namespace">`` and write ``${namespace}``; their launch files run xacro
on them, as the ``xacro`` command runs on any file whatever its name. Every mcar command
does the same (:func:`~mobile_car.load.robot.load_robot`), and says so once per file
through the listener the command line installs (the library prints nothing).

A file *uses* xacro when, as XML, it has an element or attribute in the ``xacro:``
prefix, a ``${...}`` or ``$(...)`` in an attribute value or text, or a comment that
switches xacro's comment evaluation on. A bare ``xmlns:xacro`` declaration is no use: a
file with nothing else is read as the URDF it is. Decided on the parsed document (the
standard library's expat, no lxml: checking a plain URDF stays light), so an entity
(``&#36;{``) or a UTF-16 file is judged by what xacro would see. A file that is not
well-formed XML uses nothing: it is read as a URDF, and checking it says where it breaks.

Deciding "uses xacro" only chooses xacro over reading the file as it is; what then runs
xacro (:func:`~mobile_car.expand.xacro_build.build_file`) decides for itself whether the
sandbox is needed, so a wrong answer here can never run a file's code unconfined.
"""

from __future__ import annotations

import functools
import os
import xml.parsers.expat
from collections.abc import Callable
from pathlib import Path

from ..errors import InputError
from .bounded import read_input


class _Found(Exception):
    """Raised from an expat handler to stop at the first use."""


def xacro_use(data: bytes) -> str | None:
    """What in ``data`` is xacro (``<xacro:arg>``, ``${namespace}``), or None."""
    # Most URDFs say neither word (xacro's prefix is lower case): decided without
    # parsing. Bytes are enough only when the text is ASCII-compatible (no NUL: UTF-16
    # and UTF-32 have them) and holds no character reference (&#36; is $).
    if b"\0" not in data and b"&" not in data and b"$" not in data \
            and b"xacro" not in data:
        return None
    parser = xml.parsers.expat.ParserCreate()
    parser.buffer_text = True  # a text comes in one piece: "${" is never split

    def start(name, attributes):
        if name.startswith("xacro:"):
            raise _Found(f"<{name}>")
        for attribute, value in attributes.items():
            if attribute.startswith("xacro:"):
                raise _Found(f"<{name} {attribute}=...>")
            _expression_in(value)

    def text(data):
        _expression_in(data)

    def comment(data):
        if "xacro:eval-comments" in data:
            raise _Found("<!-- xacro:eval-comments -->")

    parser.StartElementHandler = start
    parser.CharacterDataHandler = text
    parser.CommentHandler = comment
    try:
        parser.Parse(data, True)
    except _Found as found:
        return str(found)
    except (xml.parsers.expat.ExpatError, ValueError):
        return None
    return None


def _expression_in(text: str) -> None:
    for opening, closing in (("${", "}"), ("$(", ")")):
        start = text.find(opening)
        if start >= 0:
            end = text.find(closing, start)
            short = 0 <= end - start <= 40
            raise _Found(text[start:end + 1] if short else f"{opening}...{closing}")


def file_xacro_use(path: Path) -> str | None:
    """:func:`xacro_use` of a file (None when it cannot be read: loading it says why)."""
    try:
        stat = os.stat(path)
    except OSError:
        return None
    return _cached_use(os.path.abspath(path), stat.st_mtime_ns, stat.st_size, stat.st_ino)


@functools.lru_cache(maxsize=256)
def _cached_use(path: str, _mtime: int, _size: int, _inode: int) -> str | None:
    try:
        return xacro_use(read_input(Path(path)))
    except (OSError, InputError):
        return None


# -- the note ------------------------------------------------------------------------------

_listener: Callable[[str, str], None] | None = None


def listen(callback: Callable[[str, str], None] | None) -> None:
    """Have ``callback(label, use)`` called when a file not named .xacro is expanded
    because it uses xacro (the command line prints it); None stops it."""
    global _listener
    _listener = callback


def note_expanded(label: str, use: str) -> None:
    if _listener is not None:
        _listener(label, use)


def note_text(use: str) -> str:
    """The note's words, after the file's name."""
    return f"uses xacro ({use}): expanded like a .xacro, as the xacro command does"
