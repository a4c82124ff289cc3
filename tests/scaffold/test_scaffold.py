"""mcar init and mcar new part: what they write passes mcar ci --strict at once, with
pictures, and nothing is ever overwritten."""

from __future__ import annotations

import os
import re

from lxml import etree


def test_init_then_new_part_pass_ci_with_pictures(run_mcar, tmp_path):
    made = run_mcar("init", "x", "--name", "demo", cwd=tmp_path)
    assert made.returncode == 0, made.stderr
    package = tmp_path / "x"
    for name in ("package.xml", "CMakeLists.txt", ".gitignore", ".pre-commit-config.yaml",
                 ".github/workflows/mcar.yml", "urdf/define.xacro", "urdf/config.xacro",
                 "urdf/demo.urdf.xacro", "meshes/.gitkeep", "launch/display.launch",
                 "rviz/urdf.rviz", "scripts/robot_description", "scripts/joint_sliders"):
        assert (package / name).is_file(), name
    assert etree.parse(str(package / "package.xml")).findtext("name") == "demo"
    assert "mcar ci ." in (package / ".github/workflows/mcar.yml").read_text()
    assert "mcar ci ." in (package / ".pre-commit-config.yaml").read_text()

    ci = run_mcar("ci", "--strict", cwd=package)
    assert ci.returncode == 0, ci.stderr
    assert ci.stderr.splitlines()[0] == f"mcar: package demo ({package})"
    assert "mcar ci: 3 of 3 files passed" in ci.stderr  # the robot, wheel and castor
    assert (package / "renders" / "demo.png").is_file() and (package / "build/demo.urdf").is_file()

    part = run_mcar("new", "part", "arm", cwd=package / "urdf")
    assert part.returncode == 0, part.stderr
    assert (package / "urdf/arm/arm.xacro").is_file()
    ci = run_mcar("ci", "--strict", cwd=package / "urdf" / "arm")
    assert ci.returncode == 0, ci.stderr
    assert "mcar ci: 4 of 4 files passed" in ci.stderr
    assert (package / "renders/arm/test_arm.png").is_file()
    assert (package / "build/arm/test_arm.urdf").is_file()


def test_a_new_package_gets_the_bundled_ros_files_with_its_own_names(run_mcar, tmp_path):
    """CMakeLists.txt, display.launch, urdf.rviz and the launch's scripts are the bundled
    package's (tests/ros/ builds and launches them), with the name and robot put in."""
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    package = tmp_path / "demo"
    launch = (package / "launch" / "display.launch").read_text()
    assert '<arg name="model" default="$(find demo)/urdf/demo.urdf.xacro"/>' in launch
    assert "find('demo').replace(" in launch and "/scripts/robot_description" in launch
    assert "mobile_car" not in launch and "mobile_robot" not in launch
    assert "project(demo NONE)" in (package / "CMakeLists.txt").read_text()
    assert "\n      Distance: 0.75\n" in (package / "rviz" / "urdf.rviz").read_text()
    umask = os.umask(0)
    os.umask(umask)
    for script in ("robot_description", "joint_sliders"):
        assert (package / "scripts" / script).stat().st_mode & 0o777 == 0o777 & ~umask, script
    assert (package / "launch" / "display.launch").stat().st_mode & 0o777 == 0o666 & ~umask
    xml = etree.parse(str(package / "package.xml"))
    assert [(e.text, e.get("condition")) for e in xml.iter("build_type")] == [
        ("catkin", "$ROS_VERSION == 1"), ("ament_cmake", "$ROS_VERSION == 2")]


def test_scripts_are_executable_as_the_umask_allows(tmp_path):
    from mobile_car.scaffold import create_package

    old = os.umask(0o077)
    try:
        create_package(tmp_path / "demo")
    finally:
        os.umask(old)
    assert (tmp_path / "demo/scripts/robot_description").stat().st_mode & 0o777 == 0o700
    assert (tmp_path / "demo/package.xml").stat().st_mode & 0o777 == 0o600


def test_the_dimensions_of_a_new_package_are_its_own(run_mcar, tmp_path):
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    package = tmp_path / "demo"
    table = run_mcar("config", cwd=package)
    assert table.returncode == 0, table.stderr
    assert re.search(r"base_length\s+0\.3\s+m\s+design", table.stdout)
    built = run_mcar("build", "urdf/demo.urdf.xacro", "--set", "base_length=32cm", cwd=package)
    assert built.returncode == 0, built.stderr
    assert '<box size="0.32 0.2 0.05"/>' in built.stdout


def test_nothing_is_overwritten(run_mcar, tmp_path):
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    robot = tmp_path / "demo" / "urdf" / "demo.urdf.xacro"
    robot.write_text("mine")
    again = run_mcar("init", "demo", cwd=tmp_path)
    assert again.returncode == 2
    assert again.stderr.startswith("mcar: error: will not overwrite ")
    assert robot.read_text() == "mine"
    assert run_mcar("new", "part", "arm", cwd=tmp_path / "demo").returncode == 0
    twice = run_mcar("new", "part", "arm", cwd=tmp_path / "demo")
    assert twice.returncode == 2 and "will not overwrite" in twice.stderr


def test_bad_names_and_no_package_exit_2(run_mcar, tmp_path):
    bad = run_mcar("init", "My-Robot", cwd=tmp_path)
    assert bad.returncode == 2
    assert "'My-Robot' is not a valid package name" in bad.stderr
    assert not (tmp_path / "My-Robot").exists()
    outside = run_mcar("new", "part", "arm", cwd=tmp_path)
    assert outside.returncode == 2 and "not inside a description package" in outside.stderr
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    link = run_mcar("new", "part", "link", cwd=tmp_path / "demo")
    assert link.returncode == 2 and "a URDF element has that name" in link.stderr
