"""urdfdom's, sdformat's, urdf_parser_py's and yourdfpy's URDFs (their test files and the
URDF strings their tests embed, read in place from ``../shared/upstream-suites/``:
tests/upstream/urdf_corpora.py) through ``mcar check``, against check_urdf and against
the verdict each upstream test expects.

Where both accept, mcar prints check_urdf's tree byte for byte. Every difference, from
check_urdf's exit code or from upstream's verdict, is listed in
urdf_expected_differences.txt with the rules that make it (docs/rules.md shows the same
list): the test derives what mcar must do from the rules' severities as mcar reports
them, so a rule turned into a warning keeps its line true, and a line that no longer
describes what mcar does fails here.
"""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import pytest
from conftest import REPO
from upstream.urdf_corpora import CORPORA, FAILS, PASSES, SUITES, cases

from mobile_car.check.rules import RULES

CASES = cases()
DIFFERENCES_FILE = Path(__file__).resolve().parent / "urdf_expected_differences.txt"
# check_urdf answers each case in milliseconds; on a joint cycle it prints forever.
HANG_SECONDS = 5

if not CASES:
    pytest.skip(f"the upstream URDF suites are not at {SUITES} (../shared/upstream-suites)",
                allow_module_level=True)


def expected_differences() -> dict[str, tuple[frozenset, str]]:
    """case id -> (the rules that make mcar differ there, why)."""
    found = {}
    for line in DIFFERENCES_FILE.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            case, rules, reason = line.split(" ", 2)
            assert case not in found, f"{DIFFERENCES_FILE.name}: {case} is listed twice"
            found[case] = (frozenset(rules.split(",")), reason)
    return found


DIFFERENCES = expected_differences()


def _check_urdf(check_urdf: str, path: Path) -> tuple[bool, bytes]:
    """check_urdf's verdict (a hang is a refusal) and what it printed on stdout."""
    try:
        done = subprocess.run([check_urdf, str(path)], capture_output=True,
                              timeout=HANG_SECONDS)
    except subprocess.TimeoutExpired:
        return False, b""
    return done.returncode == 0, done.stdout


def _word(passes: bool) -> str:
    return "accepts" if passes else "rejects"


@pytest.mark.parametrize("case", CASES, ids=lambda case: case.ident)
def test_mcar_check_agrees_with_check_urdf_and_upstream(case, cli, check_urdf, tmp_path):
    path = case.path
    if path is None:  # a string a test embeds: checked as a file named after the test
        path = tmp_path / case.file_name
        path.write_bytes(case.text)
    theirs_pass, theirs_tree = _check_urdf(check_urdf, path)
    text = cli("check", path)
    [document] = json.loads(cli("check", "--format", "json", path).stdout)["files"]
    ours_pass = text.exit_code == 0
    assert text.exit_code in (0, 1), text.output  # a verdict, never a usage or I/O error
    reported = {d["rule"] for d in document["diagnostics"]}
    errors = {d["rule"] for d in document["diagnostics"] if d["severity"] == "error"}
    upstream_pass = None if case.verdict is None else case.verdict == PASSES
    said = (f"mcar {_word(ours_pass)} {sorted(errors) or ''}, check_urdf "
            f"{_word(theirs_pass)}, upstream's test expects "
            f"{'nothing' if case.verdict is None else case.verdict}")

    # Every file check_urdf rejects, mcar rejects (docs/rules.md): never listed away.
    assert ours_pass <= theirs_pass, f"{case.ident}: {said}"
    if ours_pass and theirs_pass:
        assert text.stdout_bytes == theirs_tree  # check_urdf's tree, byte for byte

    listed = DIFFERENCES.get(case.ident)
    differs = ours_pass != theirs_pass or (upstream_pass is not None
                                            and ours_pass != upstream_pass)
    if differs:
        assert listed is not None, f"{case.ident}: {said}: fix mcar, or list the rule " \
                                   f"that makes the difference in {DIFFERENCES_FILE.name}"
    if listed is None:
        return
    rules, _ = listed
    assert rules <= reported, f"{case.ident}: listed for {sorted(rules - reported)}, " \
                              f"which mcar no longer reports ({said})"
    if theirs_pass and not ours_pass:
        # the refusal is all documented rules: a new error here is a new difference
        assert errors <= rules, f"{case.ident}: {sorted(errors - rules)} not listed ({said})"
    elif not ours_pass and upstream_pass:
        assert rules & errors, f"{case.ident}: none of the listed rules fails it ({said})"


def test_the_listed_differences_are_cases_and_rules():
    idents = {case.ident for case in CASES}
    assert set(DIFFERENCES) <= idents, sorted(set(DIFFERENCES) - idents)
    listed_rules = set().union(*(rules for rules, _ in DIFFERENCES.values()))
    assert listed_rules <= set(RULES), sorted(listed_rules - set(RULES))


def test_the_differences_are_the_ones_docs_rules_lists():
    """docs/rules.md shows the same list, so a change to one shows in the other."""
    page = (REPO / "docs" / "rules.md").read_text(encoding="utf-8")
    section = page.split("## Upstream's test files", 1)[1].split("\n## ", 1)[0]
    documented = {case: frozenset(rules.split(", "))
                  for case, rules in re.findall(r"^\| `([^`]+)` \| ([EWN\d, ]+) \|", section,
                                                re.M)}
    assert documented == {case: rules for case, (rules, _) in DIFFERENCES.items()}
    counts = ", ".join(f"{sum(1 for case in CASES if case.corpus == corpus)} of {corpus}"
                       for corpus in CORPORA)
    assert f"{len(CASES)} cases: {counts}." in " ".join(section.split())


def test_the_strings_are_read_from_the_test_sources():
    """The extraction itself: every kind of embedded string is found, with its verdict."""
    by_ident = {case.ident: case for case in CASES}
    # a C++ robot made of adjacent literals, escapes undone; its test compares with nullptr
    one_int = by_ident["urdfdom/urdf_parser/test/urdf_version_test.cpp::test_version_one_int"]
    assert one_int.text == b'<robot name="test" version="1">  <link name="l1"/></robot>'
    assert one_int.verdict == FAILS
    # a Python test that uses the robot it parsed; one that expects a parse error
    assert by_ident["urdf_parser_py/test/test_urdf.py::LinkOriginTestCase::"
                    "test_xml_with_UTF8_encoding"].verdict == PASSES
    assert by_ident["urdf_parser_py/test/test_urdf_error.py::TestURDFParserError::"
                    "test_bad_ducktype"].verdict == FAILS
    # urdfdom's files: fail_* must fail, as test_robot_model_parser.cpp says
    assert by_ident["urdfdom/urdf/test/fail_pr2_desc_loop.urdf"].verdict == FAILS
    assert by_ident["urdfdom/urdf/test/one_link.urdf"].verdict == PASSES
    assert {case.corpus for case in CASES} == set(CORPORA)
