"""What every check module shares: collecting diagnostics and reading numbers strictly.

A :class:`Reporter` turns "rule R broken at this element" into a :class:`Diagnostic` with
the right FILE:LINE. For a URDF file that is the element's own line; for a URDF built
from xacro, a locator maps the element back to the xacro source where it can.
"""

from __future__ import annotations

from collections.abc import Callable

from .diagnostics import Diagnostic
from .urdf_model import parse_number, parse_numbers, tag_name

# (file, line or None, a note to append to the message or "")
Locator = Callable[[object], tuple[str, "int | None", str]]


_CLEAN: set = set()
_CLEAN_LIMIT = 1_000_000


def has_xacro_expression(text: str) -> bool:
    return "${" in text or "$(" in text


def shorten(text: str, limit: int = 60) -> str:
    text = text.replace("\t", "\\t").replace("\n", "\\n").replace("\r", "\\r")
    return text if len(text) <= limit else text[: limit - 3] + "..."


class Reporter:
    """Collects the diagnostics of one input."""

    def __init__(self, file: str, locate: Locator | None = None, line_of=None):
        self.file = file
        self.locate = locate
        self.line_of = line_of or (lambda element: element.sourceline)
        self.diagnostics: list[Diagnostic] = []

    def once_clean(self, key, check, *args) -> None:
        """Run ``check(*args)`` unless an element with the same ``key`` already passed it.

        Robots repeat the same origins, shapes and limits thousands of times; a check
        whose verdict depends only on ``key`` runs once per distinct clean value.
        """
        if key in _CLEAN:
            return
        before = len(self.diagnostics)
        check(*args)
        if len(self.diagnostics) == before and len(_CLEAN) < _CLEAN_LIMIT:
            _CLEAN.add(key)

    def add(self, rule: str, where, message: str) -> None:
        """Record ``rule`` at ``where``: an lxml element, or a line number, or None."""
        if where is None or isinstance(where, int):
            file, line, note = self.file, where, ""
            if self.locate is not None and where is not None:
                file, line, note = self.locate(where)
        elif self.locate is not None:
            file, line, note = self.locate(where)
        else:
            file, line, note = self.file, self.line_of(where), ""
        self.diagnostics.append(Diagnostic(rule, file, line, message + note))

    def number(self, element, attr: str, owner: str) -> float | None:
        """The number in ``attr``, or None (absent, unreadable: E114, or xacro: E105)."""
        text = element.get(attr)
        if text is None:
            return None
        value = parse_number(text)
        if value is None and not has_xacro_expression(text):
            self.add("E114", element, f"{owner}: <{tag_name(element)} {attr}="
                                      f"\"{shorten(text)}\"> is not a number urdfdom can read")
        return value

    def numbers(self, element, attr: str, count: int, owner: str) -> tuple[float, ...] | None:
        """Exactly ``count`` numbers from ``attr``, or None (absent or unreadable: E114)."""
        text = element.get(attr)
        if text is None:
            return None
        value = parse_numbers(text, count)
        if value.__class__ is tuple:
            return value
        if not has_xacro_expression(text):
            self.add("E114", element,
                     f"{owner}: <{tag_name(element)} {attr}=\"{shorten(text)}\">: {value}")
        return None

    def origin(self, origin, owner: str) -> None:
        """Check the numbers of an ``<origin>`` Node (None: there is none)."""
        if origin is not None:
            self.once_clean(("origin", origin.get("xyz"), origin.get("rpy")),
                            self._origin, origin, owner)

    def _origin(self, origin, owner: str) -> None:
        self.numbers(origin, "xyz", 3, owner)
        self.numbers(origin, "rpy", 3, owner)
