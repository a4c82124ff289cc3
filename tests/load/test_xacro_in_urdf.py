"""A file named .urdf that uses xacro is expanded like a .xacro by every command, with a
note saying so (issue 26): TurtleBot3's released ROS 2 files check, tree and sim as they
are. What counts as a use is held to the cases in tests/load/xacro_use/."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from sim.test_sim_real_robots import real_robots

from mobile_car.load.xacro_use import note_text, xacro_use

CASES = Path(__file__).resolve().parent / "xacro_use"
SAVED_AS_URDF = Path(__file__).resolve().parent / "xacro_saved_as_urdf.urdf"
FOLDER = real_robots()
needs_folder = pytest.mark.skipif(FOLDER is None, reason="the shared real-robots folder is "
                                  "absent (set MCAR_REAL_ROBOTS)")


def _expected() -> list[tuple[str, str | None]]:
    rows = []
    for text in (CASES / "expected.txt").read_text().splitlines():
        if text.strip() and not text.startswith("#"):
            name, use = (cell.strip() for cell in text.split("|"))
            rows.append((name, None if use == "-" else use))
    return rows


def test_every_case_file_is_in_the_table():
    files = {p.name for p in CASES.glob("*.urdf")}
    assert files == {name for name, _ in _expected()}


@pytest.mark.parametrize(("name", "use"), _expected())
def test_what_counts_as_using_xacro(name, use):
    assert xacro_use((CASES / name).read_bytes()) == use


def _invoke(*args):
    from mobile_car.cli.main import main

    runner = CliRunner()
    return runner.invoke(main, [str(a) for a in args], catch_exceptions=False,
                         terminal_width=200)


def _note(label: str, use: str) -> str:
    return f"mcar: {label}: {note_text(use)}"


def test_check_expands_it_with_one_note(tmp_path, run_mcar):
    robot = tmp_path / "robot.urdf"
    robot.write_bytes(SAVED_AS_URDF.read_bytes())
    result = run_mcar("check", "robot.urdf", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stderr.splitlines().count(_note("robot.urdf", "<xacro:property>")) == 1
    assert "Successfully Parsed XML" in result.stdout


def test_its_arguments_are_taken_and_unknown_ones_refused(tmp_path, run_mcar):
    robot = tmp_path / "robot.urdf"
    robot.write_bytes((CASES / "arg.urdf").read_bytes())
    taken = run_mcar("tree", "robot.urdf", "namespace:=tb3_", cwd=tmp_path)
    assert taken.returncode == 0, taken.stderr
    assert taken.stdout.splitlines()[0] == "tb3_base"
    refused = run_mcar("check", "robot.urdf", "nmespace:=tb3_", cwd=tmp_path)
    assert refused.returncode == 2
    assert "unknown xacro argument 'nmespace' (did you mean 'namespace'?)" in refused.stderr


def test_a_plain_urdf_is_read_as_it_is_and_refuses_arguments(tmp_path, run_mcar):
    robot = tmp_path / "robot.urdf"
    robot.write_bytes((CASES / "dollar_in_comment.urdf").read_bytes())
    result = run_mcar("check", "robot.urdf", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "uses xacro" not in result.stderr
    refused = run_mcar("check", "robot.urdf", "a:=b", cwd=tmp_path)
    assert refused.returncode == 2
    assert "NAME:=VALUE, --set and --config apply to .xacro inputs" in refused.stderr


def test_a_nameless_fragment_that_uses_xacro_is_a_macro_file(tmp_path, run_mcar):
    fragment = tmp_path / "extras.urdf"
    fragment.write_bytes((CASES / "undeclared_prefix.urdf").read_bytes())
    result = run_mcar("check", "extras.urdf", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines()[0] == (
        "mcar: error: extras.urdf is a macro file: include it from a robot file, or build "
        "its test file")


@needs_folder
@pytest.mark.parametrize("robot", ["burger", "waffle", "waffle_pi"])
def test_turtlebot3_urdf_checks_and_draws_its_tree_as_it_is(robot):
    source = FOLDER / "turtlebot3_description" / "urdf" / f"turtlebot3_{robot}.urdf"
    label = str(source)
    checked = _invoke("check", source, "--format", "json")
    (entry,) = json.loads(checked.stdout)["files"]
    assert entry["errors"] == 0, checked.stderr
    assert entry["root"] == "base_footprint"
    assert {"wheel_left_link", "wheel_right_link"} <= {link["name"] for link in entry["links"]}
    # every link is located in the .urdf itself, at its own tag
    lines = source.read_text().splitlines()
    for link in entry["links"]:
        assert link["file"] == label
        assert f'<link name="${{namespace}}{link["name"]}"' in lines[link["line"] - 1]
    assert _note(label, "<xacro:arg>") in checked.stderr.splitlines()
    tree = _invoke("tree", source, "namespace:=tb3_")
    assert tree.exit_code == 0, tree.stderr
    assert tree.stdout.splitlines()[0] == "tb3_base_footprint"


@needs_folder
@pytest.mark.parametrize("robot", ["burger", "waffle", "waffle_pi"])
def test_turtlebot3_urdf_simulates_as_it_is(robot):
    source = FOLDER / "turtlebot3_description" / "urdf" / f"turtlebot3_{robot}.urdf"
    result = _invoke("sim", source)
    assert result.exit_code == 0, result.stdout + result.stderr
    assert "mcar sim: 3 passed, 0 failed, 0 skipped in 1 file" in result.stderr
    assert _note(str(source), "<xacro:arg>") in result.stderr.splitlines()
