"""The repository, and a package `mcar init` wrote, build as ROS packages: with catkin in a
catkin workspace (`catkin_make install`, ROS 1) and with ament_cmake (ROS 2; configured,
built and installed by cmake, as colcon does), each installing what its ROS uses."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import MCAR, REPO

# A plain shell's PATH: catkin's CMake runs the first python3 on PATH, which must be the
# one with catkin_pkg (a virtualenv's has none: deactivate it, or pass
# -DPYTHON_EXECUTABLE=/usr/bin/python3, as docs/rviz.md says).
SYSTEM_PATH = "/usr/bin:/bin"
ROS1_FILES = ["launch/display.launch", "rviz/urdf.rviz", "scripts/joint_sliders",
              "scripts/robot_description"]

needs_catkin = pytest.mark.skipif(
    shutil.which("catkin_make") is None,
    reason="catkin is not installed (Debian package catkin; `make test` installs it)")
needs_ament = pytest.mark.skipif(
    not Path("/usr/share/ament_cmake/cmake/ament_cmakeConfig.cmake").is_file()
    or shutil.which("cmake") is None,
    reason="ament_cmake is not installed (Debian package ament-cmake; `make test` installs it)")


def _package(kind: str, folder: Path) -> tuple[str, Path]:
    """(name, source folder) of the repository or of a fresh `mcar init` package."""
    if kind == "repository":
        return "mobile_car_description", REPO
    subprocess.run([str(MCAR), "init", "demo_description"], cwd=folder, check=True,
                   capture_output=True)
    return "demo_description", folder / "demo_description"


def _run(command: list[str], cwd: Path, ros_version: str | None) -> None:
    env = {key: value for key, value in os.environ.items()
           if not key.startswith(("ROS_", "AMENT_", "CMAKE_", "VIRTUAL_ENV"))}
    env.update(PATH=SYSTEM_PATH, HOME=str(cwd), PWD=str(cwd))  # catkin_make reads PWD
    if ros_version:
        env["ROS_VERSION"] = ros_version
    done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, f"{' '.join(command)}:\n{done.stdout[-3000:]}{done.stderr}"


@needs_catkin
@pytest.mark.parametrize("kind", ["repository", "mcar init"])
def test_catkin_make_builds_and_installs_the_viewer(kind, tmp_path):
    name, source = _package(kind, tmp_path)
    workspace = tmp_path / "catkin_ws"
    (workspace / "src").mkdir(parents=True)
    (workspace / "src" / name).symlink_to(source)  # a checkout linked into the workspace
    _run(["catkin_make", "install", f"-DCMAKE_INSTALL_PREFIX={workspace / 'install'}"],
         workspace, ros_version=None)
    share = workspace / "install" / "share" / name
    for rel in ["package.xml", *ROS1_FILES]:
        assert (share / rel).is_file(), rel
    for script in ("scripts/joint_sliders", "scripts/robot_description"):
        assert os.access(share / script, os.X_OK), script
    robots = sorted(p.name for p in (share / "urdf").glob("*.*xacro"))
    assert robots == sorted(p.name for p in (source / "urdf").glob("*.*xacro"))


@needs_ament
@pytest.mark.parametrize("kind", ["repository", "mcar init"])
def test_ament_builds_and_installs_the_description(kind, tmp_path):
    name, source = _package(kind, tmp_path)
    build, install = tmp_path / "build", tmp_path / "install"
    _run(["cmake", "-S", str(source), "-B", str(build), f"-DCMAKE_INSTALL_PREFIX={install}"],
         tmp_path, ros_version="2")
    _run(["cmake", "--build", str(build)], tmp_path, ros_version="2")
    _run(["cmake", "--install", str(build)], tmp_path, ros_version="2")
    share = install / "share" / name
    assert (install / "share" / "ament_index" / "resource_index" / "packages" / name).is_file()
    assert (share / "package.xml").is_file() and (share / "urdf").is_dir()
    assert not (share / "launch").exists()  # ROS 1's roslaunch XML is not ROS 2's
    # what is installed is whole: its robot builds there, every $(find) resolved in it
    robot = "mobile_robot.xacro" if kind == "repository" else f"{name}.urdf.xacro"
    built = subprocess.run([str(MCAR), "build", str(share / "urdf" / robot), "-o", "-"],
                           capture_output=True, text=True, cwd=tmp_path)
    assert built.returncode == 0, built.stderr
    assert "<robot name=" in built.stdout
