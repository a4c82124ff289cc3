"""The URDF cases of four upstream projects' own tests (urdfdom, sdformat, urdf_parser_py,
yourdfpy), read in place from ``../shared/upstream-suites/`` (SOURCES.md there): their
test files and the URDF strings their test sources embed, each with the verdict the
upstream test expects of it where a test says.

The strings are taken from the test sources when the tests run, never copied into the
project: a Python test's string literals holding ``<robot`` (read with ``ast``), a C++
test's string literals (adjacent ones joined, as the compiler does; raw strings too)
assigned to a ``std::string``. The verdict is read from what the test does with the
robot it parses (see ``_python_verdict`` and ``_cpp_verdict``).
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from pathlib import Path

from conftest import REPO

SUITES = REPO.parent / "shared" / "upstream-suites"
CORPORA = ("urdfdom", "sdformat", "urdf_parser_py", "yourdfpy")

PASSES, FAILS = "passes", "fails"


@dataclass(frozen=True)
class Case:
    """One URDF of an upstream suite: ``ident`` is ``CORPUS/PATH`` for a file, with
    ``::TEST`` (``::CLASS::TEST`` in Python) for a string a test embeds."""

    ident: str
    corpus: str
    text: bytes
    verdict: str | None  # PASSES, FAILS, or None where no upstream test says
    path: Path | None = None  # the upstream file itself (None for an embedded string)

    @property
    def file_name(self) -> str:
        """A name for the string's file: the test's, so that messages say whose it is."""
        return self.path.name if self.path else self.ident.rsplit("::", 1)[1] + ".urdf"


def cases() -> list[Case]:
    """Every case of the four corpora, in a stable order; [] without the suites."""
    found: list[Case] = []
    for corpus in CORPORA:
        folder = SUITES / corpus
        if folder.is_dir():
            found += _files(corpus, folder) + _embedded(corpus, folder)
    return found


# --- files ----------------------------------------------------------------------------

def _files(corpus: str, folder: Path) -> list[Case]:
    verdicts = _file_verdicts(corpus, folder)
    return [Case(f"{corpus}/{path.relative_to(folder)}", corpus, path.read_bytes(),
                 verdicts.get(path), path)
            for path in sorted(folder.rglob("*.urdf"))]


def _file_verdicts(corpus: str, folder: Path) -> dict[Path, str]:
    """What upstream's tests expect of its files, from the tests where they are here."""
    if corpus == "urdfdom":
        # test_robot_model_parser.launch names the files the parser test reads;
        # test_robot_model_parser.cpp expects the ones named fail_* to fail.
        test = folder / "urdf" / "test"
        launch = (test / "test_robot_model_parser.launch").read_text()
        # args: the package folder (argv[1]), then the files, in the folder's test/
        args = re.search(r'type="test_parser" args="([^"]*)"', launch).group(1).split()[1:]
        return {test / name: FAILS if name.startswith("fail_") else PASSES for name in args}
    if corpus == "sdformat":
        # sdformat's URDF-import tests (test/integration/*.cc at SOURCES.md's commit,
        # not in the folder) load every one of these URDFs; their urdfdom parse succeeds.
        return {path: PASSES for path in (folder / "test" / "integration").rglob("*.urdf")}
    if corpus == "yourdfpy":
        # test_mimic_joint and test_equality load franka.urdf (URDF.load raises on a
        # file it cannot parse).
        return {path: PASSES for path in (folder / "tests" / "models").rglob("*.urdf")}
    return {}


# --- strings in test sources -----------------------------------------------------------

def _embedded(corpus: str, folder: Path) -> list[Case]:
    found = []
    for source in sorted(folder.rglob("*.py")):
        found += _python_strings(corpus, folder, source)
    for source in sorted(folder.rglob("*.cpp")) + sorted(folder.rglob("*.cc")):
        found += _cpp_strings(corpus, folder, source)
    return found


def _python_strings(corpus: str, folder: Path, source: Path) -> list[Case]:
    tree = ast.parse(source.read_bytes(), filename=str(source))
    found = []
    for owner, test in _test_functions(tree):
        for node in ast.walk(test):
            if isinstance(node, ast.Constant) and _holds_robot(node.value):
                name = f"{owner}::{test.name}" if owner else test.name
                found.append(Case(f"{corpus}/{source.relative_to(folder)}::{name}", corpus,
                                  _as_bytes(node.value), _python_verdict(test)))
    for cls in (n for n in tree.body if isinstance(n, ast.ClassDef)):
        # a class attribute its tests parse (self.xml)
        for statement in cls.body:
            if isinstance(statement, ast.Assign) and isinstance(statement.value, ast.Constant) \
                    and _holds_robot(statement.value.value):
                [target] = statement.targets
                users = [f for f in cls.body if isinstance(f, ast.FunctionDef)
                         and f.name.startswith("test")
                         and f"self.{target.id}" in ast.unparse(f)]
                verdict = _agreed({_python_verdict(f) for f in users})
                found.append(Case(f"{corpus}/{source.relative_to(folder)}::{cls.name}::"
                                  f"{target.id}", corpus, _as_bytes(statement.value.value),
                                  verdict))
    return found


