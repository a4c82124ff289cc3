"""Every diagnostic points at the file and line where its element was written, through
macros and ${name} templates, and names the calls that expanded it: problems at four
calls of one macro are four diagnostics (issue 26).

The package tests/check_xacro/wheel_macros/ is shaped like Husky's description: a wheel
macro whose names are all ${prefix}_..., called twice from the robot file and twice more
through an axle macro; one call's radius is broken, one block argument has a stray
attribute, and the macro's <axis rpy> (as Husky ships it) warns once per wheel. A comment
``at: NAME`` ends each line a diagnostic or call is expected at: no line is written here.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "check_xacro" / "wheel_macros"
ROBOT = "urdf/robot.urdf.xacro"


def _at() -> dict[str, tuple[str, int]]:
    """Marker name -> (file relative to the package, line)."""
    found = {}
    for path in sorted((PACKAGE / "urdf").iterdir()):
        for number, text in enumerate(path.read_text().splitlines(), start=1):
            match = re.search(r"<!-- at: (.+?) -->", text)
            if match:
                found[match.group(1)] = (f"urdf/{path.name}", number)
    return found


def _line_of(file: str, pattern: str) -> int:
    lines = (PACKAGE / file).read_text().splitlines()
    (number,) = [i for i, text in enumerate(lines, start=1) if pattern in text]
    return number


@pytest.fixture(scope="module")
def checked():
    """(exit code, text diagnostics, JSON document) of `mcar check` on the robot file,
    run in the package folder so that paths show as urdf/..."""
    import os

    from click.testing import CliRunner
    from mobile_car.cli.main import main

    here = os.getcwd()
    os.chdir(PACKAGE)
    try:
        runner = CliRunner()
        text = runner.invoke(main, ["check", ROBOT], catch_exceptions=False)
        document = runner.invoke(main, ["check", ROBOT, "--format", "json"],
                                 catch_exceptions=False)
        github = runner.invoke(main, ["check", ROBOT, "--format", "github"],
                               catch_exceptions=False)
    finally:
        os.chdir(here)
    diagnostics = [line for line in text.stderr.splitlines() if re.search(r"\[[EW]\d{3}\]$", line)]
    return text.exit_code, diagnostics, json.loads(document.stdout)["files"][0], github.stdout


def _called(*markers: str) -> str:
    at = _at()
    return " (" + ", ".join(f"in xacro:{macro} called at {at[name][0]}:{at[name][1]}"
                            for macro, name in (m.split("@") for m in markers)) + ")"


def test_each_problem_is_at_its_element_with_the_calls_that_made_it(checked):
    code, diagnostics, _, _ = checked
    at = _at()
    cylinder, axis, origin = at["cylinder"], at["axis"], at["front_left origin"]
    rpy = "warning: <axis> has unknown attribute 'rpy'"
    assert code == 1
    assert sorted(diagnostics) == sorted([
        f"{cylinder[0]}:{cylinder[1]}: error: link 'front_right_wheel_link' <visual>: "
        f"<cylinder radius=\"-0.1651\"> must be > 0{_called('wheel@front_right')} [E113]",
        # one warning per call, four calls of the same line: four diagnostics
        f"{axis[0]}:{axis[1]}: {rpy}{_called('wheel@front_left')} [W202]",
        f"{axis[0]}:{axis[1]}: {rpy}{_called('wheel@front_right')} [W202]",
        f"{axis[0]}:{axis[1]}: {rpy}{_called('wheel@left of axle', 'axle@rear axle')} [W202]",
        f"{axis[0]}:{axis[1]}: {rpy}{_called('wheel@right of axle', 'axle@rear axle')} [W202]",
        # a block argument is written at the call, and expanded nowhere else
        f"{origin[0]}:{origin[1]}: warning: <origin> has unknown attribute 'scale' [W202]",
    ])


def test_links_and_joints_named_by_a_template_are_at_their_tags(checked):
    _, _, document, _ = checked
    link = _line_of("urdf/wheel.urdf.xacro", '<link name="${prefix}_wheel_link">')
    joint = _line_of("urdf/wheel.urdf.xacro", '<joint name="${prefix}_wheel"')
    wheels = {"front_left", "front_right", "rear_left", "rear_right"}
    assert {(entry["name"], entry["file"], entry["line"]) for entry in document["links"]
            if entry["name"].endswith("_wheel_link")} == \
        {(f"{w}_wheel_link", "urdf/wheel.urdf.xacro", link) for w in wheels}
    assert {(entry["name"], entry["file"], entry["line"]) for entry in document["joints"]
            if entry["name"].endswith("_wheel")} == \
        {(f"{w}_wheel", "urdf/wheel.urdf.xacro", joint) for w in wheels}
    base = _line_of(ROBOT, '<link name="base_link">')
    assert ("base_link", ROBOT, base) in {(e["name"], e["file"], e["line"])
                                         for e in document["links"]}


def test_github_annotations_are_four_not_one(checked):
    _, _, _, github = checked
    axis = _at()["axis"]
    annotations = [line for line in github.splitlines()
                   if line.startswith(f"::warning file={axis[0]},line={axis[1]},")]
    assert len(annotations) == 4
    assert len(set(annotations)) == 4


def test_an_included_file_and_a_urdf_that_uses_xacro_are_located_in_themselves(tmp_path,
                                                                              cli):
    """Elements of an included file are at their own lines there; a robot expanded from
    a .urdf that uses xacro is located in that .urdf (TurtleBot3's case)."""
    (tmp_path / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="part">\n'
        '    <visual><geometry><sphere radius="-1"/></geometry></visual>\n'
        '  </link>\n</robot>\n')
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="parts.xacro"/>\n'
        '  <link name="${\'base\'}">\n'
        '    <visual><geometry><box size="1 1 -1"/></geometry></visual>\n'
        '  </link>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="part"/></joint>\n'
        '</robot>\n')
    result = cli("check", "--format", "json", tmp_path / "robot.urdf")
    found = {(Path(d["file"]).name, d["line"], d["rule"])
             for d in json.loads(result.stdout)["files"][0]["diagnostics"]}
    assert found == {("parts.xacro", 3, "E113"), ("robot.urdf", 4, "E113")}


