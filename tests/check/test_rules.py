"""The rule table: documented in docs/rules.md as it is in the code, and every rule tested."""

from __future__ import annotations

import re
from pathlib import Path

from mobile_car.check.rules import RETIRED, RULES, markdown_table

TESTS = Path(__file__).resolve().parents[1]
RULES_PAGE = TESTS.parent / "docs" / "rules.md"


def test_documented_rule_table_is_the_code_table():
    assert markdown_table() in RULES_PAGE.read_text(encoding="utf-8")


def test_every_rule_has_a_test_that_expects_it():
    expected = set()
    for case in (TESTS / "check_corpus" / "broken").glob("*.urdf"):
        expected |= set(re.findall(r"<!-- expect: ([EW]\d{3}) ", case.read_text()))
    # What Gazebo changes: tests/gazebo/cases/, checked with --gazebo.
    for case in (TESTS / "gazebo" / "cases").glob("*.urdf"):
        expected |= set(re.findall(r"<!-- expect: ([EWN]\d{3}) ", case.read_text()))
    # The two rules about building xacro inputs are tested in test_check_cli.py, and so
    # is xacro left in a URDF read from stdin (a file that uses xacro is expanded).
    cli_tests = (TESTS / "check" / "test_check_cli.py").read_text()
    expected |= {rule for rule in ("E140", "W220", "E105") if f"[{rule}]" in cli_tests}
    # An <include> is refused before libsdformat runs, so it has no Gazebo case: it is
    # attacked in tests/untrusted/test_gazebo_includes.py.
    includes = (TESTS / "untrusted" / "test_gazebo_includes.py").read_text()
    expected |= {"E152"} if "[E152]" in includes else set()
    # What mcar specs finds (W5xx, E5xx): its tests in tests/specs/ expect them by id.
    for case in (TESTS / "specs").glob("test_*.py"):
        expected |= set(re.findall(r"\[([EW]5\d\d)\]", case.read_text()))
    # The package's own ROS YAML against the robot: tests/check/test_stack_rules.py.
    stack = (TESTS / "check" / "test_stack_rules.py").read_text()
    expected |= {rule for rule in RULES if rule.startswith(("W51", "N405"))
                 and f"[{rule}]" in stack}
    assert expected == set(RULES)


def test_ids_are_stable_in_form_and_severity():
    for rule_id, rule in RULES.items():
        assert re.fullmatch(r"E1\d\d|W2\d\d|N4\d\d|[EW]5\d\d", rule_id)
        assert rule.severity == {"E": "error", "W": "warning", "N": "note"}[rule_id[0]]
        assert re.fullmatch(r"[a-z0-9-]+", rule.name)
    assert len({rule.name for rule in RULES.values()}) == len(RULES)


def test_a_retired_id_is_never_reused_and_names_its_successor():
    assert not set(RETIRED) & set(RULES)
    for old, new in RETIRED.items():
        assert new in RULES and f"was {old}" in RULES[new].summary
        assert f"**{old}**" in RULES_PAGE.read_text(encoding="utf-8")
