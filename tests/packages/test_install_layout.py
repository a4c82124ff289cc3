"""``$(find PKG)/DIR/...`` where PKG installs another source folder as DIR.

ros2_control_demos' example packages install ``description/ros2_control`` as
``share/PKG/ros2_control`` and their robots include
``$(find PKG)/ros2_control/x.xacro``: a path of the install, not of the checkout.
"""

from __future__ import annotations

from pathlib import Path

from conftest import line_of

from mobile_car.packages.install_layout import source_of

CMAKE = """cmake_minimum_required(VERSION 3.16)
project(demo_bot)
# install(DIRECTORY commented DESTINATION share/${PROJECT_NAME})
install(
  DIRECTORY description/ros2_control description/urdf
  DESTINATION share/${PROJECT_NAME}
)
install(DIRECTORY bringup/config/ DESTINATION share/${PROJECT_NAME}/config)
install(FILES extra/arm.xacro DESTINATION share/demo_bot/parts)
"""

ROBOT = """<?xml version="1.0"?>
<robot name="demo" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find demo_bot)/ros2_control/demo.ros2_control.xacro"/>
  <xacro:property name="dims" value="${xacro.load_yaml('$(find demo_bot)/config/dims.yaml')}"/>
  <link name="base_link">
    <visual><geometry><box size="${dims['length']} 0.2 0.1"/></geometry></visual>
  </link>
  <xacro:demo_control/>
</robot>
"""

CONTROL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="demo_control">
    <ros2_control name="Demo" type="system">
      <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    </ros2_control>
  </xacro:macro>
</robot>
"""


def make_demo(root: Path, control: str = CONTROL) -> Path:
    """A package laid out as ros2_control_demos' examples are; its robot file."""
    (root / "description" / "urdf").mkdir(parents=True)
    (root / "description" / "ros2_control").mkdir()
    (root / "bringup" / "config").mkdir(parents=True)
    (root / "package.xml").write_text(
        "<package format='3'><name>demo_bot</name></package>")
    (root / "CMakeLists.txt").write_text(CMAKE)
    (root / "description" / "ros2_control" / "demo.ros2_control.xacro").write_text(control)
    (root / "bringup" / "config" / "dims.yaml").write_text("length: 0.4\n")
    robot = root / "description" / "urdf" / "demo.urdf.xacro"
    robot.write_text(ROBOT)
    return robot


def test_an_include_and_a_yaml_named_as_installed_are_read_from_the_sources(
        tmp_path, run_mcar):
    robot = make_demo(tmp_path / "demo_bot")
    result = run_mcar("build", str(robot))
    assert result.returncode == 0, result.stderr
    assert '<ros2_control name="Demo" type="system">' in result.stdout
    assert '<box size="0.4 0.2 0.1"/>' in result.stdout
    deps = run_mcar("build", "--deps", "--absolute", str(robot))
    assert deps.stdout.split() == [
        str(robot), str(robot.parents[1] / "ros2_control" / "demo.ros2_control.xacro"),
        str(tmp_path / "demo_bot" / "bringup" / "config" / "dims.yaml")]


def test_an_error_in_the_mapped_include_names_the_source_file_and_line(tmp_path, run_mcar):
    broken = CONTROL.replace("<hardware>", "<hardware>${undefined_name}")
    robot = make_demo(tmp_path / "demo_bot", control=broken)
    result = run_mcar("build", str(robot))
    included = robot.parents[1] / "ros2_control" / "demo.ros2_control.xacro"
    assert result.returncode == 1
    first = result.stderr.splitlines()[0]
    assert first.startswith(f"{included}:{line_of(included, 'undefined_name')}: error: ")
    assert "Traceback" not in result.stderr


def test_a_path_no_rule_installs_stays_missing(tmp_path, run_mcar):
    robot = make_demo(tmp_path / "demo_bot")
    robot.write_text(ROBOT.replace("/ros2_control/demo.", "/launch/demo."))
    result = run_mcar("build", str(robot))
    assert result.returncode == 1
    assert result.stderr.startswith(
        f"{robot}:{line_of(robot, '/launch/demo.')}: error: cannot read "
        f"{tmp_path}/demo_bot/launch/demo.ros2_control.xacro: No such file or directory")


def test_rules_map_folders_their_contents_and_files(tmp_path):
    root = tmp_path / "demo_bot"
    make_demo(root)
    (root / "extra").mkdir()
    (root / "extra" / "arm.xacro").write_text("<robot/>")
    control = root / "description" / "ros2_control" / "demo.ros2_control.xacro"
    assert source_of(root, "demo_bot", "ros2_control/demo.ros2_control.xacro") == control
    assert source_of(root, "demo_bot", "config/dims.yaml") == \
        root / "bringup" / "config" / "dims.yaml"
    assert source_of(root, "demo_bot", "parts/arm.xacro") == root / "extra" / "arm.xacro"
    # the commented rule, a folder itself, a file that is not there, a climb out
    assert source_of(root, "demo_bot", "commented/x.xacro") is None
    assert source_of(root, "demo_bot", "ros2_control") is None
    assert source_of(root, "demo_bot", "urdf/none.xacro") is None
    assert source_of(root, "demo_bot", "ros2_control/../../../CMakeLists.txt") is None


def test_another_package_share_or_an_unknown_variable_maps_nothing(tmp_path):
    root = tmp_path / "demo_bot"
    make_demo(root)
    (root / "CMakeLists.txt").write_text(
        "project(demo_bot)\n"
        "install(DIRECTORY description/ros2_control DESTINATION share/other_pkg)\n"
        "install(DIRECTORY description/ros2_control DESTINATION ${SHARE_DIR})\n")
    assert source_of(root, "demo_bot", "ros2_control/demo.ros2_control.xacro") is None


def test_a_run_reads_the_install_rules_once_for_every_path_the_checkout_lacks(
        tmp_path, monkeypatch):
    # Each include and YAML named as installed read CMakeLists.txt again (ros2_control_demos'
    # robots name a handful a build): one package search, one read.
    from mobile_car.packages import install_layout
    from mobile_car.packages.search import PackageSearch

    root = tmp_path / "demo_bot"
    robot = make_demo(root)
    read = []

    def counted(path, *args, **kwargs):
        read.append(Path(path).name)
        return reading(path, *args, **kwargs)

    reading = install_layout.read_text_quietly
    monkeypatch.setattr(install_layout, "read_text_quietly", counted)
    search = PackageSearch(origin=robot)
    share = search.find("demo_bot")
    assert search.installed_source(share / "ros2_control" / "demo.ros2_control.xacro") == \
        root / "description" / "ros2_control" / "demo.ros2_control.xacro"
    assert search.installed_source(share / "config" / "dims.yaml") == \
        root / "bringup" / "config" / "dims.yaml"
    assert search.installed_source(share / "urdf" / "none.xacro") is None
    assert search.installed_source(robot) is None  # there: no rule asked
    assert read == ["CMakeLists.txt"]
    # another run reads the package as it is then
    (root / "CMakeLists.txt").write_text("project(demo_bot)\n")
    again = PackageSearch(origin=robot)
    assert again.find("demo_bot") == share
    assert again.installed_source(share / "config" / "dims.yaml") is None
    assert read == ["CMakeLists.txt"] * 2
