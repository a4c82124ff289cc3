"""``mcar check --gazebo`` on the robots people ship (the shared real-robots folder, read in
place): libsdformat lumps their fixed links, and drops nothing; Gazebo simulates the mass
the URDF describes. TurtleBot3's .urdf holds a <xacro:arg>: built first, as ROS 2 launch
expands it."""

from __future__ import annotations

import json

import pytest
from sim.test_sim_real_robots import FOLDER, needs_folder

# robot file (in the folder), xacro arguments, Gazebo's links, URDF mass (SOURCES.md)
ROBOTS = [
    ("turtlebot3_description/urdf/turtlebot3_burger.urdf", (), 3, 1.002),
    ("turtlebot3_description/urdf/turtlebot3_waffle.urdf", (), 3, 1.554),
    ("turtlebot3_description/urdf/turtlebot3_waffle_pi.urdf", (), 3, 1.554),
    ("husky_description/urdf/husky.urdf.xacro", (), 5, 56.58),
    ("husky_description/urdf/husky.urdf.xacro",
     ("laser_enabled:=1", "laser_3d_enabled:=1", "blackfly_enabled:=1"), 5, 58.55),
    ("jackal_description/urdf/jackal.urdf.xacro", (), 5, 18.43),
]


@needs_folder
@pytest.mark.parametrize("robot, arguments, links, mass", ROBOTS,
                         ids=["burger", "waffle", "waffle_pi", "husky", "husky-sensors",
                              "jackal"])
def test_gazebo_lumps_a_shipped_robot_and_drops_nothing(cli, gazebo, tmp_path, robot,
                                                        arguments, links, mass):
    source = FOLDER / robot
    if source.suffix == ".urdf":
        built = tmp_path / source.name
        assert cli("build", "--package-path", FOLDER, source, "-o", built).exit_code == 0
        source = built
    result = cli("check", "--gazebo", "--format", "json", "--package-path", FOLDER, source,
                 *arguments)
    [file] = json.loads(result.stdout)["files"]
    rules = [d["rule"] for d in file["diagnostics"]]
    assert not [d for d in file["diagnostics"] if d["severity"] == "error"]
    assert result.exit_code == 0
    view = file["gazebo"]
    assert len(view["links"]) == links
    assert view["lost"] == {}
    assert len(view["lumped"]) == rules.count("N401") > 0
    assert view["gazebo_mass"] == pytest.approx(view["urdf_mass"], rel=1e-9)
    assert view["urdf_mass"] == pytest.approx(mass, abs=0.005)
    assert not [rule for rule in rules if rule in ("W230", "W231", "W232")]


@needs_folder
def test_quiet_gazebo_check_of_husky_prints_no_notes(cli, gazebo):
    husky = FOLDER / "husky_description/urdf/husky.urdf.xacro"
    loud = cli("check", "--gazebo", "--package-path", FOLDER, husky)
    assert loud.exit_code == 0
    assert loud.stderr.count(": note: ") >= 12  # the control: the notes -q leaves out
    quiet = cli("check", "-q", "--gazebo", "--package-path", FOLDER, husky)
    assert quiet.exit_code == 0
    assert quiet.stdout == ""
    assert ": note: " not in quiet.stderr
