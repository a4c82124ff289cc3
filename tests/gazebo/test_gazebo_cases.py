"""What Gazebo changes, one robot per file in tests/gazebo/cases/: each declares in leading
comments every diagnostic ``mcar check --gazebo`` must report (``<!-- expect: E150
line=24 -->``, and nothing else) and words that must be in them (``<!-- says: E150
...-->``). A new case is one new file; tests/check/test_rules.py counts their rules."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

CASES = sorted((Path(__file__).parent / "cases").glob("*.urdf"))
EXPECT_RE = re.compile(r"<!-- expect: ([EWN]\d{3}) line=(\d+) -->")
SAYS_RE = re.compile(r"<!-- says: ([EWN]\d{3}) (.*?) -->", re.S)


@pytest.mark.parametrize("case", CASES, ids=lambda p: p.stem)
def test_case_reports_what_gazebo_changes_where_it_is_written(case, cli, gazebo):
    text = case.read_text(encoding="utf-8")
    expected = {(rule, int(line)) for rule, line in EXPECT_RE.findall(text)}
    says = SAYS_RE.findall(text)
    assert expected and says, f"{case.name}: declare expect: and says: comments"
    result = cli("check", "--gazebo", "--format", "json", case)
    [file] = json.loads(result.stdout)["files"]
    found = {(d["rule"], d["line"]) for d in file["diagnostics"]}
    assert found == expected
    messages = [(d["rule"], d["message"]) for d in file["diagnostics"]]
    for rule, words in says:
        words = " ".join(words.split())
        assert any(r == rule and words in m for r, m in messages), (rule, words, messages)
    errors = any(rule.startswith("E") for rule, _ in expected)
    assert result.exit_code == (1 if errors else 0)
    assert re.fullmatch(r"\d+\.\d+\.\d+", file["gazebo"]["sdformat"])
