"""`mcar check` states the robot's size in its rest pose (stderr in text, "extents" in JSON),
and its plausibility rules (W211-W214, one corpus case each in check_corpus/broken/) raise
nothing on the robots people ship: the bundled car, its tutorial files, part test files
and variants, and TurtleBot3, Husky and Jackal from the shared real-robots folder (each
TurtleBot3 under half a metre, as its real size; its castors' inertias are wrong, and
said so)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import REPO
from sim.test_sim_real_robots import FOLDER, needs_folder

PLAUSIBILITY = {"W211", "W212", "W213", "W214"}
TUTORIAL = REPO / "urdf" / "tutorial"


def _json(cli, *args) -> dict:
    result = cli("check", "--format", "json", *args)
    [document] = json.loads(result.stdout)["files"]
    return document


def test_the_size_is_said_on_stderr_and_in_json(cli):
    result = cli("check", TUTORIAL / "03_color.urdf")
    assert result.exit_code == 0
    assert result.stderr == "size: 0.25 x 0.30 x 0.15 m\n"  # stdout stays check_urdf's
    assert result.stdout.startswith("robot name is: test_robot\n")
    assert _json(cli, TUTORIAL / "03_color.urdf")["extents"] == pytest.approx([0.25, 0.3, 0.15])


def test_quiet_leaves_the_size_out_and_many_inputs_name_their_file(cli):
    assert cli("check", "-q", TUTORIAL / "03_color.urdf").stderr == ""
    result = cli("check", TUTORIAL / "01_skeleton.urdf", TUTORIAL / "02_visual.urdf")
    # the skeleton has no shape: no size; the other is named
    [line] = result.stderr.splitlines()
    assert line.endswith("tutorial/02_visual.urdf: size: 0.25 x 0.30 x 0.15 m")
    assert _json(cli, TUTORIAL / "01_skeleton.urdf")["extents"] is None


def test_a_robot_with_an_error_has_no_size_and_no_plausibility_said(cli, tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"><visual><geometry><box size="2e6 1 1"/>'
                     '</geometry></visual></link></robot>')
    document = _json(cli, robot)
    assert [d["rule"] for d in document["diagnostics"]] == ["E117"] and not document["extents"]


def test_the_size_counts_meshes_in_metres_and_link_poses(cli, tmp_path):
    """box_mm.dae (400 mm) on a link turned a quarter about z and lifted: 0.2 x 0.4 x 0.1."""
    meshes = REPO / "tests" / "load" / "meshes_as_rviz"
    robot = tmp_path / "r.urdf"
    robot.write_text(f'<robot name="r"><link name="a"/><link name="b"><visual><geometry>'
                     f'<mesh filename="{meshes / "box_mm.dae"}"/></geometry></visual></link>'
                     '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
                     '<origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/></joint></robot>')
    # the meshes lie outside the robot's folder: named with --asset-path (W215 otherwise)
    assert _json(cli, "--asset-path", meshes, robot)["extents"] == pytest.approx(
        [0.2, 0.4, 0.1], abs=1e-6)


BUNDLED = [*sorted((REPO / "urdf").rglob("test_*.urdf.xacro")),
           *sorted((REPO / "urdf" / "chassis" / "steps").glob("*.xacro")),
           *sorted(TUTORIAL.iterdir())]


@pytest.mark.parametrize("path", BUNDLED, ids=lambda p: p.name)
def test_the_bundled_car_s_files_raise_no_plausibility_warning(cli, path):
    document = _json(cli, path)
    assert document["diagnostics"] == [] and document["ok"]


@pytest.mark.parametrize("variant", [None, "small.yaml", "large.yaml"])
def test_the_car_and_its_variants_raise_none_and_are_car_sized(cli, variant):
    args = ["--config", REPO / "urdf" / "variants" / variant] if variant else []
    document = _json(cli, REPO / "urdf" / "mobile_robot.xacro", *args)
    assert document["diagnostics"] == []
    assert 0.1 < max(document["extents"]) < 0.3


@pytest.fixture(scope="module")
def turtlebots(tmp_path_factory) -> dict[str, Path]:
    from click.testing import CliRunner
    from mobile_car.cli.main import main

    out = tmp_path_factory.mktemp("turtlebot3")
    built = {}
    for robot in ("burger", "waffle", "waffle_pi"):
        source = FOLDER / "turtlebot3_description" / "urdf" / f"turtlebot3_{robot}.urdf"
        built[robot] = out / f"{robot}.urdf"
        result = CliRunner().invoke(main, ["build", "--package-path", str(FOLDER), str(source),
                                           "-o", str(built[robot])])
        assert result.exit_code == 0, result.output
    return built


# Their castors: 5 g blocks of 3 cm with 0.001 kg m² on each axis, 2,600 times what that
# mass can have there (a radius of gyration of 45 cm). Nothing else.
CASTORS = {"burger": ["caster_back_link"],
           "waffle": ["caster_back_left_link", "caster_back_right_link"],
           "waffle_pi": ["caster_back_left_link", "caster_back_right_link"]}


@needs_folder
@pytest.mark.parametrize("robot", ["burger", "waffle", "waffle_pi"])
def test_turtlebot3_is_its_real_size_and_only_its_castors_are_wrong(cli, turtlebots, robot):
    document = _json(cli, "--package-path", FOLDER, turtlebots[robot])
    assert max(document["extents"]) < 0.5  # waffle's camera in metres was 51 m
    found = [d for d in document["diagnostics"] if d["rule"] in PLAUSIBILITY]
    assert [d["rule"] for d in found] == ["W213"] * len(CASTORS[robot])
    assert sorted(d["message"].split("'")[1] for d in found) == CASTORS[robot]
    assert {d["rule"] for d in document["diagnostics"]} <= {"W207", "W213"}  # waffle's base


@needs_folder
@pytest.mark.parametrize("robot, args", [
    ("husky_description/urdf/husky.urdf.xacro", []),
    ("husky_description/urdf/husky.urdf.xacro",
     ["laser_enabled:=1", "laser_3d_enabled:=1", "blackfly_enabled:=1"]),
    ("jackal_description/urdf/jackal.urdf.xacro", [])], ids=["husky", "husky-all", "jackal"])
def test_husky_and_jackal_raise_no_plausibility_warning(cli, robot, args):
    document = _json(cli, "--package-path", FOLDER, FOLDER / robot, *args)
    assert not [d for d in document["diagnostics"] if d["rule"] in PLAUSIBILITY]
    assert 0.5 < max(document["extents"]) < 1.0  # about a metre long


@pytest.mark.parametrize("large", [False, True], ids=["python", "numpy"])
def test_repeated_parts_are_each_named_at_their_own_line(cli, tmp_path, monkeypatch, large):
    """Links whose content is byte for byte the same are checked once (link_bodies.py);
    a warning about each still points at its own <inertia>, whichever way the rest pose
    is worked out."""
    from mobile_car.check import checker

    monkeypatch.setattr(checker, "LARGE_ROBOT", 0 if large else 10**9)
    castor = ('<collision><geometry><box size="0.03 0.009 0.02"/></geometry></collision>\n'
              '<inertial><mass value="0.005"/>\n<inertia ixx="0.001" ixy="0" ixz="0" '
              'iyy="0.001" iyz="0" izz="0.001"/></inertial>')
    links = "".join(f'<link name="castor_{i}">\n{castor}</link>\n<joint name="j{i}" '
                    f'type="fixed"><parent link="base"/><child link="castor_{i}"/>'
                    f'<origin xyz="{0.1 * i} 0 0"/></joint>\n' for i in range(3))
    robot = tmp_path / "r.urdf"
    robot.write_text(f'<robot name="r">\n<link name="base"/>\n{links}</robot>\n')
    lines = robot.read_text().splitlines()
    expected = [number for number, text in enumerate(lines, 1) if "<inertia " in text]
    found = [(d["rule"], d["line"], d["message"].split("'")[1])
             for d in _json(cli, robot)["diagnostics"]]
    assert found == [("W213", line, f"castor_{i}") for i, line in enumerate(expected)]