def _test_functions(tree: ast.Module):
    """(class name or None, function) for every test function."""
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
            yield None, node
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and item.name.startswith("test"):
                    yield node.name, item


def _holds_robot(value) -> bool:
    return isinstance(value, (str, bytes)) and b"<robot" in _as_bytes(value)


def _as_bytes(value) -> bytes:
    return value if isinstance(value, bytes) else value.encode("utf-8")


# What a Python test does with the string it parses: expects an exception (assertRaises,
# assertParseErrorPath: a parse error), or goes on with the robot it got.
_FAILS_CALLS = ("assertRaises", "assertParseErrorPath")
_PASSES_CALLS = ("parse_and_compare", "parse", "from_xml_string", "load")


def _python_verdict(test: ast.FunctionDef) -> str | None:
    called = {_call_name(node.func) for node in ast.walk(test) if isinstance(node, ast.Call)}
    if called & set(_FAILS_CALLS):
        return FAILS
    if called & set(_PASSES_CALLS):
        return PASSES
    return None


def _call_name(func: ast.expr) -> str:
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def _agreed(verdicts: set) -> str | None:
    return verdicts.pop() if len(verdicts) == 1 else None


# C++: TEST(SUITE, NAME) { ... std::string VAR = "..." "..." ; ... }
_CPP_TEST = re.compile(r"^TEST(?:_F)?\((\w+),\s*(\w+)\)\s*\{(.*?)^\}", re.M | re.S)
_CPP_STRING_VAR = re.compile(r"std::string\s+(\w+)\s*=\s*((?:\s*(?:R\"\((?:.|\n)*?\)\"|"
                             r"\"(?:[^\"\\\n]|\\.)*\"))+)\s*;")
_CPP_LITERAL = re.compile(r"R\"\(((?:.|\n)*?)\)\"|\"((?:[^\"\\\n]|\\.)*)\"")
_CPP_ESCAPES = {"n": "\n", "t": "\t", "\\": "\\", '"': '"', "'": "'", "r": "\r", "0": "\0"}


def _cpp_strings(corpus: str, folder: Path, source: Path) -> list[Case]:
    text = _without_cpp_comments(source.read_text(encoding="utf-8"))
    found = []
    for _suite, name, body in _CPP_TEST.findall(text):
        for variable, literals in _CPP_STRING_VAR.findall(body):
            # each literal is raw or quoted: the other group is empty
            value = "".join(raw + _cpp_unescape(quoted)
                            for raw, quoted in _CPP_LITERAL.findall(literals))
            if "<robot" in value:
                found.append(Case(f"{corpus}/{source.relative_to(folder)}::{name}", corpus,
                                  value.encode("utf-8"), _cpp_verdict(body, variable)))
    return found


def _without_cpp_comments(text: str) -> str:
    """The source without // and /* */ comments (string literals kept as they are)."""
    return re.sub(r"(\"(?:[^\"\\\n]|\\.)*\")|//[^\n]*|/\*.*?\*/",
                  lambda m: m.group(1) or "", text, flags=re.S)


def _cpp_unescape(quoted: str) -> str:
    return re.sub(r"\\(.)", lambda m: _CPP_ESCAPES.get(m.group(1), m.group(0)), quoted)


def _cpp_verdict(body: str, variable: str) -> str | None:
    """urdfdom's tests parse with ``parseURDF(VAR)`` into a pointer, then either compare
    it with nullptr (EXPECT_EQ: must fail; EXPECT_NE: must parse) or use it (``->``)."""
    parsed = re.search(rf"(\w+)\s*=\s*urdf::parseURDF\(\s*{variable}\s*\)", body)
    if parsed is None:
        return None
    pointer = parsed.group(1)
    if re.search(rf"EXPECT_EQ\(\s*{pointer}\s*,\s*nullptr\s*\)", body):
        return FAILS
    if re.search(rf"EXPECT_NE\(\s*{pointer}\s*,\s*nullptr\s*\)|\b{pointer}->", body):
        return PASSES
    return None
