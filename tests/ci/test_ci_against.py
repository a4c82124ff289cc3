"""`mcar ci --against REV`: the diff of each robot file in the JUnit report and a markdown
file, in a git repository the tests make (the car, then a commit with bigger wheels)."""

from __future__ import annotations

import json
import shutil
from xml.etree import ElementTree as ET

from diff.test_diff import _git, two_commits  # noqa: F401  (two_commits is a fixture)
from markdown_it import MarkdownIt


def _ci(run_mcar, folder, *args):
    return run_mcar("ci", "--no-render", "--no-sim", "--no-gazebo", "--junit-xml", "junit.xml",
                    *args, cwd=folder)


def _properties(folder) -> dict[str, set[str]]:
    """testcase name -> the mcar.diff values of its testcases."""
    found: dict[str, set[str]] = {}
    for case in ET.parse(folder / "junit.xml").getroot().iter("testcase"):
        values = {p.get("value") for p in case.iter("property") if p.get("name") == "mcar.diff"}
        found.setdefault(case.get("name"), set()).update(values)
    return found


def _expected_count(run_mcar, folder, revision: str, robot: str) -> int:
    """The number of changes `mcar diff` itself reports for one robot file."""
    result = run_mcar("diff", revision, robot, "--format", "json", cwd=folder)
    (diff,) = json.loads(result.stdout)["robots"]
    return (len(diff["added"]) + len(diff["removed"]) + len(diff["renamed"])
            + len(diff["changes"]) + sum(t["changed"] for t in diff["totals"])
            + len(diff["dimensions"] or ()))


def test_the_diff_is_a_junit_property_and_a_markdown_report(run_mcar, two_commits):  # noqa: F811
    result = _ci(run_mcar, two_commits, "--against", "HEAD~1", "--diff-report", "diff.md")
    assert result.returncode == 0, result.stderr  # bigger wheels are not a failure
    count = _expected_count(run_mcar, two_commits, "HEAD~1", "urdf/mobile_robot.xacro")
    assert count > 5
    properties = _properties(two_commits)
    assert properties["mobile_robot.xacro"] == {f"{count} changes"}
    assert properties["tutorial/01_skeleton.urdf"] == {"no change"}
    assert properties["mobile_robot.xacro @ small"] == set()  # variants are not compared
    commit = _git(two_commits, "rev-parse", "HEAD~1").strip()
    report = (two_commits / "diff.md").read_text(encoding="utf-8")
    assert report.startswith(f"## mcar diff against `HEAD~1` ({commit[:12]})\n")
    tokens = MarkdownIt("commonmark").enable("table").parse(report)
    headings = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open"]
    assert "`mobile_robot.xacro@HEAD~1` → `mobile_robot.xacro`" in headings
    cells = [t.content for t in tokens if t.type == "inline"]
    assert "`wheel_radius`" in cells and any(t.type == "table_open" for t in tokens)
    unchanged = report.split("No change: ", 1)[1].splitlines()[0]
    assert "`tutorial/01_skeleton.urdf`" in unchanged.split(", ")
    compared = [values for values in properties.values() if values]
    changed = sum(1 for values in compared if values != {"no change"})
    assert f"against HEAD~1: {changed} of {len(compared)} robot files changed" in result.stderr


def test_a_new_revision_is_never_answered_from_the_ci_record(run_mcar, two_commits):  # noqa: F811
    assert _ci(run_mcar, two_commits, "--against", "HEAD~1").returncode == 0
    built = two_commits / "build" / "mobile_robot.urdf"
    stamp = built.stat().st_mtime_ns
    result = _ci(run_mcar, two_commits, "--against", "HEAD", "--diff-report", "diff.md")
    assert result.returncode == 0, result.stderr
    assert built.stat().st_mtime_ns == stamp  # build and check were replayed...
    assert _properties(two_commits)["mobile_robot.xacro"] == {"no change"}  # ...not the diff
    report = (two_commits / "diff.md").read_text(encoding="utf-8")
    assert "**No robot changed.**" in report


def test_a_robot_file_added_since_the_revision(run_mcar, two_commits):  # noqa: F811
    shutil.copy(two_commits / "urdf" / "mobile_robot.xacro", two_commits / "urdf" / "copy.xacro")
    result = _ci(run_mcar, two_commits, "--against", "HEAD", "--diff-report", "diff.md")
    assert result.returncode == 0, result.stderr
    assert _properties(two_commits)["copy.xacro"] == {"added since HEAD"}
    assert "- `copy.xacro`: added since HEAD\n" in (two_commits / "diff.md").read_text("utf-8")


def test_bad_against_arguments_exit_2_before_building(run_mcar, two_commits, tmp_path):  # noqa: F811
    result = _ci(run_mcar, two_commits, "--against", "nosuch")
    assert result.returncode == 2
    assert result.stderr.startswith("mcar: error: --against nosuch: not a commit of the git "
                                    "repository "), result.stderr
    assert not (two_commits / "build").exists()
    result = _ci(run_mcar, two_commits, "--diff-report", "diff.md")
    assert (result.returncode, result.stderr) == (
        2, "mcar: error: --diff-report FILE needs --against REV (the revision to compare "
           "with)\n")
    result = _ci(run_mcar, two_commits, "--against", "HEAD", "--diff-report",
                 "urdf/config.xacro")
    assert result.returncode == 2 and "would overwrite" in result.stderr, result.stderr
    shutil.rmtree(two_commits / ".git")
    result = _ci(run_mcar, two_commits, "--against", "HEAD")
    assert result.returncode == 2
    assert result.stderr.endswith("is not in a git repository\n"), result.stderr
