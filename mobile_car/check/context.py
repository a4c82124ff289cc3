"""What every check module shares: collecting diagnostics and reading numbers strictly.

A :class:`Reporter` turns "rule R broken at this element" into a :class:`Diagnostic` with
the right FILE:LINE. For a URDF file that is the element's own line; for a URDF built
from xacro, a locator maps the element back to the xacro source where it can.

Numbers are read quickly first: Python's ``float`` reads every number urdfdom reads, and
a few more (``nan``, ``1_0``, a trailing space, a tab between numbers). Each text read
that way is kept, and :meth:`Reporter.numbers_confirmed` then proves in one pass over
their joined bytes that every one of them is spelled with digits, ``.eE+-`` and (in lists)
spaces only, where Python and urdfdom read exactly alike. A document that fails the proof
is checked again with urdfdom's grammar (:mod:`mobile_car.check.urdf_model`) throughout, so the
verdicts are always urdfdom's; the quick way only saves the grammar's regular expression
on the common spelling (much of checking a robot whose every number differs).
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import repeat
from math import isfinite

from .diagnostics import Diagnostic
from .urdf_model import parse_number, parse_numbers, tag_name

# (file, line or None, a note to append to the message or "")
Locator = Callable[[object], tuple[str, "int | None", str]]


_CLEAN: set = set()
_CLEAN_LIMIT = 1_000_000
_LISTS_KEPT = 4096
# Texts read by float() are joined by "," (which no number read that way contains) and
# must then consist of these bytes only.
_SINGLE_BYTES = b"0123456789.eE+-,"
_LIST_BYTES = _SINGLE_BYTES + b" "


# Bounds of rule E117: numbers urdfdom reads but that no robot has, and that overflow
# when drawn or simulated (1e300 squared is inf). Lengths and coordinates in metres (a
# robot a thousand kilometres across is a typo); angles in radians alike; a mesh scale so
# that 1e6 m of mesh times the scale still fits float32 (3.4e38) with room; inertia
# moments up to the largest mass at the largest distance.
MAX_LENGTH = 1e6
MAX_ANGLE = 1e6
MAX_SCALE = 1e6
MAX_MASS = 1e6
MAX_INERTIA = MAX_MASS * MAX_LENGTH ** 2


def within(values, bound: float) -> bool:
    """True if every value's magnitude is at most ``bound`` (False for a NaN)."""
    # A loop, not all() over a generator: called for most numbers of a robot, and a
    # generator's frame costs more than the comparisons.
    for value in values:
        if not -bound <= value <= bound:
            return False
    return True


def _power(bound: float) -> str:
    """1e+06 -> 1e6, as the rule text writes the bounds."""
    return f"{bound:.0e}".replace("e+0", "e").replace("e+", "e")


def has_xacro_expression(text: str) -> bool:
    return "${" in text or "$(" in text


def shorten(text: str, limit: int = 60) -> str:
    text = text.replace("\t", "\\t").replace("\n", "\\n").replace("\r", "\\r")
    return text if len(text) <= limit else text[: limit - 3] + "..."


