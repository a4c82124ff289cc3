"""The check corpus against the real check_urdf (urdfdom 3.0, Debian liburdfdom-tools).

``check_corpus/valid/``: robots of many shapes (and generators for the big ones, run at
test time). For each, ``mcar check`` prints byte for byte what check_urdf prints, both
exit 0, and mcar reports nothing: on stderr, only the robot's size in its rest pose (when
it has a shape).

``check_corpus/broken/``: one problem per file, declared in leading comments:
``<!-- expect: E104 line=7 -->`` (one per diagnostic; together they are all mcar may
report) and ``<!-- check_urdf: accepts|rejects|hangs -->``. mcar must report exactly the
expected rule ids at the expected lines, exit 1 when one is an error (else 0, and 1 with
--strict), and reject every file check_urdf rejects. The declared check_urdf verdict is
itself checked against the tool; a file it hangs on is run with a short timeout.
"""

from __future__ import annotations

import json
import re
import runpy
import subprocess
from pathlib import Path

import pytest
from conftest import mcar_process

CORPUS = Path(__file__).resolve().parents[1] / "check_corpus"
VALID = sorted((CORPUS / "valid").glob("*.urdf")) + \
    sorted((CORPUS / "valid").glob("generated_*.py"))
BROKEN = sorted((CORPUS / "broken").glob("*.urdf"))
EXPECT_RE = re.compile(r"<!-- expect: ([EW]\d{3}) line=(\d+) -->")
VERDICT_RE = re.compile(r"<!-- check_urdf: (accepts|rejects|hangs) -->")
# check_urdf answers a corpus file in milliseconds; on a cycle it loops, burning a CPU for
# as long as it is let.
HANG_SECONDS = 1


def _robot_file(case: Path, tmp_path: Path) -> Path:
    """The case itself, or the URDF its generator writes."""
    if case.suffix != ".py":
        return case
    target = tmp_path / f"{case.stem}.urdf"
    target.write_text(runpy.run_path(str(case))["urdf"](), encoding="utf-8")
    return target


@pytest.mark.parametrize("case", VALID, ids=lambda p: p.name)
def test_valid_robot_prints_what_check_urdf_prints(case, tmp_path, check_urdf, mcar_bin):
    path = _robot_file(case, tmp_path)
    theirs = subprocess.run([check_urdf, str(path)], capture_output=True, timeout=60)
    ours = mcar_process("check", path, timeout=60, text=False)
    assert theirs.returncode == 0, theirs.stderr.decode(errors="replace")
    assert re.fullmatch(r"(size: [0-9.]+ x [0-9.]+ x [0-9.]+ m\n)?", ours.stderr.decode())
    assert ours.returncode == 0
    assert ours.stdout == theirs.stdout
    assert ours.stdout.startswith(b"robot name is: ")


def _declared(case: Path) -> tuple[set[tuple[str, int]], str]:
    text = case.read_text(encoding="utf-8")
    expected = {(rule, int(line)) for rule, line in EXPECT_RE.findall(text)}
    verdict = VERDICT_RE.search(text)
    assert expected and verdict, f"{case.name}: declare expect: and check_urdf: comments"
    return expected, verdict.group(1)


def _check_urdf_verdict(check_urdf: str, path: Path) -> str:
    try:
        done = subprocess.run([check_urdf, str(path)], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=HANG_SECONDS)
    except subprocess.TimeoutExpired:
        return "hangs"
    return "accepts" if done.returncode == 0 else "rejects"


@pytest.mark.parametrize("case", BROKEN, ids=lambda p: p.name)
def test_broken_robot_is_reported_where_it_is_broken(case, cli):
    expected, _ = _declared(case)
    result = cli("check", "--format", "json", case)
    document = json.loads(result.stdout)
    [file] = document["files"]
    found = {(d["rule"], d["line"]) for d in file["diagnostics"]}
    assert found == expected
    assert {Path(d["file"]).resolve() for d in file["diagnostics"]} == {case}
    has_error = any(rule.startswith("E") for rule, _ in expected)
    assert result.exit_code == (1 if has_error else 0)
    assert cli("check", "--strict", "-q", case).exit_code == 1


@pytest.mark.parametrize("case", BROKEN, ids=lambda p: p.name)
def test_broken_robot_rejected_when_check_urdf_rejects_it(case, cli, check_urdf):
    _, declared = _declared(case)
    assert _check_urdf_verdict(check_urdf, case) == declared
    result = cli("check", case)
    if declared != "accepts":
        assert result.exit_code == 1
        assert re.search(rf"^\S*{re.escape(case.name)}:\d+: error: .+ \[E1\d\d\]$",
                         result.stderr, re.M), result.stderr
        assert result.stdout == ""  # no "Successfully Parsed" for a file with errors
