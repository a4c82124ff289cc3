"""No INPUT picks the package's complete robot for single-robot commands (issue 30, item 5).

`mcar tree` said "one INPUT at a time, got 13" and `mcar sim --record x.gif` "13 robot
files: name one INPUT" in the bundled package, which has one complete robot
(urdf/mobile_robot.xacro) beside its parts' test files. Now tree, view and sim --record
(and export) take that robot, and say so on stderr; where a package has several complete robots,
they exit 2 listing each on its own line.
"""

from __future__ import annotations

import shutil

import pytest

CHOSEN = "mcar: urdf/mobile_robot.xacro, the one complete robot here (an INPUT names another)"


@pytest.fixture
def in_package(package_copy, monkeypatch):
    monkeypatch.chdir(package_copy)
    return package_copy


@pytest.fixture
def two_robots(in_package):
    shutil.copy(in_package / "urdf" / "mobile_robot.xacro",
                in_package / "urdf" / "second_robot.xacro")
    return in_package


def test_tree_without_input_is_the_complete_robot(cli, in_package):
    result = cli("tree")
    assert result.exit_code == 0, result.output
    assert result.stderr.splitlines()[-1] == CHOSEN
    assert "wheel_left_link" in result.stdout and "caster_link" in result.stdout


def test_a_named_folder_is_read_the_same_way(cli, in_package):
    result = cli("tree", "urdf")
    assert result.exit_code == 0, result.output
    assert CHOSEN in result.stderr.splitlines()


def test_a_part_name_with_one_robot_file_needs_no_note(cli, in_package):
    result = cli("tree", "wheel")
    assert result.exit_code == 0, result.output
    assert "complete robot" not in result.stderr


@pytest.mark.parametrize("words", [["tree"], ["view", "--no-browser"],
                                   ["sim", "--record", "run.gif"],
                                   ["export", "--to", "mjcf", "-o", "out"]],
                         ids=["tree", "view", "sim --record", "export"])
def test_several_complete_robots_are_listed_one_per_line(cli, two_robots, words):
    result = cli(*words)
    command = " ".join(words[:1] + (["--record"] if "--record" in words else []))
    assert result.exit_code == 2, result.output
    assert result.stderr.splitlines()[-3:] == [
        f"mcar: error: mcar {command} works on one robot, and there are 2 here: "
        "name one INPUT",
        "  urdf/mobile_robot.xacro",
        "  urdf/second_robot.xacro"]
    assert not (two_robots / "run.gif").exists() and not (two_robots / "out").exists()


def test_sim_record_without_input_records_the_complete_robot(cli, in_package):
    result = cli("sim", "--record", "run.gif", "--scenario", "drop")
    assert CHOSEN in result.stderr.splitlines(), result.output
    assert result.exit_code == 0, result.output
    assert (in_package / "run.gif").stat().st_size > 0
