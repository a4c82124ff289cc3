"""One problem found in a file, and its three spellings: text, GitHub annotation, JSON;
and the robot's size as check says it.

The library only builds the strings and dicts; the command line prints them.
"""

from __future__ import annotations

from ..errors import EXIT_OK, EXIT_PROBLEMS
from ..names import shown, shown_lines
from ..values import Value
from .rules import ERROR, NOTE, RULES, WARNING


class Diagnostic(Value):
    """A rule broken at FILE:LINE (line is None when no line is known)."""

    _fields = __slots__ = ("rule", "file", "line", "message")
    rule: str
    file: str
    line: int | None
    message: str

    def __init__(self, rule: str, file: str, line: int | None, message: str):
        self._set(rule, file, line, message)

    @property
    def severity(self) -> str:
        return RULES[self.rule].severity

    @property
    def is_error(self) -> bool:
        return self.severity == ERROR

    def sort_key(self):
        return (self.file, self.line or 0, self.rule, self.message)

    def location(self) -> str:
        """``FILE:LINE``, the name escaped (mobile_car.names: a file name is data)."""
        return f"{shown(self.file)}:{self.line}" if self.line else shown(self.file)

    def text(self) -> str:
        """``FILE:LINE: error: message [E104]``, the form compilers and linters use."""
        return f"{self.location()}: {self.severity}: {shown(self.message)} [{self.rule}]"

    def rule_name(self) -> str:
        return RULES[self.rule].name

    @classmethod
    def knows(cls, rule: str) -> bool:
        """Whether ``rule`` is one of this kind's (a recorded diagnostic is checked)."""
        return rule in RULES

    def github(self) -> str:
        """A GitHub Actions workflow command that annotates the line in the pull request."""
        return github_annotation(self.severity, self.file, self.line,
                                 f"{self.rule} {self.rule_name()}", self.message)

    @property
    def is_warning(self) -> bool:
        return self.severity == WARNING

    def as_json(self) -> dict:
        return {"rule": self.rule, "severity": self.severity, "file": self.file,
                "line": self.line, "message": self.message}


class Counted:
    """``errors``, ``warnings`` and the exit code of an object's ``diagnostics`` and
    ``failure`` (a check's result, or one read back from its record)."""

    diagnostics: list
    failure: object

    def exit_code(self, strict: bool = False) -> int:
        if self.failure is not None:
            return self.failure.exit_code
        if self.errors or (strict and self.warnings):
            return EXIT_PROBLEMS
        return EXIT_OK

    @property
    def errors(self) -> int:
        return count(self.diagnostics)[0]

    @property
    def warnings(self) -> int:
        return count(self.diagnostics)[1]


def github_annotation(severity: str, file: str, line: int | None, title: str | None,
                      message: str) -> str:
    """``::error file=F,line=L,title=T::message``, escaped as GitHub's toolkit does, after
    control characters other than a message's line breaks are (the log shows ANSI
    sequences: see mobile_car.names)."""
    file, title, message = shown(file), title and shown(title), shown_lines(message)
    severity = "notice" if severity == NOTE else severity  # GitHub's word for a note
    props = [f"file={_escape_property(file)}"]
    if line:
        props.append(f"line={line}")
    if title:
        props.append(f"title={_escape_property(title)}")
    return f"::{severity} {','.join(props)}::{_escape_data(message)}"


def _escape_data(text: str) -> str:
    # The escapes GitHub's toolkit (@actions/core, command.ts) applies to message data.
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(text: str) -> str:
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def count(diagnostics: list[Diagnostic]) -> tuple[int, int]:
    """(errors, warnings); notes are neither."""
    errors = sum(1 for d in diagnostics if d.is_error)
    return errors, sum(1 for d in diagnostics if d.is_warning)


def size_text(extents: tuple) -> str:
    """``0.28 x 0.31 x 0.19 m``: centimetres shown down to a decimetre, then millimetres."""
    def shown(value: float) -> str:
        return f"{value:.2f}" if value >= 0.1 or value == 0 else f"{value:.3f}" \
            if value >= 0.001 else f"{value:.2g}"
    return " x ".join(map(shown, extents)) + " m"
