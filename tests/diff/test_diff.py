"""`mcar diff`: what a change does to the robot, asserted on what it prints and its exit code."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

SMALL = """<?xml version="1.0"?>
<robot name="small">
  <link name="base_link">
    <inertial>
      <origin xyz="0 0 0.05"/>
      <mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/>
    </inertial>
    <visual><geometry><box size="0.4 0.3 0.1"/></geometry></visual>
  </link>
  <link name="laser_link">
    <visual><geometry><cylinder radius="0.03" length="0.04"/></geometry></visual>
  </link>
  <joint name="laser_joint" type="fixed">
    <origin xyz="0.1 0 0.12" rpy="0 0 0"/>
    <parent link="base_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
"""

# The same robot, written otherwise: elements and attributes reordered, numbers spelled
# differently (0.5e-1, 2, .4, 0.000), the defaults written out.
SMALL_RESPELLED = """<robot name="small">
  <joint type="fixed" name="laser_joint">
    <child link="laser_link"/>
    <parent link="base_link"/>
    <origin rpy="0.000 -0 0e0" xyz="1e-1 0.0 0.120"/>
  </joint>
  <link name="laser_link">
    <visual><origin xyz="0 0 0"/><geometry><cylinder length="4e-2" radius=".03"/></geometry>
    </visual>
  </link>
  <link name="base_link">
    <visual><geometry><box size=".4 0.30 1e-1"/></geometry></visual>
    <inertial>
      <inertia izz="3e-2" iyz="0" iyy="0.020" ixz="0" ixy="-0" ixx=".01"/>
      <mass value="2"/>
      <origin xyz="0 0 0.5e-1"/>
    </inertial>
  </link>
</robot>
"""


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def diff_json(cli, *args) -> tuple[int, dict]:
    result = cli("diff", *map(str, args), "--format", "json")
    return result.exit_code, json.loads(result.stdout)


def changes_of(document: dict) -> dict:
    """(section, name, field) -> change, for the one robot compared."""
    (robot,) = document["robots"]
    return {(c["section"], c["name"], c["field"]): c for c in robot["changes"]}


def test_the_same_robot_written_otherwise_is_no_change(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL_RESPELLED)
    result = cli("diff", old, new)
    assert result.exit_code == 0, result.output
    assert result.stdout == f"{old} -> {new}: no change to the robot\n"
    code, document = diff_json(cli, old, new)
    assert code == 0 and document["changed"] is False
    assert document["robots"][0]["changes"] == []


def test_a_renamed_joint_is_one_rename_not_a_removal_and_an_addition(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL.replace('"laser_joint"', '"scanner_joint"'))
    code, document = diff_json(cli, old, new)
    assert code == 1
    robot = document["robots"][0]
    assert robot["renamed"] == [{"what": "joint", "old": "laser_joint", "new": "scanner_joint"}]
    assert robot["added"] == [] and robot["removed"] == [] and robot["changes"] == []
    text = cli("diff", old, new).stdout
    assert "renamed joint laser_joint -> scanner_joint (same content)" in text


def test_a_renamed_link_renames_its_joint_s_child_too(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL.replace('"laser_link"', '"lidar_link"'))
    code, document = diff_json(cli, old, new)
    robot = document["robots"][0]
    assert code == 1
    assert robot["renamed"] == [{"what": "link", "old": "laser_link", "new": "lidar_link"}]
    # The joint kept its name and, read through the rename, its content.
    assert robot["changes"] == [] and robot["added"] == [] and robot["removed"] == []


def test_a_moved_sensor_is_reported_in_mm_and_degrees(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    moved = SMALL.replace('xyz="0.1 0 0.12" rpy="0 0 0"',
                          'xyz="0.11 0 0.12" rpy="0 0 0.2617993877991494"')  # 15 degrees
    new = write(tmp_path, "new.urdf", moved)
    code, document = diff_json(cli, old, new)
    assert code == 1
    changes = changes_of(document)
    assert changes[("joint", "laser_joint", "origin xyz")]["delta"] == pytest.approx([0.01, 0, 0])
    assert changes[("joint", "laser_joint", "origin rpy")]["new"] == pytest.approx(
        [0, 0, 0.2617993877991494])
    assert changes[("frame", "laser_link", "position")]["unit"] == "m"
    assert ("frame", "base_link", "position") not in changes  # the root did not move
    text = cli("diff", old, new).stdout
    assert "origin xyz (mm)            100 0 120  ->  110 0 120   (+10 0 0; 10 mm)" in text
    assert "origin rpy (deg)           0 0 0  ->  0 0 15   (0 0 +15; turned 15 deg)" in text
    assert "rotation (deg)             0 0 0  ->  0 0 15   (0 0 +15; turned 15 deg)" in text


def test_a_change_within_the_tolerance_is_no_change(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL.replace('xyz="0.1 0 0.12"', 'xyz="0.1000001 0 0.12"'))
    assert cli("diff", old, new).exit_code == 1
    assert cli("diff", old, new, "--tolerance", "1e-6").exit_code == 0


def _set_wheel_radius(package: Path, value: str) -> None:
    config = package / "urdf" / "config.xacro"
    text = config.read_text(encoding="utf-8")
    old = '<xacro:property name="wheel_radius" value="0.0325"/>'
    assert old in text
    config.write_text(text.replace(old, f'<xacro:property name="wheel_radius" value="{value}"/>'),
                      encoding="utf-8")


def _check_wheel_radius_change(document: dict, old_radius: float, new_radius: float) -> None:
    rise = new_radius - old_radius
    changes = changes_of(document)
    for side in ("left", "right"):
        link = f"wheel_{side}_link"
        geometry = changes[("link", link, "visual radius, length")]
        assert geometry["old"][0] == pytest.approx(old_radius)
        assert geometry["new"][0] == pytest.approx(new_radius)
        assert geometry["new"][1] == pytest.approx(geometry["old"][1])  # same width
        # Each wheel's height above the ground (base_footprint) follows the radius.
        assert changes[("frame", link, "position")]["delta"] == pytest.approx([0, 0, rise])
    # base_footprint -> base_link is the axle height.
    assert changes[("joint", "base_joint", "origin xyz")]["delta"] == pytest.approx([0, 0, rise])
    totals = {t["field"]: t for t in document["robots"][0]["totals"]}
    assert totals["mass"]["changed"] is False
    assert totals["mass"]["old"] == totals["mass"]["new"]
    dimensions = {d["field"]: d for d in document["robots"][0]["dimensions"]}
    assert dimensions["wheel_radius"]["old"] == [pytest.approx(old_radius)]
    assert dimensions["wheel_radius"]["new"] == [pytest.approx(new_radius)]
    assert dimensions["axle_height"]["delta"] == [pytest.approx(rise)]
    assert "wheel_mass" not in dimensions


def test_a_change_of_wheel_radius(cli, package_copy, tmp_path):
    new_package = tmp_path / "new" / package_copy.name
    shutil.copytree(package_copy, new_package)
    _set_wheel_radius(new_package, "0.040")
    robot = Path("urdf") / "mobile_robot.xacro"
    code, document = diff_json(cli, package_copy / robot, new_package / robot)
    assert code == 1
    _check_wheel_radius_change(document, 0.0325, 0.040)
    text = cli("diff", package_copy / robot, new_package / robot).stdout
    assert "total mass unchanged" in text
    assert "  wheel_radius                 0.0325 m  ->  0.04 m   (+0.0075)" in text


def test_set_applies_to_both_sides(cli, package_copy):
    robot = package_copy / "urdf" / "mobile_robot.xacro"
    code, document = diff_json(cli, robot, robot, "--set", "wheel_radius=40mm")
    assert code == 0 and document["changed"] is False


def _git(repo: Path, *args: str) -> str:
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com")
    return subprocess.run(["git", *args], cwd=repo, env=env, check=True, capture_output=True,
                          text=True).stdout


def commit_the_car(package: Path) -> None:
    """Make the package a git repository whose one commit is the bundled car."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    _git(package, "init", "-q")
    _git(package, "add", ".")
    _git(package, "commit", "-qm", "the car")


