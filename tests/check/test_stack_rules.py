"""``mcar check`` compares the package's own ROS YAML with the robot (W510-W514,
mobile_car/specs/stack_check.py): the control package's controller geometry and wheel
names, Nav2's footprint and radius, laser_filters' bounds. Each mismatch is a warning at
the YAML line; a package without such YAML is checked as before, without MuJoCo."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from sim.robot_makers import skid_steer, two_wheeler
from specs.stack_package import (
    DIFF_CONTROL,
    PACKAGE_XML,
    checked_and_model,
    write_package,
)

from mobile_car.specs.figures import Figure, Section
from mobile_car.specs.stack_check import find_package_yaml
from mobile_car.specs.stack_compare import compare

CONTROL = "bot_control/config/control.yaml"


def diff_control(separation=0.16, radius=0.033, left="wheel_left_joint",
                 right="wheel_right_joint", extra=""):
    return DIFF_CONTROL.format(left=left, right=right, separation=separation,
                               radius=radius) + extra


def check(run_mcar, root, *args):
    return run_mcar("check", "-q", *args, "bot_description/robot.urdf", "--package-path", root,
                    cwd=root)


def warnings(result, rule):
    return [line for line in result.stderr.splitlines() if line.endswith(f"[{rule}]")]


def test_a_wheel_separation_ten_percent_off_is_a_located_warning(run_mcar, tmp_path):
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control(separation=0.176)})
    result = check(run_mcar, tmp_path)
    assert result.returncode == 0, result.stderr
    assert warnings(result, "W510") == [
        f"{CONTROL}:5: warning: wheel_separation 0.176 m, but the drive wheels "
        "wheel_left_joint and wheel_right_joint are 0.16 m apart (+10.0%): odometry and "
        "turning rates would be off [W510]"]
    # one warning more than the same robot with a matching controller (its root's W208)
    assert result.stderr.splitlines()[-1] == "mcar check: 0 errors, 2 warnings in 1 file"
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control(separation=0.16)})
    assert check(run_mcar, tmp_path).stderr.splitlines()[-1] == \
        "mcar check: 0 errors, 1 warning in 1 file"


def test_the_effective_separation_counts_the_multiplier_and_says_so(run_mcar, tmp_path):
    extra = "    wheel_separation_multiplier: 1.1\n"
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control(extra=extra)})
    (line,) = warnings(check(run_mcar, tmp_path), "W510")
    assert line == (f"{CONTROL}:5: warning: wheel_separation 0.16 m x "
                    "wheel_separation_multiplier 1.1 = 0.176 m effective, but the drive "
                    "wheels wheel_left_joint and wheel_right_joint are 0.16 m apart (+10.0%): "
                    "odometry and turning rates would be off [W510]")


def test_radius_and_wheel_names_are_compared(run_mcar, tmp_path):
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control(
        radius=0.03, left="wheel_right_joint", right="wheel_missing")})
    result = check(run_mcar, tmp_path)
    assert warnings(result, "W511") == [
        f"{CONTROL}:6: warning: wheel_radius 0.03 m, but the drive wheels' collision radius "
        "is 0.033 m (-9.1%): the robot would drive faster or slower than commanded [W511]"]
    assert warnings(result, "W512") == [
        f"{CONTROL}:3: warning: left_wheel_names names wheel_right_joint: it is the right "
        "wheel [W512]",
        f"{CONTROL}:4: warning: right_wheel_names names wheel_missing: the robot has no "
        "joint of that name [W512]"]


def test_a_matching_controller_and_another_robots_are_not_flagged(run_mcar, tmp_path):
    other = diff_control(separation=1.0, left="a", right="b").replace("diff_cont", "other")
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control() + other})
    result = check(run_mcar, tmp_path)
    assert result.returncode == 0, result.stderr
    assert "[W51" not in result.stderr and "[W208]" in result.stderr


def test_a_skid_steer_effective_separation_may_be_larger_not_smaller(run_mcar, tmp_path):
    names = {"left": "front_left_wheel_joint, rear_left_wheel_joint",
             "right": "front_right_wheel_joint, rear_right_wheel_joint"}
    larger = diff_control(separation=0.9, radius=0.1, **names)  # track 0.45, scrubbing
    write_package(tmp_path, skid_steer(), {CONTROL: larger})
    assert "[W510]" not in check(run_mcar, tmp_path).stderr
    smaller = diff_control(separation=0.4, radius=0.1, **names)
    write_package(tmp_path, skid_steer(), {CONTROL: smaller})
    (line,) = warnings(check(run_mcar, tmp_path), "W510")
    assert line.startswith(f"{CONTROL}:5: warning: wheel_separation 0.4 m, but the drive "
                           "wheels front_left_wheel_joint, rear_left_wheel_joint and ")


def test_a_package_without_ros_yaml_is_checked_without_mujoco(tmp_path):
    """The comparison looks for the YAML and, finding none, builds nothing: the start-up
    tests' way of listing what a run imported."""
    write_package(tmp_path, two_wheeler(), {"bot_control/package.xml": "",
                                            "bot_control/config/readme.txt": "no yaml"})
    (tmp_path / "bot_control" / "package.xml").unlink()
    main = "import sys; from mobile_car.cli.main import main; sys.argv[0] = 'mcar'; main()"

    def imported(*extra):
        env = {k: v for k, v in os.environ.items()
               if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}
        done = subprocess.run([sys.executable, "-X", "importtime", "-c", main, "check", "-q",
                               "bot_description/robot.urdf", "--package-path", tmp_path],
                              cwd=tmp_path, env=env, capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stderr
        return {line.split("|")[-1].strip().split(".")[0] for line in done.stderr.splitlines()
                if line.startswith("import time:") and "|" in line}

    assert "mujoco" not in imported()
    # control: with a controller to compare, the drive is found with MuJoCo
    write_package(tmp_path, two_wheeler(), {CONTROL: diff_control()})
    assert "mujoco" in imported()


@pytest.fixture(scope="module")
def two_wheeler_model(tmp_path_factory):
    """A two-wheeler whose bot_navigation package exists before it is loaded (the package
    search is made once, at loading); each test writes the YAML it needs there."""
    root = tmp_path_factory.mktemp("nav")
    robot = write_package(root, two_wheeler(), {"bot_navigation/params/nav2.yaml": "{}\n"})
    return root, checked_and_model(robot, root)


def body(outline, radius):
    return Section("body", [Figure("body.footprint", "f", outline, "m", ""),
                            Figure("body.radius.circumscribed", "r", radius, "m", "")])


NAV2 = """local_costmap:
  local_costmap:
    ros__parameters:
      {key}: {value}
"""
OUTLINE = [[0.1, -0.06], [0.1, 0.06], [-0.1, 0.06], [-0.1, -0.06]]


@pytest.mark.parametrize("key, value, expected", [
    ("footprint", '"[[0.1, -0.06], [0.1, 0.06], [-0.1, 0.06], [-0.1, -0.06]]"', None),
    ("footprint", '"[[0.08, -0.06], [0.08, 0.06], [-0.1, 0.06], [-0.1, -0.06]]"',
     "bot_navigation/params/nav2.yaml:4: warning: footprint leaves part of the robot out: "
     "its outline reaches (0.100, -0.060) m, 20 mm outside (body.footprint, collision "
     "geometry at rest) [W513]"),
    ("robot_radius", "0.117", None),
    ("robot_radius", "0.1",
     "bot_navigation/params/nav2.yaml:4: warning: robot_radius 0.1 m, but the robot reaches "
     "0.117 m from its root (body.radius.circumscribed): Nav2 would plan paths it cannot "
     "fit through [W513]"),
], ids=["footprint-ok", "footprint-short", "radius-ok", "radius-short"])
def test_nav2_footprint_or_radius_smaller_than_the_robot(two_wheeler_model, key, value,
                                                         expected, monkeypatch):
    root, (checked, sim) = two_wheeler_model
    monkeypatch.chdir(root)
    write_package(root, two_wheeler(), {"bot_navigation/params/nav2.yaml":
                                        NAV2.format(key=key, value=value)})
    found = find_package_yaml(checked.loaded)
    diagnostics, _ = compare(found, checked, sim, [body(OUTLINE, 0.1166)])
    assert [d.text() for d in diagnostics] == ([expected] if expected else [])


FILTERS = """scan_to_scan_filter_chain:
  ros__parameters:
    filter1:
      name: rear
      type: laser_filters/LaserScanAngularBoundsFilterInPlace
      params:
        lower_angle: {lower}
        upper_angle: 3.1416
"""


@pytest.mark.parametrize("lower, flagged", [(2.9, False), (3.0, True)])
def test_laser_filter_bounds_must_cover_the_blocked_sector(two_wheeler_model, monkeypatch,
                                                           lower, flagged):
    root, (checked, sim) = two_wheeler_model
    monkeypatch.chdir(root)
    write_package(root, two_wheeler(), {"bot_navigation/config/filters.yaml":
                                        FILTERS.format(lower=lower)})
    sensors = Section("sensors", [Figure("sensors.lidar.blocked", "b", [[170, 180]], "deg",
                                         "")])
    diagnostics, _ = compare(find_package_yaml(checked.loaded), checked, sim, [sensors])
    texts = [d.text() for d in diagnostics]
    assert texts == (["bot_navigation/config/filters.yaml:5: warning: no angular bounds "
                      "filter covers lidar's blocked sector 2.967..3.142 rad (170.0..180.0 "
                      "deg): the robot's own body stays in its scans [W514]"] if flagged
                     else [])


def test_an_edited_controller_yaml_is_compared_again_not_read_back(run_mcar, tmp_path):
    """A .xacro's check is recorded and read back while nothing it depends on changed;
    the package's controller YAML is among those files."""
    robot = two_wheeler().replace('<robot name="two_wheeler">',
                                  '<robot name="two_wheeler" '
                                  'xmlns:xacro="http://www.ros.org/wiki/xacro">')
    write_package(tmp_path, robot, {CONTROL: diff_control()})
    (tmp_path / "bot_description" / "robot.urdf").rename(
        tmp_path / "bot_description" / "robot.urdf.xacro")
    env = {"MCAR_CACHE_DIR": str(tmp_path / "cache")}

    def run():
        return run_mcar("check", "-q", "bot_description/robot.urdf.xacro", "--package-path",
                        tmp_path, cwd=tmp_path, env=env)

    assert "[W510]" not in run().stderr
    assert "[W510]" not in run().stderr  # (read back)
    (tmp_path / CONTROL).write_text(diff_control(separation=0.176))
    assert len(warnings(run(), "W510")) == 1


def test_a_control_package_added_beside_the_robots_is_compared(run_mcar, tmp_path):
    """A record made while the package had no sibling control package is not read back
    once one appears beside it."""
    robot = two_wheeler().replace('<robot name="two_wheeler">',
                                  '<robot name="two_wheeler" '
                                  'xmlns:xacro="http://www.ros.org/wiki/xacro">')
    write_package(tmp_path, robot, {})
    (tmp_path / "bot_description" / "robot.urdf").rename(
        tmp_path / "bot_description" / "robot.urdf.xacro")
    env = {"MCAR_CACHE_DIR": str(tmp_path / "cache")}

    def run():
        return run_mcar("check", "-q", "bot_description/robot.urdf.xacro", "--package-path",
                        tmp_path, cwd=tmp_path, env=env)

    assert "[W510]" not in run().stderr
    control = tmp_path / CONTROL
    control.parent.mkdir(parents=True)
    control.write_text(diff_control(separation=0.176))
    (tmp_path / "bot_control" / "package.xml").write_text(PACKAGE_XML.format("bot_control"))
    assert len(warnings(run(), "W510")) == 1


@pytest.mark.parametrize("robot", ["irobot_create_description/urdf/create3.urdf.xacro",
                                   "husky_description/urdf/husky.urdf.xacro",
                                   "steer_bot_description/urdf/steer_bot.urdf.xacro"])
def test_released_packages_own_yaml_agrees_with_their_robots(robot):
    """Create 3's control.yaml gives wheel_separation 0.233 and wheel_radius 0.03575, as
    its URDF; Husky's gives only a multiplier; steer_bot's ROS 1 ackermann controller a
    wheel_separation_h (its wheelbase) and radius: each read, none flagged."""
    from sim.test_sim_real_robots import FOLDER

    if FOLDER is None:
        pytest.skip("the shared real-robots folder is absent")
    from mobile_car.check.checker import check_input
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.specs.stack_check import resting_model

    checked = check_input(RobotInput(FOLDER / robot), LoadOptions(package_paths=[FOLDER]))
    found = find_package_yaml(checked.loaded)
    assert found.controllers and found.read
    assert compare(found, checked, resting_model(checked), [])[0] == []


MECANUM = """mecanum_drive_controller:
  ros__parameters:
    front_left_wheel_command_joint_name: front_left_wheel_joint
    front_right_wheel_command_joint_name: front_right_wheel_joint
    rear_left_wheel_command_joint_name: rear_left_wheel_joint
    rear_right_wheel_command_joint_name: {rear_right}
    kinematics:
      wheels_radius: {radius}
      sum_of_robot_center_projection_on_X_Y_axis: {lx_ly}
"""


def test_a_mecanum_controllers_kinematics_and_names(run_mcar, tmp_path):
    from sim.robot_makers import mecanum

    good = MECANUM.format(rear_right="rear_right_wheel_joint", radius=0.06, lx_ly=0.4)
    write_package(tmp_path, mecanum(), {CONTROL: good})
    assert "[W51" not in check(run_mcar, tmp_path).stderr
    bad = MECANUM.format(rear_right="rear_left_wheel_joint", radius=0.066, lx_ly=0.44)
    write_package(tmp_path, mecanum(), {CONTROL: bad})
    result = check(run_mcar, tmp_path)
    assert [line for line in result.stderr.splitlines() if "[W51" in line] == [
        f"{CONTROL}:6: warning: rear_right_wheel_command_joint_name names "
        "rear_left_wheel_joint: it is the rear left wheel [W512]",
        f"{CONTROL}:8: warning: wheels_radius 0.066 m, but the drive wheels' collision radius "
        "is 0.06 m (+10.0%): the robot would drive faster or slower than commanded [W511]",
        f"{CONTROL}:9: warning: sum_of_robot_center_projection_on_X_Y_axis 0.44 m, but the "
        "wheels stand 0.4 m from the root frame along x plus along y (+10.0%) [W510]"]


def test_check_takes_the_outline_from_specs_outline(cli, tmp_path, monkeypatch):
    """check's W513 asks specs' outline module (body.footprint's) for the robot's outline
    and radius (here a stand-in giving a 0.3 m square and its 0.2121 m radius)."""
    import types

    fake = types.ModuleType("mobile_car.specs.outline")
    fake.footprint = lambda sim: [(0.15, -0.15), (0.15, 0.15), (-0.15, 0.15), (-0.15, -0.15)]
    fake.radii = lambda points: (max((x * x + y * y) ** 0.5 for x, y in points), 0.15)
    monkeypatch.setitem(sys.modules, "mobile_car.specs.outline", fake)
    monkeypatch.chdir(tmp_path)
    write_package(tmp_path, two_wheeler(), {
        CONTROL: diff_control(),
        "bot_navigation/params/nav2.yaml": NAV2.format(key="robot_radius", value="0.2")})
    result = cli("check", "-q", "bot_description/robot.urdf", "--package-path", tmp_path)
    assert result.exit_code == 0, result.stderr
    assert warnings(result, "W513") == [
        "bot_navigation/params/nav2.yaml:4: warning: robot_radius 0.2 m, but the robot "
        "reaches 0.212 m from its root (body.radius.circumscribed): Nav2 would plan paths it "
        "cannot fit through [W513]"]


def _naming(parameters: str) -> str:
    """The Gazebo plugin's <parameters>, as a robot names its controllers' file."""
    return ('<gazebo><plugin filename="gz_ros2_control-system" '
            'name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
            f"<parameters>{parameters}</parameters></plugin></gazebo>")


@pytest.mark.parametrize("named", ["{root}/bot_control/config/control.yaml",
                                   "package://bot_control/config/control.yaml", None])
def test_the_controller_file_the_robot_names_is_compared_not_its_siblings(
        run_mcar, tmp_path, named):
    """ROSbot's control package holds mecanum_drive_controller.yaml and
    diff_drive_controller.yaml, one per variant; its plain-wheeled URDF names the latter,
    whose figures match, and was warned about the former's wheel_radius."""
    variant = diff_control(radius=0.03).replace("diff_cont", "mecanum_cont")
    extra = "" if named is None else _naming(named.format(root=tmp_path))
    write_package(tmp_path, two_wheeler(extra=extra),
                  {CONTROL: diff_control(), "bot_control/config/variant.yaml": variant})
    # (not -q: it leaves notes out)
    result = run_mcar("check", "bot_description/robot.urdf", "--package-path", tmp_path,
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert warnings(result, "W511") == []
    # Named, the sibling is not read; named none, mcar cannot tell which file this robot
    # runs (no launch says): a note, not a warning (ROSbot 2 was warned at its defaults)
    expected = [] if named else [
        "bot_control/config/variant.yaml:6: note: wheel_radius 0.03 m, but the drive "
        "wheels' collision radius is 0.033 m (-9.1%): the robot would drive faster or "
        "slower than commanded [W511, if this variant runs it: the robot names none of "
        "bot_control/config/control.yaml, bot_control/config/variant.yaml in <parameters>, "
        "and no launch of the package chooses one by an argument of this build] [N405]"]
    assert warnings(result, "N405") == expected


# ROSbot 2's controller.launch.py, its choice of file and its xacro argument
LAUNCH = """from launch.substitutions import Command, LaunchConfiguration, PythonExpression


def generate_launch_description():
    variant = LaunchConfiguration("variant")
    name = PythonExpression(["'variant.yaml' if ", variant, " else 'control.yaml'"])
    description = Command(["xacro ", "robot.urdf", " variant:=", variant])
"""


@pytest.mark.parametrize("argument", [None, "variant:=true", "variant:=false"])
def test_the_controller_file_the_launch_picks_by_a_xacro_argument_is_compared(
        run_mcar, tmp_path, argument):
    """ROSbot 2 names no <parameters> at its default arguments: its launch loads
    mecanum_drive_controller.yaml if mecanum else diff_drive_controller.yaml, and builds
    the robot with mecanum:= the same. Each file is compared with the robot it goes with."""
    variant = diff_control(radius=0.03).replace("diff_cont", "mecanum_cont")
    robot = two_wheeler().replace(
        '<robot name="two_wheeler">', '<robot name="two_wheeler" xmlns:xacro='
        '"http://www.ros.org/wiki/xacro"><xacro:arg name="variant" default="false"/>')
    write_package(tmp_path, robot, {CONTROL: diff_control(separation=0.176),
                                    "bot_control/config/variant.yaml": variant,
                                    "bot_control/launch/controller.launch.py": LAUNCH})
    result = run_mcar("check", "bot_description/robot.urdf", *([argument] if argument else []),
                      "--package-path", tmp_path, cwd=tmp_path)  # (not -q: notes too)
    assert result.returncode == 0, result.stderr
    assert warnings(result, "N405") == []
    if argument == "variant:=true":
        assert warnings(result, "W510") == []
        assert warnings(result, "W511") == [
            "bot_control/config/variant.yaml:6: warning: wheel_radius 0.03 m, but the drive "
            "wheels' collision radius is 0.033 m (-9.1%): the robot would drive faster or "
            "slower than commanded [W511]"]
    else:
        assert warnings(result, "W511") == []
        assert [line.split(": warning:")[0] for line in warnings(result, "W510")] == [
            "bot_control/config/control.yaml:5"]
