"""The stack's fragments (mobile_car/specs/stack.py): Nav2's costmap parameters, the drive's
ros2_controllers controller by kind and ROS 2 release, laser_filters' bounds, and the
files ``--stack DIR`` writes, each loading with yaml.safe_load. The body, statics and
sensors figures are given as specs-core and the other parts compute them (Sections made
here); the drive is sim's, of robots written in tmp_path."""

from __future__ import annotations

import click
import pytest
import yaml
from click.testing import CliRunner
from sim.robot_makers import ackermann, mecanum, two_wheeler
from sim.test_sim_real_robots import FOLDER, needs_folder
from specs.stack_package import checked_and_model, write_package

from mobile_car.errors import InputError, UsageError
from mobile_car.specs.figures import Figure, Section
from mobile_car.specs.stack import (
    controller_fragment,
    laser_filters_fragment,
    nav2_fragment,
    stack_documents,
    write_stack,
    yaml_text,
)

FOOTPRINT = [[0.12341, -0.0701], [0.12341, 0.0701], [-0.0952, 0.0701], [-0.0952, -0.0701]]


def body(radius=0.15391, footprint=FOOTPRINT, **more):
    figures = [Figure("body.footprint", "footprint", footprint, "m", "collision geometry"),
               Figure("body.radius.circumscribed", "radius", radius, "m", "footprint")]
    figures += [Figure(key, key, value, "", "test") for key, value in more.items()]
    return Section("body", figures)


def statics(top_speed):
    return Section("statics", [Figure("statics.top_speed", "top speed", top_speed, "m/s", "")])


@pytest.fixture(scope="module")
def models(tmp_path_factory):
    """kind -> (CheckResult, SimModel) of a two-wheeler, an Ackermann car, a mecanum base."""
    found = {}
    for kind, robot in (("differential", two_wheeler()), ("ackermann", ackermann()),
                        ("mecanum", mecanum())):
        root = tmp_path_factory.mktemp(kind)
        found[kind] = checked_and_model(write_package(root, robot, {}), root)
    return found


def test_nav2_fragment_nests_as_nav2_params_and_rounds_outward():
    fragment = nav2_fragment([body()])
    expected = {"footprint": "[[0.124, -0.071], [0.124, 0.071], [-0.096, 0.071], "
                             "[-0.096, -0.071]]",
                "robot_radius": 0.154}
    assert fragment == {"local_costmap": {"local_costmap": {"ros__parameters": expected}},
                        "global_costmap": {"global_costmap": {"ros__parameters": expected}}}
    text = yaml_text(["h"], fragment)
    assert yaml.safe_load(text) == fragment
    # Nav2 reads the footprint as a string holding a list (it parses it itself)
    assert yaml.safe_load(expected["footprint"])[0] == [0.124, -0.071]


def test_nav2_fragment_is_empty_without_body_figures():
    assert nav2_fragment([Section("body")]) == {}


def test_differential_controller_has_the_wheels_geometry_and_limits(models):
    _, sim = models["differential"]
    sections = [body(), statics(0.5)]
    fragment = controller_fragment(sections, sim)
    assert fragment["controller_manager"] == {"ros__parameters": {"diff_drive_controller": {
        "type": "diff_drive_controller/DiffDriveController"}}}
    params = fragment["diff_drive_controller"]["ros__parameters"]
    assert params == {"left_wheel_names": ["wheel_left_joint"],
                      "right_wheel_names": ["wheel_right_joint"],
                      "wheel_separation": 0.16, "wheel_radius": 0.033,
                      "linear": {"x": {"max_velocity": 0.5, "min_velocity": -0.5}},
                      "angular": {"z": {"max_velocity": 6.25, "min_velocity": -6.25}}}
    humble = controller_fragment(sections, sim, "humble")["diff_drive_controller"]
    assert humble["ros__parameters"]["wheels_per_side"] == 1
    assert humble["ros__parameters"]["linear"]["x"]["has_velocity_limits"] is True


def test_a_figure_from_the_sections_wins_over_sims_drive(models):
    _, sim = models["differential"]
    fragment = controller_fragment([body(**{"wheels.radius": 0.04, "wheels.track": 0.2})], sim)
    params = fragment["diff_drive_controller"]["ros__parameters"]
    assert (params["wheel_radius"], params["wheel_separation"]) == (0.04, 0.2)
    assert "linear" not in params  # no statics.top_speed: no limits invented