@pytest.fixture
def two_commits(package_copy) -> Path:
    """A git clone of the package: the bundled car, then a commit that enlarges the wheels."""
    commit_the_car(package_copy)
    _set_wheel_radius(package_copy, "0.045")
    _git(package_copy, "commit", "-qam", "bigger wheels")
    return package_copy


def test_diff_against_the_previous_commit(run_mcar, two_commits):
    before = _git(two_commits, "status", "--porcelain", "--ignored")
    result = run_mcar("diff", "HEAD~1", "urdf/mobile_robot.xacro", "--format", "json",
                      cwd=two_commits)
    assert result.returncode == 1, result.stderr
    document = json.loads(result.stdout)
    (robot,) = document["robots"]
    assert robot["old"]["file"] == "urdf/mobile_robot.xacro@HEAD~1"
    assert robot["new"]["file"] == "urdf/mobile_robot.xacro"
    _check_wheel_radius_change(document, 0.0325, 0.045)
    # Nothing in the working tree, index or HEAD was touched.
    assert _git(two_commits, "status", "--porcelain", "--ignored") == before
    assert _git(two_commits, "worktree", "list").count("\n") == 1


def test_diff_of_two_revisions_and_of_the_whole_package(run_mcar, two_commits):
    same = run_mcar("diff", "HEAD", "urdf/wheel", cwd=two_commits)
    assert same.returncode == 0, same.stderr
    assert same.stdout == ("urdf/wheel/test_wheel.urdf.xacro@HEAD -> "
                           "urdf/wheel/test_wheel.urdf.xacro: no change to the robot\n")
    both = run_mcar("diff", "HEAD~1", "HEAD", "wheel", "--format", "json", cwd=two_commits)
    assert both.returncode == 1, both.stderr
    (robot,) = json.loads(both.stdout)["robots"]
    assert robot["new"]["file"] == "urdf/wheel/test_wheel.urdf.xacro@HEAD"
    whole = run_mcar("diff", "HEAD~1", "--format", "json", cwd=two_commits)
    assert whole.returncode == 1, whole.stderr
    robots = {r["new"]["file"]: r for r in json.loads(whole.stdout)["robots"]}
    assert robots["urdf/mobile_robot.xacro"]["changes"] != []
    # The laser has no wheel: nothing of it moved. The config it reads changed, which the
    # JSON keeps, but the laser itself did not: no change to report for it.
    laser = robots["urdf/laser/test_laser.urdf.xacro"]
    assert laser["changes"] == [] and laser["changed"] is False
    assert "wheel_radius" in {d["field"] for d in laser["dimensions"]}
    text = run_mcar("diff", "HEAD~1", cwd=two_commits).stdout
    assert "urdf/laser/test_laser.urdf.xacro: no change to the robot\n" in text
    # config.xacro's changes are listed once, under the first robot they change
    assert text.count("Dimensions (config.xacro):\n") == 1
    assert text.count("Dimensions (config.xacro): the same changes as above") == \
        sum(1 for r in robots.values() if r["changed"]) - 1