class Reporter:
    """Collects the diagnostics of one input.

    ``quick_numbers``: read numbers with ``float`` and prove the spelling afterwards (see
    the module docstring); False reads each with urdfdom's grammar straight away.
    """

    def __init__(self, file: str, locate: Locator | None = None, line_of=None,
                 quick_numbers: bool = True):
        self.file = file
        self.locate = locate
        self.line_of = line_of or (lambda element: element.sourceline)
        self.diagnostics: list[Diagnostic] = []
        self.quick_numbers = quick_numbers
        self._read_singles: list[str] = []
        self._read_lists: list[str] = []
        self._read_triples: list[str] = []  # read together: see triples()
        # Lists read so far, up to _LISTS_KEPT: robots repeat "0 0 1" and "0 0 0" thousands
        # of times and those come early; remembering every list of a CAD export, where
        # almost none repeats, would cost more than it saves.
        self._lists: dict[str, tuple[float, ...]] = {}
        # Keys found clean here; they join _CLEAN only once the numbers are confirmed.
        self._clean_here: set = set()

    def once_clean(self, key, check, *args) -> None:
        """Run ``check(*args)`` unless an element with the same ``key`` already passed it.

        Robots repeat the same origins, shapes and limits thousands of times; a check
        whose verdict depends only on ``key`` runs once per distinct clean value.
        """
        if key in _CLEAN or key in self._clean_here:
            return
        before = len(self.diagnostics)
        check(*args)
        if len(self.diagnostics) == before:
            self._clean_here.add(key)

    def numbers_confirmed(self) -> bool:
        """True if urdfdom reads every number read so far as ``float`` did; then the
        values found clean here are remembered for the next inputs too."""
        if self.quick_numbers:
            singles = ",".join(self._read_singles).encode()
            lists = ",".join(self._read_lists).encode()
            if singles.translate(None, _SINGLE_BYTES) or lists.translate(None, _LIST_BYTES):
                return False
            # Texts read together (triples()): each one's three numbers one space apart.
            triples = self._read_triples
            if ",".join(triples).encode().translate(None, _LIST_BYTES) or \
                    set(map(str.count, triples, repeat(" "))) - {2}:
                return False
        if len(_CLEAN) < _CLEAN_LIMIT:
            _CLEAN.update(self._clean_here)
        return True

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

    def place(self, element) -> str:
        """Where another element was written, for a message that points at two places (a
        name defined twice): "line 12" in a plain URDF; in one built from xacro its source
        file and line and the macro calls, never a line of the expansion nobody wrote."""
        if self.locate is None:
            return f"line {self.line_of(element)}"
        file, line, note = self.locate(element)
        if line is None:  # the expansion's line: the note says so
            return f"{file}{note}"
        calls = note.removeprefix(" (").removesuffix(")")
        return f"{file}:{line}, {calls}" if calls else f"{file}:{line}"

    def value(self, text: str | None) -> float | None:
        """The number urdfdom reads from ``text``, or None (absent or unreadable); silent."""
        if not self.quick_numbers:
            return parse_number(text)
        try:
            value = float(text)
        except (TypeError, ValueError):  # TypeError: no text
            return parse_number(text)
        if not isfinite(value):
            return None  # nan, inf, 1e400: C++ reads none of them
        self._read_singles.append(text)
        return value

    def values(self, text: str | None, count: int) -> tuple[float, ...] | None:
        """Exactly ``count`` numbers from ``text``, or None (absent or unreadable); silent."""
        if self.quick_numbers and text is not None:
            known = self._lists.get(text)
            if known is not None and len(known) == count:
                return known
            pieces = text.split()
            if len(pieces) == count:
                try:
                    values = tuple(map(float, pieces))
                except ValueError:
                    values = None
                if values is not None and all(map(isfinite, values)):
                    self._read_lists.append(text)
                    if len(self._lists) < _LISTS_KEPT:
                        self._lists[text] = values
                    return values
        value = parse_numbers(text, count)
        return value if value.__class__ is tuple else None

    def triples(self, texts: list[str]) -> tuple[float, ...] | None:
        """Three numbers from each of ``texts``, all in one tuple, or None if one does not
        read; silent. Unlike :meth:`values`, a number may come back infinite (1e400):
        the caller bounds every one of them."""
        if self.quick_numbers:
            # Cut at each space: three words in all per text, each text's one space apart
            # (two spaces apart or with spaces around, as urdfdom allows, make an empty
            # word, which float refuses: then one by one below); that each has three,
            # not four here and two there, is proved with the spelling: every text has
            # two spaces (numbers_confirmed). (Another white space float takes around a
            # word fails the spelling.)
            words = " ".join(texts).split(" ")
            if len(words) == 3 * len(texts):
                try:
                    values = tuple(map(float, words))
                except ValueError:
                    values = None
                if values is not None:
                    self._read_triples += texts
                    return values
        values = []
        for text in texts:
            three = self.values(text, 3)
            if three is None:
                return None
            values += three
        return tuple(values)

    def singles(self, texts: list) -> tuple[float, ...] | None:
        """The number in each of ``texts``, or None if one is absent or does not read;
        silent. A number may come back infinite or NaN: the caller bounds each."""
        if self.quick_numbers:
            try:
                values = tuple(map(float, texts))
            except (TypeError, ValueError):  # TypeError: an absent text
                values = None
            if values is not None:
                self._read_singles += texts
                return values
        values = tuple([self.value(text) for text in texts])
        return None if None in values else values

    def number(self, element, attr: str, owner: str) -> float | None:
        """The number in ``attr``, or None (absent, unreadable: E114, or xacro: E105)."""
        text = element.get(attr)
        if text is None:
            return None
        value = self.value(text)
        if value is None and not has_xacro_expression(text):
            self.add("E114", element, f"{owner}: <{tag_name(element)} {attr}="
                                      f"\"{shorten(text)}\"> is not a number urdfdom can read")
        return value

    def numbers(self, element, attr: str, count: int, owner: str,
                rule: str = "E114") -> tuple[float, ...] | None:
        """Exactly ``count`` numbers from ``attr``, or None (absent or unreadable: ``rule``,
        E114 but for a colour, which only changes how the robot looks)."""
        text = element.get(attr)
        if text is None:
            return None
        value = self.values(text, count)
        if value is None and not has_xacro_expression(text):
            self.add(rule, element, f"{owner}: <{tag_name(element)} {attr}="
                                    f"\"{shorten(text)}\">: {parse_numbers(text, count)}")
        return value

    def origin(self, origin, owner: str) -> None:
        """Check the numbers of an ``<origin>`` Node (None: there is none)."""
        if origin is not None:
            self.once_clean(("origin", origin.get("xyz"), origin.get("rpy")),
                            self._origin, origin, owner)

    def bounded(self, element, attr: str, values, bound: float, unit: str,
                owner: str) -> bool:
        """Report E117 if a number read from ``attr`` is beyond ``bound``; True if not."""
        if values is None or within(values, bound):
            return True
        self.add("E117", element, f"{owner}: <{tag_name(element)} {attr}="
                                  f"\"{shorten(element.get(attr))}\"> is beyond "
                                  f"{_power(bound)}{unit}, more than any robot has")
        return False

    def _origin(self, origin, owner: str) -> None:
        self.bounded(origin, "xyz", self.numbers(origin, "xyz", 3, owner), MAX_LENGTH, " m",
                     owner)
        self.bounded(origin, "rpy", self.numbers(origin, "rpy", 3, owner), MAX_ANGLE, " rad",
                     owner)