def test_ackermann_controller_names_by_release(models):
    _, sim = models["ackermann"]
    jazzy = controller_fragment([], sim)["ackermann_steering_controller"]["ros__parameters"]
    assert jazzy == {"traction_joints_names": ["rear_right_wheel_joint", "rear_left_wheel_joint"],
                     "steering_joints_names": ["front_right_steering_joint",
                                               "front_left_steering_joint"],
                     "wheelbase": 0.5, "traction_track_width": 0.4,
                     "steering_track_width": 0.4, "traction_wheels_radius": 0.08}
    humble = controller_fragment([], sim, "humble")["ackermann_steering_controller"]
    assert humble["ros__parameters"] == {
        "front_steering": True,
        "rear_wheels_names": ["rear_right_wheel_joint", "rear_left_wheel_joint"],
        "front_wheels_names": ["front_right_steering_joint", "front_left_steering_joint"],
        "wheelbase": 0.5, "front_wheel_track": 0.4, "rear_wheel_track": 0.4,
        "front_wheels_radius": 0.08, "rear_wheels_radius": 0.08}


def test_mecanum_controller_uses_its_own_parameter_names(models):
    _, sim = models["mecanum"]
    fragment = controller_fragment([], sim)
    assert fragment["controller_manager"]["ros__parameters"] == {"mecanum_drive_controller": {
        "type": "mecanum_drive_controller/MecanumDriveController"}}
    params = fragment["mecanum_drive_controller"]["ros__parameters"]
    assert params == {"front_left_wheel_command_joint_name": "front_left_wheel_joint",
                      "rear_left_wheel_command_joint_name": "rear_left_wheel_joint",
                      "front_right_wheel_command_joint_name": "front_right_wheel_joint",
                      "rear_right_wheel_command_joint_name": "rear_right_wheel_joint",
                      "kinematics": {"base_frame_offset": {"x": 0.0, "y": 0.0, "theta": 0.0},
                                     "wheels_radius": 0.06,
                                     "sum_of_robot_center_projection_on_X_Y_axis": 0.4}}


def test_no_drive_no_controller():
    class Undriven:
        drive = None
    assert controller_fragment([body()], Undriven()) == {}


def test_laser_filters_keep_the_scans_own_angles():
    """A 0..360° scan (TurtleBot3's LDS) blocked across its rear keeps its angles: the
    filter compares the reading's own angle, so a bound at -170° would remove nothing."""
    sensors = Section("sensors", [
        Figure("sensors.lidar.blocked", "blocked", [[30, 40], [170, 190]], "deg", "rays"),
        Figure("sensors.lidar.range", "range", [0.1, 8], "m", "")])
    fragment = laser_filters_fragment([sensors])
    chain = fragment["scan_to_scan_filter_chain"]["ros__parameters"]
    bounds = [(f["params"]["lower_angle"], f["params"]["upper_angle"]) for f in chain.values()]
    assert [f["type"] for f in chain.values()] == \
        ["laser_filters/LaserScanAngularBoundsFilterInPlace"] * 2
    assert bounds == [(0.523599, 0.698132), (2.96706, 3.316126)]
    assert yaml.safe_load(yaml_text([], fragment)) == fragment


def test_two_lidars_get_a_chain_each_and_an_unblocked_one_none():
    sensors = Section("sensors", [
        Figure("sensors.front.blocked", "b", [[-100, -80]], "deg", ""),
        Figure("sensors.rear.blocked", "b", [[80, 100]], "deg", ""),
        Figure("sensors.top.blocked", "b", [], "deg", "")])
    assert sorted(laser_filters_fragment([sensors])) == ["front_filter_chain",
                                                         "rear_filter_chain"]
    assert laser_filters_fragment([Section("sensors")]) == {}


def test_stack_writes_each_file_loadable_and_never_over_an_input(models, tmp_path):
    _, sim = models["differential"]
    sensors = Section("sensors", [Figure("sensors.lidar.blocked", "b", [[150, 210]], "deg", "")])
    sections = [body(), statics(0.5), sensors]
    folder = tmp_path / "stack"
    written = write_stack(folder, sections, sim)
    assert sorted(p.name for p in written) == ["controllers.yaml", "laser_filters.yaml",
                                               "nav2.yaml"]
    documents = stack_documents(sections, sim)
    for path in written:
        assert yaml.safe_load(path.read_text()) == documents[path.name][1]
        assert path.read_text().startswith("# ")
    earlier = (folder / "nav2.yaml").read_bytes()
    with pytest.raises(UsageError) as error:
        write_stack(folder, [body(radius=0.3)], sim, inputs=[folder / "nav2.yaml"])
    assert error.value.message.startswith("would overwrite ")
    assert "nav2.yaml, a file this run read (the package's own YAML)" in error.value.message
    assert (folder / "nav2.yaml").read_bytes() == earlier
    # a file where the folder should be: one error, nothing half-written
    blocked = tmp_path / "plain_file"
    blocked.write_text("kept")
    with pytest.raises(InputError):
        write_stack(blocked, sections, sim)
    assert blocked.read_text() == "kept"


