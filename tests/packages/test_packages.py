"""Package search without ROS: order, environment variables, and package:// safety."""

from __future__ import annotations

from pathlib import Path

import pytest

from mobile_car.errors import InputError, PackageNotFoundError
from mobile_car.packages.asset_roots import OutsideRootsError
from mobile_car.packages.bundled import description_dir
from mobile_car.packages.search import PackageSearch


def make_package(root: Path, name: str) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    (root / "package.xml").write_text(f"<package format='3'>\n  <name>{name}</name>\n</package>")
    return root


def test_bundled_description_is_found_with_an_empty_environment():
    search = PackageSearch(environ={})
    assert search.find("mobile_car_description") == description_dir()
    assert (description_dir() / "urdf").is_dir()


def test_order_input_package_then_package_path_then_ros_then_ament(tmp_path):
    own = make_package(tmp_path / "own", "demo")
    flag = make_package(tmp_path / "flag" / "demo", "demo")
    ros = make_package(tmp_path / "ros" / "src" / "nested" / "demo", "demo")
    ament = make_package(tmp_path / "ament" / "share" / "demo", "demo")
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "ros"), "AMENT_PREFIX_PATH": str(tmp_path / "ament")}
    origin = own / "urdf" / "robot.xacro"
    assert PackageSearch([tmp_path / "flag"], origin, env).find("demo") == own
    assert PackageSearch([tmp_path / "flag"], None, env).find("demo") == flag
    assert PackageSearch([], None, env).find("demo") == ros
    del env["ROS_PACKAGE_PATH"]
    assert PackageSearch([], None, env).find("demo") == ament


def test_a_checkout_of_the_description_beats_the_bundled_copy(tmp_path):
    checkout = make_package(tmp_path / "mobile_car_description", "mobile_car_description")
    search = PackageSearch(origin=checkout / "urdf" / "mobile_robot.xacro", environ={})
    assert search.find("mobile_car_description") == checkout


def test_ament_index_marker_is_enough(tmp_path):
    marker = tmp_path / "share" / "ament_index" / "resource_index" / "packages" / "bare"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    search = PackageSearch(environ={"AMENT_PREFIX_PATH": str(tmp_path)})
    assert search.find("bare") == tmp_path / "share" / "bare"


def test_catkin_ignore_and_nested_packages_are_not_crawled(tmp_path):
    make_package(tmp_path / "ignored" / "demo", "demo")
    (tmp_path / "ignored" / "CATKIN_IGNORE").write_text("")
    outer = make_package(tmp_path / "outer", "outer")
    make_package(outer / "inner", "inner")  # inside a package: rospack does not look there
    search = PackageSearch(environ={"ROS_PACKAGE_PATH": str(tmp_path)})
    assert search.find("outer") == outer
    for name in ("demo", "inner"):
        with pytest.raises(PackageNotFoundError):
            search.find(name)


def test_not_found_names_the_package_and_every_place_looked(tmp_path):
    env = {"ROS_PACKAGE_PATH": "/opt/ros_ws/src"}
    with pytest.raises(PackageNotFoundError) as info:
        PackageSearch([tmp_path], None, env).find("ghost_description")
    message = str(info.value)
    assert "package 'ghost_description' not found" in message
    for place in (f"--package-path {tmp_path}", "ROS_PACKAGE_PATH=/opt/ros_ws/src",
                  "AMENT_PREFIX_PATH (unset)", "the bundled mobile_car_description"):
        assert place in message
    assert info.value.exit_code == 2


def test_package_path_must_be_a_directory(tmp_path):
    with pytest.raises(InputError, match="not a directory"):
        PackageSearch([tmp_path / "missing"])


def test_resolve_uri_forms(tmp_path):
    package = make_package(tmp_path / "pkg", "pkg")
    search = PackageSearch(environ={"ROS_PACKAGE_PATH": str(tmp_path)})
    assert search.resolve_uri("package://pkg/meshes/a.stl") == (package / "meshes/a.stl").resolve()
    assert search.resolve_uri(f"file://{package}/b.stl") == package / "b.stl"
    assert search.resolve_uri("meshes/c.stl", base=package) == package / "meshes/c.stl"
    # outside every allowed folder (the packages, the input's, --asset-path's): refused
    with pytest.raises(OutsideRootsError, match="'file:///abs/b.stl' is outside the folders"):
        search.resolve_uri("file:///abs/b.stl")


def test_package_uri_may_not_leave_its_package(tmp_path):
    make_package(tmp_path / "pkg", "pkg")
    make_package(tmp_path / "other", "other")
    (tmp_path / "secret.txt").write_text("x")
    search = PackageSearch(environ={"ROS_PACKAGE_PATH": str(tmp_path)})
    # into another allowed package: still refused, as before
    with pytest.raises(InputError, match="leaves package 'pkg'"):
        search.resolve_uri("package://pkg/../other/package.xml")
    # out of every allowed folder: refused before anything is looked at
    with pytest.raises(OutsideRootsError):
        PackageSearch(environ={"ROS_PACKAGE_PATH": str(tmp_path / "pkg")}).resolve_uri(
            "package://pkg/../secret.txt")


def _workspace_with_a_dependency(tmp_path: Path) -> Path:
    """ws/robot/urdf/robot.urdf.xacro includes $(find part_lib)/urdf/part.xacro from a
    subfolder (as Husky's accessories include clearpath_deps); ws/ holds both."""
    ws = tmp_path / "ws"
    make_package(ws / "deps" / "part_lib", "part_lib")
    (ws / "deps" / "part_lib" / "urdf").mkdir()
    (ws / "deps" / "part_lib" / "urdf" / "part.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="part"><link name="part_link"/></xacro:macro>\n</robot>\n')
    robot = make_package(ws / "robot", "robot")
    (robot / "urdf" / "accessories").mkdir(parents=True)
    (robot / "urdf" / "accessories" / "mount.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find part_lib)/urdf/part.xacro"/>\n</robot>\n')
    (robot / "urdf" / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="accessories/mount.xacro"/>\n'
        '  <xacro:part/>\n</robot>\n')
    return ws


@pytest.mark.parametrize("how", ["--package-path", "ROS_PACKAGE_PATH"])
def test_a_relative_package_path_is_taken_from_the_working_folder(tmp_path, run_mcar, how):
    """A relative folder found $(find part_lib) as a relative path, which xacro then
    joined to the including file's folder ("cannot read robot/urdf/accessories/deps/...")."""
    ws = _workspace_with_a_dependency(tmp_path)
    args, env = (["--package-path", "."], None) if how == "--package-path" else \
        ([], {"ROS_PACKAGE_PATH": "."})
    result = run_mcar("build", "robot/urdf/robot.urdf.xacro", "-o", tmp_path / "out.urdf",
                      *args, cwd=ws, env=env)
    assert result.returncode == 0, result.stderr
    assert '<link name="part_link"/>' in (tmp_path / "out.urdf").read_text()


def test_package_paths_are_absolute_once_read(tmp_path, monkeypatch):
    ws = _workspace_with_a_dependency(tmp_path)
    monkeypatch.chdir(ws)
    search = PackageSearch([Path("deps")], None, {"ROS_PACKAGE_PATH": "robot"})
    assert search.package_paths == [ws / "deps"]
    assert search.find("part_lib") == ws / "deps" / "part_lib"
    assert search.find("robot") == ws / "robot"