@pytest.mark.parametrize("index, folder", [(0, PACKAGE), (1, PACKAGE.parents[1] / "build_errors")])
def test_the_transcripts_of_docs_locations_are_what_mcar_prints(index, folder, run_mcar):
    text = (PACKAGE.parents[2] / "docs" / "locations.md").read_text()
    blocks = [body for body in re.findall(r"```\n(.*?)```", text, re.S)
              if body.startswith("$ ")]
    command, *shown = blocks[index].splitlines()
    result = run_mcar(*command.removeprefix("$ mcar ").split(), cwd=folder)
    assert result.returncode == 1
    assert result.stderr.splitlines() == shown


@pytest.mark.parametrize("value", ["s99999999", "w0", "s²", "garbage", ""])
def test_a_xacro_that_writes_the_mark_itself_moves_a_line_at_most(tmp_path, run_mcar, value):
    """The mark is an attribute, and xacro:attribute can write any attribute: whatever a
    file writes there, the build succeeds, the URDF holds no mark, and nothing crashes."""
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="a">\n'
        f'    <xacro:attribute name="mcar_origin_" value="{value}"/>\n'
        '    <visual><geometry><box size="1 1 -1"/></geometry></visual>\n'
        '  </link>\n</robot>\n')
    built = run_mcar("build", "r.urdf.xacro", "-o", "r.urdf", cwd=tmp_path)
    assert built.returncode == 0, built.stderr
    assert "mcar_origin_" not in (tmp_path / "r.urdf").read_text()
    checked = run_mcar("check", "r.urdf.xacro", cwd=tmp_path)
    assert checked.returncode == 1
    assert re.search(r"^r\.urdf\.xacro:4: error: .*<box size=\"1 1 -1\">", checked.stderr, re.M)
