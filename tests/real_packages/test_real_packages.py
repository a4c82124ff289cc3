"""Real description packages: `mcar build` writes what the `xacro` command writes, byte
for byte but the banner, whichever way the package is found; `mcar check` finds no error.
The packages and where they come from: README.md beside this file."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
UR = HERE / "ur_description"
FRANKA = HERE / "franka_description"
XACRO = Path(sys.executable).parent / "xacro"
BANNER = re.compile(r"<!-- =+ -->\n(?:<!-- \|.*\| -->\n)+<!-- =+ -->\n")
# (robot file, xacro arguments): each is built by both and compared.
ROBOTS = [*[(UR / "urdf" / "ur.urdf.xacro", [f"ur_type:={kind}", "name:=ur"])
            for kind in ("ur3", "ur5e", "ur10e", "ur20", "ur30")],
          *[(FRANKA / "robots" / kind / f"{kind}.urdf.xacro", [])
            for kind in ("fer", "fr3", "fp3", "multi_arm")],
          (FRANKA / "robots" / "fr3" / "fr3.urdf.xacro", ["hand:=true", "ros2_control:=true"])]


@pytest.fixture(scope="module")
def ament_prefix(tmp_path_factory) -> Path:
    """An install prefix as colcon makes it: share/PKG and the package index marker."""
    prefix = tmp_path_factory.mktemp("prefix")
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    for package in (UR, FRANKA):
        (index / package.name).touch()
        (prefix / "share" / package.name).symlink_to(package)
    return prefix


def peer_build(robot: Path, args: list[str], prefix: Path) -> str:
    env = {**os.environ, "AMENT_PREFIX_PATH": str(prefix),
           "PYTHONPATH": str(HERE / "peer")}
    done = subprocess.run([str(XACRO), str(robot), *args], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return BANNER.sub("", done.stdout)


@pytest.mark.parametrize("robot, args", ROBOTS,
                         ids=[f"{r.stem}{'-' + '-'.join(a) if a else ''}" for r, a in ROBOTS])
def test_builds_as_the_xacro_command_builds_it(robot, args, run_mcar, ament_prefix, tmp_path):
    expected = peer_build(robot, args, ament_prefix)
    ours = run_mcar("build", robot, *args, "-o", tmp_path / "robot.urdf")
    assert ours.returncode == 0, ours.stderr
    assert BANNER.sub("", (tmp_path / "robot.urdf").read_text()) == expected
    checked = run_mcar("check", "-q", robot, *args)
    assert checked.returncode == 0, checked.stderr  # the meshes are left out: W207 only
    assert " error: " not in checked.stderr


def test_the_robots_of_a_package_are_found_where_it_keeps_them(run_mcar, tmp_path):
    """franka keeps its robots in robots/; robots/common/franka_arm.xacro names its <robot>
    but is a macro file that franka_robot.xacro includes: not a robot to build."""
    result = run_mcar("build", FRANKA, "-o", tmp_path / "out", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert sorted(p.relative_to(tmp_path / "out").as_posix()
                  for p in (tmp_path / "out").rglob("*.urdf")) == \
        ["fer/fer.urdf", "fp3/fp3.urdf", "fr3/fr3.urdf", "multi_arm/multi_arm.urdf"]


@pytest.mark.parametrize("how", ["--package-path", "ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"])
def test_the_package_is_found_from_outside_it_every_way(how, run_mcar, ament_prefix, tmp_path):
    robot = tmp_path / "ur.urdf.xacro"  # outside the package: $(find) must search for it
    robot.write_text((UR / "urdf" / "ur.urdf.xacro").read_text())
    args = ["ur_type:=ur5e", "name:=ur"]
    expected = peer_build(robot, args, ament_prefix)
    options, env = [], {}
    if how == "--package-path":
        options = ["--package-path", str(HERE)]
    elif how == "ROS_PACKAGE_PATH":
        env = {"ROS_PACKAGE_PATH": str(HERE)}
    else:
        env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    ours = run_mcar("build", robot, *args, *options, env=env, cwd=tmp_path)
    assert ours.returncode == 0, ours.stderr
    assert BANNER.sub("", ours.stdout) == expected
