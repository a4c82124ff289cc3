"""Point a problem in a URDF built from xacro back at the xacro source.

The expansion records where each element of the URDF was written (:mod:`.origins`): the
file and line of its tag, and the macro calls that expanded it. A diagnostic about an
element names that file and line; when the element was written inside a macro, the
message ends with the calls, innermost first (``(in xacro:wheel called at
robot.urdf.xacro:14)``), so that one problem at four calls of a macro is four
diagnostics, each saying which call. A line of the expanded URDF (a problem found before
any element is known) names the input file, and which line of the expansion it is.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from ..load.inputs import display_path


class SourceLocator:
    """Element of the expanded URDF -> (file, line, note)."""

    def __init__(self, source: Path, origins):
        self.source = display_path(source)
        self.origins = origins  # Origins, or None: every element is then the input's
        self._root = None
        self._index: dict = {}

    def __call__(self, where) -> tuple[str, int | None, str]:
        """(file, line, note) for an element of the built URDF, or for a line of it."""
        if isinstance(where, int):
            return self.source, None, f" (line {where} of the expanded URDF)"
        site = self.origins.site(self._position(where)) if self.origins is not None else None
        if site is None:
            return self.source, None, f" (line {where.sourceline} of the expanded URDF)"
        file, line, calls = site
        return display_path(file), line, _calls_note(calls)

    def _position(self, element) -> int:
        """The element's place in document order, as the origins count them."""
        root = element.getroottree().getroot()
        if root is not self._root:  # proxies kept alive here stay the same objects
            self._root = root
            self._index = {e: i for i, e in enumerate(root.iter(etree.Element))}
        return self._index.get(element, -1)


def _calls_note(calls: list[tuple[str, str, int]]) -> str:
    """`` (in xacro:wheel called at robot.urdf.xacro:14, in xacro:base called at ...)``"""
    if not calls:
        return ""
    return " (" + ", ".join(f"in xacro:{name} called at {display_path(file)}:{line}"
                            for name, file, line in calls) + ")"
