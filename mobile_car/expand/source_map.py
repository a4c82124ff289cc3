"""Point a problem in a URDF built from xacro back at the xacro source, where possible.

xacro keeps no line numbers, so the source line is found by name: the element, or its
nearest ancestor with a ``name`` (the link or joint), is searched for as
``<TAG ... name="VALUE"`` and then as ``name="VALUE"`` in the files the build read (the
input first, then its includes). A name written literally is found at its definition; a
name passed to a macro (``<xacro:wheel name="left"/>``) is found at the call when the
macro builds the name from it unchanged. A name computed inside a macro
(``name="wheel_${side}_link"``) is found by matching the template as a pattern
(``wheel_.*_link``) against the built name. A ``<gazebo reference="...">`` block is found
by its reference the same way, or at the macro call that passes the reference (under
whatever parameter name). An element without a name of its own (a
``<visul>`` inside a link) is then looked for as its tag after its ancestor's line, the
same number of times it occurs under that ancestor. When nothing matches, the diagnostic
names the input file without a line and says which line of the expanded URDF it is about.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..check.urdf_model import tag_name
from ..load.bounded import read_text_quietly
from ..load.inputs import display_path


class SourceLocator:
    def __init__(self, source: Path, deps: list[Path]):
        self.source = display_path(source)
        self.files = list(dict.fromkeys([source, *deps]))
        self._lines: dict[Path, list[str]] = {}
        self._texts: dict[Path, str] = {}
        self._found: dict[tuple[str, str], tuple[str, int] | None] = {}

    def _read(self, path: Path) -> list[str]:
        if path not in self._lines:
            self._lines[path] = (read_text_quietly(path) or "").splitlines()
        return self._lines[path]

    def _text(self, path: Path) -> str:
        """The file's lines joined by "\\n": one search per file, not one per line."""
        if path not in self._texts:
            self._texts[path] = "\n".join(self._read(path))
        return self._texts[path]

    def _search(self, tag: str, name: str, attribute: str = "name") -> tuple[str, int] | None:
        key = (tag, name, attribute)
        if key not in self._found:
            quoted = re.escape(name)
            value = rf"""{attribute}\s*=\s*(?:"{quoted}"|'{quoted}')"""
            # [^>\n]: a tag's name is found on one line, as it always was
            patterns = [re.compile(rf"<{re.escape(tag)}\b[^>\n]*\b{value}"),
                        re.compile(rf"\b{value}")]
            if attribute != "name":  # a <gazebo> a macro makes: the call that names it
                patterns.append(re.compile(
                    rf"""<xacro:[\w.-]+\b[^>\n]*=\s*(?:"{quoted}"|'{quoted}')"""))
            self._found[key] = None
            for pattern in patterns:
                hit = self._first_hit(pattern, literal=name)
                if hit:
                    self._found[key] = hit
                    break
            else:
                self._found[key] = self._template_hit(tag, name, attribute)
        return self._found[key]

    def _template_hit(self, tag: str, name: str, attribute: str) -> tuple[str, int] | None:
        """The first ``<TAG name="...${...}...">`` whose template matches the built name."""
        opening = re.compile(rf"""<{re.escape(tag)}\b[^>\n]*\b{attribute}\s*=\s*(["'])"""
                             r"""([^"'\n]*\$\{.*?)\1""")
        for path in self.files:
            text = self._text(path)
            for match in opening.finditer(text):
                if _template_matches(match.group(2), name):
                    return display_path(path), text.count("\n", 0, match.start()) + 1
        return None

    def _refine(self, hit: tuple[str, int], anchor, where) -> tuple[str, int]:
        """From the anchor's line, the line of ``where`` itself: its tag's k-th occurrence."""
        tag = tag_name(where)
        same = [e for e in anchor.iter(where.tag) if e is not anchor]
        if where not in same:
            return hit
        k = same.index(where)
        path = next((p for p in self.files if display_path(p) == hit[0]), None)
        if path is None:
            return hit
        pattern = re.compile(rf"<{re.escape(tag)}\b")
        lines = self._read(path)
        for number in range(hit[1], min(len(lines), hit[1] + 400) + 1):
            if pattern.search(lines[number - 1]):
                if k == 0:
                    return hit[0], number
                k -= 1
        return hit

    def _first_hit(self, pattern, literal: str | None = None) -> tuple[str, int] | None:
        """The first match in the files, in order; a file without ``literal`` is skipped
        unsearched (a name's pattern cannot match where the name is not written)."""
        for path in self.files:
            if literal is not None and literal not in self._text(path):
                continue
            hit = self._search_in(path, pattern)
            if hit:
                return hit
        return None

    def _search_in(self, path: Path, pattern) -> tuple[str, int] | None:
        text = self._text(path)
        match = pattern.search(text)
        if match is None:
            return None
        return display_path(path), text.count("\n", 0, match.start()) + 1

    def __call__(self, where) -> tuple[str, int | None, str]:
        """(file, line, note) for an element of the built URDF, or for a line of it."""
        if isinstance(where, int):
            return self.source, None, f" (line {where} of the expanded URDF)"
        if where.getparent() is None:  # the <robot> itself: the input's <robot> tag
            hit = self._search_in(self.files[0], re.compile(r"^[^\S\n]*<robot\b", re.M))
            if hit:
                return hit[0], hit[1], ""
        element = where
        while element is not None:
            # The robot's own name says nothing about where one of its parts is written.
            anchor = _is_anchor(element) and (element is where or element.tag != "robot")
            attribute = _IDENTITY.get(element.tag, "name")
            name = element.get(attribute) if anchor else None
            if name:
                hit = self._search(tag_name(element), name, attribute)
                if hit:
                    if element is not where:
                        hit = self._refine(hit, element, where)
                    return hit[0], hit[1], ""
            element = element.getparent()
        return (self.source, None,
                f" (line {where.sourceline} of the expanded URDF)")


# The attribute that identifies an element, where it is not ``name``.
_IDENTITY = {"gazebo": "reference"}


def _is_anchor(element) -> bool:
    """Elements whose name identifies them; a visual's <material name> names a colour.
    A ``<gazebo>`` block is known by its ``reference``, a plugin by its name."""
    tag = element.tag
    if tag == "material":
        parent = element.getparent()
        return parent is None or parent.tag == "robot"
    return tag in ("robot", "link", "joint", "visual", "collision", "transmission", "gazebo",
                   "plugin")


def _template_matches(template: str, name: str) -> bool:
    """``wheel_${side}_link`` matches ``wheel_left_link``: each ``${...}`` as ``.+``."""
    parts = re.split(r"\$\{[^}]*\}", template)
    if len(parts) < 2:
        return False
    return re.fullmatch(".+".join(re.escape(p) for p in parts), name) is not None
