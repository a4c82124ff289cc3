"""What mobile_car.sim.declared reads as a package's drive declaration, in the spellings
released packages use: Gazebo plugins (ROS 1, ROS 2, gz-sim) and controller YAML (ROS 1
and ROS 2 controllers). Pure parsing: no engine."""

from __future__ import annotations

import pytest
import yaml
from lxml import etree

from mobile_car.sim.declared import in_urdf, in_yaml_mapping, joint_problems


def plugins(body: str):
    root = etree.fromstring(f"<robot name='r'><gazebo>{body}</gazebo></robot>")
    return [(d.kind, d.left, d.right, d.driven, d.steering) for d in in_urdf(list(root))]


@pytest.mark.parametrize("body, found", [
    ('<plugin name="d" filename="libgazebo_ros_diff_drive.so"><leftJoint>l</leftJoint>'
     "<rightJoint>r</rightJoint></plugin>", [("differential", ["l"], ["r"], [], [])]),
    ('<plugin filename="gz-sim-diff-drive-system" name="gz::sim::systems::DiffDrive">'
     "<left_joint>fl</left_joint><left_joint>rl</left_joint><right_joint>fr</right_joint>"
     "<right_joint>rr</right_joint></plugin>",
     [("skid-steer", ["fl", "rl"], ["fr", "rr"], [], [])]),
    ('<plugin name="s" filename="libgazebo_ros_skid_steer_drive.so"><leftFrontJoint>fl'
     "</leftFrontJoint><rightFrontJoint>fr</rightFrontJoint><leftRearJoint>rl"
     "</leftRearJoint><rightRearJoint>rr</rightRearJoint></plugin>",
     [("skid-steer", ["fl", "rl"], ["fr", "rr"], [], [])]),
    ('<plugin name="a" filename="libgazebo_ros_ackermann_drive.so"><rear_left_joint>rl'
     "</rear_left_joint><rear_right_joint>rr</rear_right_joint><left_steering_joint>sl"
     "</left_steering_joint><right_steering_joint>sr</right_steering_joint></plugin>",
     [("ackermann", [], [], ["rl", "rr"], ["sl", "sr"])]),
    ('<plugin filename="gz-sim-mecanum-drive-system" name="gz::sim::systems::MecanumDrive">'
     "<front_left_joint>a</front_left_joint><front_right_joint>b</front_right_joint>"
     "<back_left_joint>c</back_left_joint><back_right_joint>d</back_right_joint></plugin>",
     [("mecanum", [], [], ["a", "b", "c", "d"], [])]),
    # planar_move moves the body: it names no wheel; gazebo_ros_control drives nothing.
    ('<plugin name="p" filename="libgazebo_ros_planar_move.so"/>'
     '<plugin name="c" filename="libgazebo_ros_control.so"/>', []),
])
def test_gazebo_drive_plugins_are_read(body, found):
    assert plugins(body) == found


def controllers(text: str):
    found = []
    todo = [yaml.compose(text)]
    while todo:
        node = todo.pop(0)
        if isinstance(node, yaml.MappingNode):
            keys = {k.value: (k, v) for k, v in node.value}
            declaration = in_yaml_mapping(keys, "c.yaml", _names)
            if declaration is not None:
                found.append((declaration.kind, declaration.left + declaration.right,
                              declaration.driven, declaration.steering, declaration.source))
            todo += [v for _, v in node.value]
    return found


def _names(node):
    if isinstance(node, yaml.ScalarNode):
        return [node.value]
    return [n.value for n in node.value]


@pytest.mark.parametrize("text, found", [
    ("c:\n  left_wheel: l\n  right_wheel: r\n",
     [("differential", ["l", "r"], [], [], "controller YAML c.yaml:2")]),
    ("c:\n  ros__parameters:\n    left_wheel_names: [fl, rl]\n    right_wheel_names: [fr, rr]\n",
     [("skid-steer", ["fl", "rl", "fr", "rr"], [], [], "controller YAML c.yaml:3")]),
    ("c:\n  rear_wheel: rw\n  front_steer: fs\n",
     [("ackermann", [], ["rw"], ["fs"], "controller YAML c.yaml:2")]),
    ("c:\n  ros__parameters:\n    traction_joints_names: [a, b]\n"
     "    steering_joints_names: [c, d]\n",
     [("ackermann", [], ["a", "b"], ["c", "d"], "controller YAML c.yaml:3")]),
    ("c:\n  ros__parameters:\n    rear_wheels_names: [a, b]\n    front_wheels_names: [c, d]\n",
     [("ackermann", [], ["a", "b"], ["c", "d"], "controller YAML c.yaml:3")]),
    ("c:\n  traction_joint_name: t\n  steering_joint_name: s\n",
     [("ackermann", [], ["t"], ["s"], "controller YAML c.yaml:2")]),
    ("c:\n  type: mecanum_drive_controller/MecanumDriveController\n"
     "  front_left_wheel_command_joint_name: a\n  front_right_wheel_command_joint_name: b\n"
     "  rear_left_wheel_command_joint_name: c\n  rear_right_wheel_command_joint_name: d\n",
     [("mecanum", [], ["a", "b", "c", "d"], [], "controller YAML c.yaml:3")]),
    # a joint_state_broadcaster, a controller's limits: nothing declared
    ("c:\n  type: joint_state_broadcaster/JointStateBroadcaster\n  publish_rate: 50\n", []),
])
def test_controller_yaml_is_read(text, found):
    assert controllers(text) == found


def test_a_declaration_naming_a_fixed_or_missing_joint_is_found():
    root = etree.fromstring(
        "<robot name='r'><gazebo><plugin filename='libgazebo_ros_diff_drive.so' name='d'>"
        "<left_joint>l</left_joint><right_joint>gone</right_joint></plugin></gazebo></robot>")
    (declaration,) = in_urdf(list(root))
    assert joint_problems(declaration, {"l": "fixed", "r": "continuous"}) == [
        ("l", "a fixed joint: it cannot turn a wheel"),
        ("gone", "the robot has no joint of that name")]
    assert joint_problems(declaration, {"l": "continuous", "gone": "continuous"}) == []
