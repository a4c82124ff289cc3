"""What one file of a description package looks like, read without running it: the facts
robot discovery (:mod:`.discover`) decides on.

One pass of the standard library's expat (no lxml, no xacro: a folder of plain URDFs is
found without importing either, and a xacro is code that discovery never runs) gives the
root element and its name, whether a ``<link>`` or anything that could make one (a macro
call, an include, ``xacro:element``) is written outside the ``<xacro:macro>`` bodies,
how many macros the file defines, and the files it includes with the defaults of its
``<xacro:arg>``\\ s, which :func:`include_target` resolves as far as a package's own
layout tells (``$(find OWN)``, ``$(optenv VAR DEFAULT)``, ``$(arg NAME)``).
"""

from __future__ import annotations

import re
import xml.parsers.expat
from pathlib import Path

from ..errors import InputError
from ..load.bounded import read_input
from ..load.xacro_use import xacro_use

# The xacro elements that are not macro calls (xacro 2's eval_all, in its order).
DIRECTIVES = frozenset({"insert_block", "include", "property", "macro", "arg", "element",
                        "attribute", "if", "unless", "call"})
# Of those, the ones whose result can hold a <link> written elsewhere.
_MAKERS = frozenset({"include", "element", "insert_block", "call"})


class FileShape:
    """The facts about one file. ``read_whole``: expat read all of it without error;
    False when it gave up (a broken file), the file could not be read, or a plain URDF
    with a ``<link>`` needed no more than its root: then nothing past the root is known."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, root: str | None = None, name: str | None = None, links: bool = False):
        self.read_whole = False
        self.root = root  # the root element's tag as written (robot, sdf, xacro:macro)
        self.name = name  # the root's name attribute
        self.links = links  # a <link> outside every <xacro:macro>
        self.makers = False  # a macro call, include or xacro:element outside them
        self.calls = False  # the same but includes: what makes links in this file itself
        self.macros = 0  # <xacro:macro> definitions
        self.uses_xacro = False  # as mobile_car.load.xacro_use decides
        self.includes: list[str] = []  # filename="..." of each include
        self.arg_defaults: dict[str, str] = {}


def file_shape(path: Path) -> FileShape:
    """The shape of ``path`` (within the input size bound; a larger or unreadable file has
    an unknown shape, and whoever loads it reports why)."""
    try:  # named as it is: a message is never shown, and display_path costs a resolve
        data = read_input(path, str(path))
    except (OSError, InputError):
        return FileShape()
    return shape_of(data)


_LINK_RE = re.compile(rb"<link(?![\w.:-])")


def shape_of(data: bytes) -> FileShape:
    if _plain(data) and _LINK_RE.search(data):  # most URDFs: a robot if its root says so
        root = _root(data)
        if root is None:
            return FileShape()
        return FileShape(root=root[0], name=root[1], links=True)
    # Read whole: what it includes and defines, and whether a file with no link in
    # sight is a fragment or broken (a broken file is taken: loading it says where).
    shape = FileShape()
    depth_in_macro = 0  # how many <xacro:macro> bodies enclose the current element
    parser = xml.parsers.expat.ParserCreate()

    def start(tag, attributes):
        nonlocal depth_in_macro
        if shape.root is None:
            shape.root, shape.name = tag, attributes.get("name")
        xacro = tag[len("xacro:"):] if tag.startswith("xacro:") else None
        if xacro == "include" and attributes.get("filename"):
            shape.includes.append(attributes["filename"])
        elif xacro == "arg" and attributes.get("name"):
            shape.arg_defaults[attributes["name"]] = attributes.get("default", "")
        if depth_in_macro or xacro == "macro":
            shape.macros += xacro == "macro"
            depth_in_macro += 1
            return
        if tag == "link":
            shape.links = True
        elif xacro is not None and (xacro in _MAKERS or xacro not in DIRECTIVES):
            shape.makers = True
            shape.calls = shape.calls or xacro != "include"

    def end(tag):
        nonlocal depth_in_macro
        if depth_in_macro:
            depth_in_macro -= 1

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(data, True)
    except (xml.parsers.expat.ExpatError, ValueError):
        return FileShape(root=shape.root, name=shape.name)
    shape.read_whole = True
    shape.uses_xacro = xacro_use(data) is not None
    return shape


def _plain(data: bytes) -> bool:
    """Nothing xacro in it can hide from a look at the bytes (as in xacro_use)."""
    return b"\0" not in data and b"&" not in data and b"$" not in data \
        and b"xacro" not in data


def _root(data: bytes) -> tuple[str, str | None] | None:
    found: list[tuple[str, str | None]] = []

    def start(tag, attributes):
        found.append((tag, attributes.get("name")))
        raise StopIteration  # the root is all we want

    parser = xml.parsers.expat.ParserCreate()
    parser.StartElementHandler = start
    try:
        parser.Parse(data, True)
    except StopIteration:
        pass
    except (xml.parsers.expat.ExpatError, ValueError):
        return None
    return found[0] if found else None


_SUBSTITUTION_RE = re.compile(r"\$\(([^()$]*)\)")  # an innermost $(...)


def include_target(spec: str, including: Path, shape: FileShape,
                   own: tuple[str, Path] | None) -> Path | None:
    """The file an include's ``filename`` names, with the package's own defaults:
    ``$(find OWN)`` is its root, ``$(optenv VAR DEFAULT)`` the default, ``$(arg NAME)``
    the ``<xacro:arg>`` default of the including file. None for anything that needs the
    environment, another package or an expression (``${...}``)."""
    resolved = spec
    for _ in range(8):  # nested substitutions: $(arg x) whose default is $(optenv ...)
        match = _SUBSTITUTION_RE.search(resolved)
        if match is None:
            break
        words = match.group(1).split(None, 2)
        if not words:
            return None
        value = _substitute(words, shape, own)
        if value is None:
            return None
        resolved = resolved[:match.start()] + value + resolved[match.end():]
    if "$" in resolved or not resolved:
        return None
    target = Path(resolved)
    return target if target.is_absolute() else including.parent / target


def _substitute(words: list[str], shape: FileShape, own) -> str | None:
    kind = words[0]
    if kind == "find" and len(words) == 2 and own is not None and words[1] == own[0]:
        return str(own[1])
    if kind == "optenv" and len(words) == 3:
        return words[2]
    if kind == "arg" and len(words) == 2 and words[1] in shape.arg_defaults:
        return shape.arg_defaults[words[1]]
    return None
