"""A robot package and its siblings written at test time, as released ROS packages lay
them out: ``bot_description`` (the robot), ``bot_control/config/*.yaml`` (its
controllers) and ``bot_navigation/params/*.yaml`` (Nav2), for the stack's fragments and
check's comparison of the package's own YAML (mobile_car/specs/stack*.py)."""

from __future__ import annotations

from pathlib import Path

PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')

# two_wheeler(): wheels 0.033 m, 0.16 m apart
DIFF_CONTROL = """diff_cont:
  ros__parameters:
    left_wheel_names: [{left}]
    right_wheel_names: [{right}]
    wheel_separation: {separation}
    wheel_radius: {radius}
"""


def write_package(root: Path, robot: str, files: dict[str, str]) -> Path:
    """``root/bot_description/robot.urdf`` holding ``robot``, and ``files`` (path under
    root -> text), each in a package of its folder's name; returns the robot file."""
    (root / "bot_description").mkdir(parents=True, exist_ok=True)
    (root / "bot_description" / "package.xml").write_text(PACKAGE_XML.format("bot_description"))
    robot_file = root / "bot_description" / "robot.urdf"
    robot_file.write_text(robot)
    for relative, text in files.items():
        path = root / relative
        package = root / Path(relative).parts[0]
        package.mkdir(parents=True, exist_ok=True)
        if not (package / "package.xml").exists():
            (package / "package.xml").write_text(PACKAGE_XML.format(package.name))
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return robot_file


def checked_and_model(robot_file: Path, root: Path):
    """(the CheckResult, sim's resting SimModel) of the robot, its packages under root."""
    from mobile_car.check.checker import check_input
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.specs.stack_check import resting_model

    checked = check_input(RobotInput(robot_file), LoadOptions(package_paths=[root]))
    assert checked.sound, [d.text() for d in checked.diagnostics]
    return checked, resting_model(checked)
