"""Data-driven `mcar build` error cases: one file per case under tests/build_errors/.

Each case declares `expect-exit: N` and `expect-stderr: REGEX` lines in its leading
comments; the test runs the installed mcar in that folder and checks both.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

CASES_DIR = Path(__file__).parents[1] / "build_errors"
CASES = sorted(CASES_DIR.glob("*.xacro"))


def expectations(case: Path) -> tuple[int, list[str]]:
    text = case.read_text()
    exits = re.findall(r"expect-exit:\s*(\d+)", text)
    patterns = re.findall(r"expect-stderr:\s*(.+?)\s*-->", text)
    assert len(exits) == 1 and patterns, f"{case.name} declares no expectation"
    return int(exits[0]), patterns


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_build_error_case(case, run_mcar):
    exit_code, patterns = expectations(case)
    result = run_mcar("build", case.name, cwd=CASES_DIR)
    assert result.returncode == exit_code, result.stderr
    assert result.stdout == "", "a failed build must print no URDF"
    assert "Traceback" not in result.stderr
    for pattern in patterns:
        assert re.search(pattern, result.stderr, re.M), (pattern, result.stderr)


def test_cases_exist():
    assert len(CASES) >= 8
