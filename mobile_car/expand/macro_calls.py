"""Macro calls without the ``xacro:`` prefix, which xacro 2 copies into the URDF as they are.

ROS 1 tutorials (the seed's complete robot among them) call macros as ``<chassis .../>``;
xacro 2 expands only ``<xacro:chassis .../>`` and leaves the rest in place without a word,
so the robot silently loses its body and wheels. An element named like a macro defined
while expanding, and not like a URDF element (a macro called ``inertial`` may share its
name with one), is such a call. Outside extension elements (``<gazebo>``, ...), whose
contents no URDF rule describes, in the expanded document and in the source text, where
the call is located (and looked for alone when xacro stopped before the end, often on the
call's own attributes).
"""

from __future__ import annotations

import re
from pathlib import Path

from ..check.urdf_vocabulary import EXTENSIONS, SPECS
from ..errors import BuildError
from ..load.bounded import read_text_quietly
from ..load.inputs import display_path

_COMMENT_RE = re.compile(r"<!--.*?-->", re.S)
# An extension element, whole: Gazebo's <sensor><imu> is SDF, not a call of a macro 'imu'
# (Panther defines one, and its <gazebo> blocks hold <imu>).
_EXTENSION_RE = re.compile(
    r"<(" + "|".join(sorted(EXTENSIONS)) + r")(?:\s[^>]*)?(?:/>|>.*?</\1\s*>)", re.S)


def unprefixed_call(macros: set[str], files: list[Path], doc=None) -> BuildError | None:
    """The first call of one of ``macros`` without the prefix, as a located BuildError."""
    names = {name for name in macros if name not in SPECS and name not in EXTENSIONS}
    if not names:
        return None
    if doc is not None:
        names &= _tags_in(doc.documentElement)
        if not names:
            return None
    pattern = re.compile(r"<(" + "|".join(map(re.escape, sorted(names))) + r")[\s/>]")
    for path in files:
        text = read_text_quietly(path)
        if text is None:
            continue
        # Blank comments and extension elements out, keeping their newlines, so line
        # numbers stay right.
        text = _EXTENSION_RE.sub(_newlines, _COMMENT_RE.sub(_newlines, text))
        match = pattern.search(text)
        if match:
            name = match.group(1)
            return BuildError(f"<{name}> calls macro '{name}' without the xacro: prefix; "
                              "xacro 2 copies it into the URDF unexpanded: write "
                              f"<xacro:{name} ...>", file=display_path(path),
                              line=text.count("\n", 0, match.start()) + 1)
    return None


def _newlines(match) -> str:
    return "\n" * match.group(0).count("\n")


def _tags_in(element) -> set[str]:
    """The names of the elements below ``element``, outside extension elements: one walk
    of the document (a walk per macro name was PR2's 60 walks of 10,000 elements)."""
    found: set[str] = set()
    pending = [element]
    while pending:
        for child in pending.pop().childNodes:
            if child.nodeType == child.ELEMENT_NODE and child.tagName not in EXTENSIONS:
                found.add(child.tagName)
                pending.append(child)
    return found
