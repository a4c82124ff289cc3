"""The controller YAML of a robot's packages is read as ROS reads it. Clearpath's Warthog
ships warthog_control/config/control.yaml with ``two_d_mode`` given twice in its EKF
section: ROS keeps the last value, mcar refused the whole file ("not read (duplicate
key ...)"), so spin no longer compared its measured multiplier with the controller's
1.125. Robots made here (robot_makers' skid-steer robot, a package pair around it)."""

from __future__ import annotations

from sim.robot_makers import skid_steer
from sim.test_sim_drives import PACKAGE_XML, SKID, rover_package

# as ROS 1's diff_drive_controller and robot_localization read it (Warthog's file)
CONTROL_YAML = """rover_velocity_controller:
  type: "diff_drive_controller/DiffDriveController"
  left_wheel: ['front_left_wheel_joint', 'rear_left_wheel_joint']
  right_wheel: ['front_right_wheel_joint', 'rear_right_wheel_joint']
  wheel_separation_multiplier: 1.7
ekf_localization:
  two_d_mode: false
  frequency: 50
  two_d_mode: true
"""


def test_a_key_given_twice_keeps_its_last_value_and_the_file_is_read(cli, tmp_path,
                                                                     monkeypatch):
    rover_package(tmp_path, CONTROL_YAML)
    monkeypatch.chdir(tmp_path)
    result = cli("sim", "rover_description/rover.urdf", "--package-path", tmp_path,
                 "--scenario", "spin", terminal_width=200)
    assert result.exit_code == 0, result.stderr
    assert "not read" not in result.stderr
    assert ("wheels front_left_wheel_joint, rear_left_wheel_joint, front_right_wheel_joint, "
            "rear_right_wheel_joint from controller YAML rover_control/config/control.yaml:3"
            ) in result.stdout
    finding = result.stdout.splitlines()[-1].strip()
    assert finding.startswith("rover_control/config/control.yaml:5: wheel_separation_multiplier "
                              "1.7; measured ")


# gz_ros2_control's demos: the plugin names its controllers' file, in a package that is
# no X_control of an X_description (gz_ros2_control_demos/config/*.yaml); the demos'
# Ackermann, tricycle and diff-drive controllers went unread.
NAMED_YAML = """controller_manager:
  ros__parameters:
    update_rate: 100
diff_drive_base_controller:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: ["front_left_wheel_joint", "rear_left_wheel_joint"]
    right_wheel_names: ["front_right_wheel_joint", "rear_right_wheel_joint"]
    wheel_separation_multiplier: 1.9
"""
PLUGIN = """
  <gazebo>
    <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
      <parameters>{}</parameters>
    </plugin>
  </gazebo>"""


def _demo(tmp_path, yaml_path):
    package = tmp_path / "robot_demos"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text(PACKAGE_XML.format("robot_demos"))
    yaml_path.parent.mkdir(parents=True, exist_ok=True)
    yaml_path.write_text(NAMED_YAML)
    # the absolute path $(find robot_demos)/config/... expands to
    robot = package / "urdf" / "robot.urdf"
    robot.write_text(skid_steer(extra=PLUGIN.format(yaml_path), **SKID))
    return robot


def test_the_controllers_file_the_robot_names_is_read_outside_a_control_package(
        cli, tmp_path, monkeypatch):
    robot = _demo(tmp_path, tmp_path / "robot_demos" / "config" / "controllers.yaml")
    monkeypatch.chdir(tmp_path)
    result = cli("sim", robot.relative_to(tmp_path), "--scenario", "spin",
                 terminal_width=200)
    assert result.exit_code == 0, result.stderr
    assert ("wheels front_left_wheel_joint, rear_left_wheel_joint, front_right_wheel_joint, "
            "rear_right_wheel_joint from controller YAML robot_demos/config/controllers.yaml:7"
            ) in result.stdout
    finding = result.stdout.splitlines()[-1].strip()
    assert finding.startswith("robot_demos/config/controllers.yaml:9: "
                              "wheel_separation_multiplier 1.9; measured ")


def test_a_named_file_outside_the_robots_folders_is_not_read(cli, tmp_path, monkeypatch):
    robot = _demo(tmp_path, tmp_path / "elsewhere" / "controllers.yaml")
    monkeypatch.chdir(tmp_path)
    result = cli("sim", robot.relative_to(tmp_path), "--scenario", "spin",
                 terminal_width=200)
    assert result.exit_code == 0, result.stderr
    assert "from geometry: a wheel that touches the floor" in result.stdout
    assert "wheel_separation_multiplier 1.9" not in result.stdout
    assert ("elsewhere/controllers.yaml: not read ('" + str(tmp_path / "elsewhere" /
            "controllers.yaml") + "' is outside the folders a robot may name files in"
            ) in result.stderr
