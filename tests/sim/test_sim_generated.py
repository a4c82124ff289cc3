"""mcar sim on robots made here at test time: the bundled car with a <transmission> block,
two-wheel robots whose wheel joints have no <limit>, whose motor figures live in
<ros2_control> or a Gazebo plugin, one of 70 kg, one on two castors. Each says where its
motor figures came from and passes, or fails naming the cause."""

from __future__ import annotations

import json

import pytest
from sim.robot_makers import two_wheeler

ROBOT = "urdf/mobile_robot.xacro"

TRANSMISSION = """
  <transmission name="wheel_left_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="wheel_left_joint">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
    </joint>
    <actuator name="wheel_left_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <ros2_control name="base" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="wheel_right_joint"><command_interface name="velocity"/></joint>
  </ros2_control>
"""


def _json(cli, *args):
    result = cli("sim", *args, "--format", "json", terminal_width=200)
    return result, json.loads(result.stdout)["files"]


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """name -> path of each generated robot."""
    folder = tmp_path_factory.mktemp("generated")
    robots = {
        "no limit": two_wheeler(),
        "two castors": two_wheeler(castors=2),
        "70 kg": two_wheeler(mass=70.0, scale=5.0),
        "ros2_control": two_wheeler(extra="""
  <ros2_control name="base" type="system">
    <joint name="wheel_left_joint"><command_interface name="velocity">
      <param name="min">-8</param><param name="max">8</param></command_interface>
      <command_interface name="effort"><param name="max">0.2</param></command_interface>
    </joint>
  </ros2_control>"""),
        "plugin": two_wheeler(extra="""
  <gazebo><plugin name="diff" filename="libgazebo_ros_diff_drive.so">
    <leftJoint>wheel_left_joint</leftJoint><rightJoint>wheel_right_joint</rightJoint>
    <wheelSeparation>0.16</wheelSeparation><wheelDiameter>0.066</wheelDiameter>
    <wheelTorque>0.3</wheelTorque></plugin></gazebo>"""),
    }
    paths = {}
    for name, text in robots.items():
        paths[name] = folder / (name.replace(" ", "_") + ".urdf")
        paths[name].write_text(text)
    return paths


def test_a_transmission_block_does_not_replace_the_wheel_joint(cli, package_copy, monkeypatch):
    path = package_copy / ROBOT
    text = path.read_text()
    assert text.rstrip().endswith("</robot>")
    path.write_text(text.rstrip()[:-len("</robot>")] + TRANSMISSION + "</robot>\n")
    monkeypatch.chdir(package_copy)
    result, (entry,) = _json(cli, ROBOT)
    assert result.exit_code == 0, result.stderr
    assert (entry["drive"]["left"], entry["drive"]["right"]) == \
        (["wheel_left_joint"], ["wheel_right_joint"])
    assert [s["status"] for s in entry["scenarios"]] == ["passed"] * 3
    named = cli("sim", ROBOT, "--left", "wheel_left_joint", "--right", "wheel_right_joint",
                "--scenario", "drop")
    assert named.exit_code == 0, named.stderr
    assert "None" not in named.stderr


def test_a_wheel_joint_without_limit_gets_a_torque_that_holds_the_robot_on_a_slope(
        cli, generated):
    result, (entry,) = _json(cli, generated["no limit"])
    assert result.exit_code == 0, result.stderr
    motor = entry["drive"]["motors"]["wheel_left_joint"]
    # 0.7 kg · 9.81 m/s² · sin 10° · 0.033 m / 2 wheels
    assert motor["effort"] == pytest.approx(0.01967, rel=1e-3)
    assert motor["effort_from"] == ("default: holds 0.7 kg on a 10° slope "
                                    "(m·g·sin 10°·r / 2)")
    assert motor["velocity"] is None and entry["drive"]["command_speed"] == 10


def test_a_70_kg_robot_follows_the_ramp(cli, generated):
    result, (entry,) = _json(cli, generated["70 kg"])
    assert result.exit_code == 0, result.stderr + result.stdout
    drive = entry["drive"]
    assert drive["mass"] == pytest.approx(70.0, rel=1e-3)
    # 70 kg · r² / 2 on a 0.165 m wheel: a gain ~950x the small car's
    assert drive["motors"]["wheel_left_joint"]["servo_gain"] > 100
    assert drive["command_speed"] == pytest.approx(0.5 / 0.165, rel=1e-3)  # walking pace
    figures = {s["name"]: {f["name"]: f["value"] for f in s["figures"]}
               for s in entry["scenarios"]}
    assert figures["drive"]["wheel speed reached"] >= 98
    assert figures["drive"]["distance error"] < 2
    assert figures["spin"]["yaw rate error"] < 5


def test_a_robot_on_two_castors_names_both(cli, generated):
    result, (entry,) = _json(cli, generated["two castors"])
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["kind"] == "differential"
    assert entry["drive"]["castors"] == ["castor_1_link", "castor_2_link"]
    assert [s["status"] for s in entry["scenarios"]] == ["passed"] * 3


def test_motor_figures_come_from_ros2_control_then_a_default(cli, generated):
    result, (entry,) = _json(cli, generated["ros2_control"], "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    motors = entry["drive"]["motors"]
    left, right = motors["wheel_left_joint"], motors["wheel_right_joint"]
    assert (left["effort"], left["effort_from"]) == \
        (0.2, "<ros2_control> effort command interface")
    assert (left["velocity"], left["velocity_from"]) == \
        (8, "<ros2_control> velocity command interface")
    assert right["effort_from"].startswith("default: holds") and right["velocity"] is None
    assert entry["drive"]["command_speed"] == 4  # half the smaller speed limit


def test_motor_figures_come_from_a_ros1_diff_drive_plugin_before_the_flags(cli, generated):
    result, (entry,) = _json(cli, generated["plugin"], "--scenario", "drop",
                             "--effort", "5", "--speed", "12")
    assert result.exit_code == 0, result.stderr
    motor = entry["drive"]["motors"]["wheel_right_joint"]
    assert (motor["effort"], motor["effort_from"]) == \
        (0.3, "<gazebo> plugin libgazebo_ros_diff_drive.so torque")
    assert (motor["velocity"], motor["velocity_from"]) == (12, "--speed")


def test_the_text_report_says_where_each_figure_came_from(cli, generated):
    result = cli("sim", generated["no limit"], "--scenario", "drop", "--effort", "0.5",
                 terminal_width=200)
    assert result.exit_code == 0
    # Motors whose figures agree share one line.
    assert "  motor wheel_left_joint, wheel_right_joint: 0.5 N·m (--effort), no limit, " \
           "servo gain 0.5 N·m·s/rad\n" in result.stdout