@pytest.mark.parametrize("count, noun, shown", [(1, "link", "1 link"), (2, "link", "2 links"),
                                                (0, "frame", "0 frames")])
def test_counts_agree_with_their_nouns(count, noun, shown):
    from mobile_car.diff.report import counted

    assert counted(count, noun) == shown


def test_a_robot_file_added_since_the_revision(run_mcar, two_commits):
    shutil.copy(two_commits / "urdf" / "mobile_robot.xacro", two_commits / "urdf" / "copy.xacro")
    result = run_mcar("diff", "HEAD", "urdf/copy.xacro", cwd=two_commits)
    assert result.returncode == 1, result.stderr
    assert result.stdout == "robot file added: urdf/copy.xacro\n"


def test_the_markdown_renders_as_a_table(cli, tmp_path):
    from markdown_it import MarkdownIt

    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL.replace('xyz="0.1 0 0.12"', 'xyz="0.1 0 0.15"'))
    result = cli("diff", old, new, "--format", "markdown")
    assert result.exit_code == 1
    tokens = MarkdownIt("commonmark").enable("table").parse(result.stdout)
    assert tokens[0].type == "heading_open"
    cells = [t.content for t in tokens if t.type == "inline"]
    opened = [i for i, t in enumerate(tokens) if t.type == "table_open"]
    assert opened, result.stdout
    header = cells[cells.index("Name") - 1:cells.index("Name") + 5]
    assert header == ["", "Name", "What", "Old", "New", "Change"]
    row = cells.index("`laser_joint`")
    assert cells[row - 1:row + 5] == ["joint", "`laser_joint`", "origin xyz (mm)", "100 0 120",
                                      "100 0 150", "0 0 +30; 30 mm"]


@pytest.mark.parametrize(("args", "message"), [
    (["only.urdf"], "mcar: error: give OLD and NEW: two robot files, or a git revision "
                    "(mcar diff HEAD~1)"),
    (["missing.urdf", "new.urdf"], "missing.urdf: error: no such file"),
    (["broken.urdf", "new.urdf"],
     "broken.urdf:3: error: not well-formed XML: Opening and ending tag mismatch"),
])
def test_errors_exit_2_with_one_line(run_mcar, tmp_path, args, message):
    write(tmp_path, "only.urdf", SMALL)
    write(tmp_path, "new.urdf", SMALL)
    write(tmp_path, "broken.urdf", "<robot name='x'>\n<link name='a'>\n</robot>\n")
    result = run_mcar("diff", *args, cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    first = result.stderr.splitlines()[0]
    assert first.startswith(message), result.stderr
    assert "Traceback" not in result.stderr


def test_a_robot_file_on_neither_side_is_an_error(run_mcar, two_commits):
    result = run_mcar("diff", "HEAD~1", "urdf/nothere.xacro", cwd=two_commits)
    assert result.returncode == 2
    assert result.stderr == ("urdf/nothere.xacro: error: no such file at HEAD~1 nor at "
                             "working tree\n")


def test_a_size_change_is_said_per_axis_not_as_a_distance(cli, tmp_path):
    old = write(tmp_path, "old.urdf", SMALL)
    new = write(tmp_path, "new.urdf", SMALL.replace('<box size="0.4 0.3 0.1"/>',
                                                    '<box size="0.411 0.3 0.111"/>'))
    lines = [line.strip() for line in cli("diff", old, new).stdout.splitlines()]
    assert "visual size (mm)           400 300 100  ->  411 300 111   (+11 0 +11)" in lines
    assert "size (mm)                    400 300 190  ->  411 300 195.5   (+11 0 +5.5)" in lines
    # A corner of the bounding box is a position: its move is still a distance too.
    assert ("bounding box min (mm)        -200 -150 -50  ->  -205.5 -150 -55.5   "
            "(-5.5 0 -5.5; 7.7782 mm)") in lines