def test_the_stack_option_writes_through_the_library(models, tmp_path):
    from mobile_car.cli.specs_stack import stack_options, write_stack_files

    checked, sim = models["differential"]

    @click.command()
    @stack_options
    def command(stack_dir, stack_distro):
        write_stack_files(stack_dir, stack_distro, [body(), statics(0.5)], sim, checked)

    result = CliRunner().invoke(command, ["--stack", str(tmp_path / "out"), "--stack-distro",
                                          "humble"])
    assert result.exit_code == 0, result.output
    assert "wrote " in result.stderr and "controllers.yaml" in result.stderr
    params = yaml.safe_load((tmp_path / "out" / "controllers.yaml").read_text())
    assert params["diff_drive_controller"]["ros__parameters"]["wheels_per_side"] == 1
    assert CliRunner().invoke(command, []).exit_code == 0  # no --stack: nothing written


@needs_folder
@pytest.mark.parametrize("robot, track, radius, multiplier, line", [
    ("husky", 0.5708, 0.1651, 1.875, 26), ("jackal", 0.37559, 0.098, 1.5, 25)])
def test_husky_and_jackal_match_their_shipped_controller(robot, track, radius, multiplier,
                                                         line):
    """Their control.yaml gives no wheel_separation nor radius: the ROS 1 controller takes
    them from the URDF, and the multiplier the package ships is carried over and said."""
    from mobile_car.check.checker import check_input
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.specs.stack_check import resting_model

    source = FOLDER / f"{robot}_description" / "urdf" / f"{robot}.urdf.xacro"
    checked = check_input(RobotInput(source), LoadOptions(package_paths=[FOLDER]))
    sim = resting_model(checked)
    header, document = stack_documents([], sim, control=sim.control)["controllers.yaml"]
    params = document["diff_drive_controller"]["ros__parameters"]
    assert params["wheel_separation"] == pytest.approx(track, abs=1e-6)
    assert params["wheel_radius"] == pytest.approx(radius, abs=1e-6)
    assert params["wheel_separation_multiplier"] == multiplier
    assert params["left_wheel_names"] == ["front_left_wheel", "rear_left_wheel"]
    assert header[1].endswith(f"{robot}_control/config/control.yaml:{line}): effective "
                              f"{track * multiplier:.4f} m")
    assert yaml.safe_load(yaml_text(header, document)) == document


def test_the_stack_section_says_the_effective_separation_and_compares_the_package(tmp_path,
                                                                                monkeypatch):
    """mcar specs' stack section (specs-core's SpecsContext: checked, sim, body)."""
    from types import SimpleNamespace

    from specs.stack_package import DIFF_CONTROL

    from mobile_car.specs.stack import section

    control = DIFF_CONTROL.format(left="wheel_left_joint", right="wheel_right_joint",
                                  separation=0.16, radius=0.03)
    control += "    wheel_separation_multiplier: 1.25\n"
    monkeypatch.chdir(tmp_path)
    robot = write_package(tmp_path, two_wheeler(), {"bot_control/config/control.yaml": control})
    checked, sim = checked_and_model(robot, tmp_path)
    sim.control = None  # (sim reads the multiplier of a skid-steer robot only: specs reads it)
    result = section(SimpleNamespace(checked=checked, sim=sim, body=body(), options={},
                                     sections=[body()]))
    (figure,) = result.figures
    assert (figure.key, figure.value, figure.unit) == ("stack.wheel_separation", 0.2, "m")
    assert figure.source == ("the drive wheels' spacing (wheels.track) x "
                             "wheel_separation_multiplier 1.25 "
                             "(bot_control/config/control.yaml:7)")
    assert [d.text() for d in result.diagnostics] == [
        "bot_control/config/control.yaml:5: warning: wheel_separation 0.16 m x "
        "wheel_separation_multiplier 1.25 = 0.2 m effective, but the drive wheels "
        "wheel_left_joint and wheel_right_joint are 0.16 m apart (+25.0%): odometry and "
        "turning rates would be off [W510]",
        "bot_control/config/control.yaml:6: warning: wheel_radius 0.03 m, but the drive "
        "wheels' collision radius is 0.033 m (-9.1%): the robot would drive faster or slower "
        "than commanded [W511]"]
