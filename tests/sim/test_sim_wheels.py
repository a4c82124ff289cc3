"""Which wheels mcar sim drives, on robots made at test time (tests/sim/robot_makers.py):
what the package declares first (a Gazebo drive plugin, a controller in its control
package), a bicycle model's virtual joints standing for the real wheels, then the
geometry (a castor's upright swivel, a dummy wheel in the air are no wheels); the options
override both; where each wheel came from is in the report; a declaration naming a fixed
joint is a located error (E306); a placeholder speed limit is not driven at; and a vehicle
sim could not drive fails (exit 1) unless only drop was asked for."""

from __future__ import annotations

import pytest
from conftest import line_of
from sim.robot_makers import (
    ACKERMANN_CONTROLLER,
    bicycle_model,
    castor_swivels,
    diff_drive_plugin,
    dummy_wheel,
    tricycle,
    two_wheeler,
)
from sim.sim_json import sim

PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')
GEOMETRY = "geometry: a wheel that touches the floor"


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """name -> path of each robot, and the bicycle model in its description package
    beside a control package configuring ackermann_steering_controller (found on the
    package path, ``folder``)."""
    folder = tmp_path_factory.mktemp("wheels")
    texts = {"swivels": castor_swivels(), "dummy": dummy_wheel(),
             "tricycle": tricycle(), "bicycle_alone": bicycle_model(),
             "placeholder": two_wheeler(limit='<limit effort="1" velocity="200"/>'),
             "fixed_plugin": two_wheeler(extra=diff_drive_plugin("castor_1_joint",
                                                                 "wheel_right_joint")),
             "plugin": two_wheeler(extra=diff_drive_plugin("wheel_left_joint",
                                                           "wheel_right_joint"))}
    paths = {}
    for name, text in texts.items():
        paths[name] = folder / f"{name}.urdf"
        paths[name].write_text(text)
    for package in ("bike_description", "bike_control"):
        (folder / package / "config").mkdir(parents=True)
        (folder / package / "package.xml").write_text(PACKAGE_XML.format(package))
    (folder / "bike_control" / "config" / "ctrl_ackermann.yaml").write_text(
        ACKERMANN_CONTROLLER)
    paths["bicycle"] = folder / "bike_description" / "bike.urdf"
    paths["bicycle"].write_text(bicycle_model())
    paths["folder"] = folder
    return paths




def statuses(entry) -> dict[str, str]:
    return {s["name"]: s["status"] for s in entry["scenarios"]}


def test_castor_swivels_are_not_wheels_and_their_wheels_are_castors(cli, made):
    code, stderr, entry = sim(cli, made["swivels"])
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["left"], drive["right"]) == (
        "differential", ["left_wheel_joint"], ["right_wheel_joint"])
    assert drive["sources"] == {"left_wheel_joint": GEOMETRY, "right_wheel_joint": GEOMETRY}
    corners = ["back_left", "back_right", "front_left", "front_right"]
    assert drive["castors"] == [f"{c}_castor_link" for c in corners]
    assert drive["not_wheels"] == {
        f"{c}_castor_swivel_joint": "its axis stands upright (a swivel, not a wheel)"
        for c in ("front_left", "front_right", "back_left", "back_right")}
    assert statuses(entry) == {"drop": "passed", "drive": "passed", "spin": "passed"}


def test_a_dummy_wheel_in_the_air_is_not_driven(cli, made):
    code, stderr, entry = sim(cli, made["dummy"], "--scenario", "drop")
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["left"], drive["right"], drive["track"]) == (
        ["wheel_left_joint"], ["wheel_right_joint"], pytest.approx(0.16))
    assert drive["not_wheels"] == {
        "dummy_wheel_joint": "5.0 mm above the floor at rest (not a wheel)"}


def test_a_bicycle_models_virtual_joints_stand_for_the_real_wheels(cli, made):
    code, stderr, entry = sim(cli, made["bicycle"], "--scenario", "drop,drive",
                              "--package-path", made["folder"])
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"]) == ("ackermann", "declared")
    assert (drive["left"], drive["right"]) == (["rear_left_wheel_joint"],
                                               ["rear_right_wheel_joint"])
    assert drive["steering"] == ["front_left_steering_joint", "front_right_steering_joint"]
    yaml = made["folder"] / "bike_control" / "config" / "ctrl_ackermann.yaml"
    source = f"controller YAML {yaml}:4 (rear_wheel_joint stands for it)"
    assert drive["sources"] == {"rear_left_wheel_joint": source,
                                "rear_right_wheel_joint": source}
    assert drive["not_wheels"] == {
        "rear_wheel_joint": "75.0 mm above the floor at rest (not a wheel)"}
    assert statuses(entry) == {"drop": "passed", "drive": "passed"}


def test_the_text_report_says_where_the_wheels_came_from(cli, made, monkeypatch):
    monkeypatch.chdir(made["folder"])
    result = cli("sim", "bike_description/bike.urdf", "--scenario", "drop", "--package-path",
                 made["folder"])
    assert result.exit_code == 0, result.stderr
    assert ("  wheels rear_left_wheel_joint, rear_right_wheel_joint from controller YAML "
            "bike_control/config/ctrl_ackermann.yaml:4 (rear_wheel_joint stands for it)"
            ) in result.stdout.splitlines()
    result = cli("sim", "plugin.urdf", "--scenario", "drop")
    line = line_of(made["plugin"], "<plugin ")
    assert ("  wheels wheel_left_joint, wheel_right_joint from <gazebo> plugin "
            f"libgazebo_ros_diff_drive.so at plugin.urdf:{line}") in result.stdout.splitlines()


def test_the_options_override_the_declaration(cli, made):
    # --drive: the declared Ackermann car driven as skid-steer, its steering held.
    code, stderr, entry = sim(cli, made["bicycle"], "--drive", "skid-steer", "--scenario",
                              "drop", "--package-path", made["folder"])
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"], drive["steering"]) == ("skid-steer", "--drive", [])
    assert set(drive["sources"].values()) == {"--drive skid-steer"}
    assert len(drive["left"]) == len(drive["right"]) == 2
    # --left/--right: the wheels named, the others roll free.
    code, stderr, entry = sim(cli, made["bicycle"], "--left", "front_left_wheel_joint",
                              "--right", "front_right_wheel_joint", "--drive", "differential",
                              "--scenario", "drop", "--package-path", made["folder"])
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"]) == ("differential", "--left/--right")
    assert drive["sources"] == {"front_left_wheel_joint": "--left/--right",
                                "front_right_wheel_joint": "--left/--right"}
    assert sorted(drive["free"]) == ["rear_left_wheel_joint", "rear_right_wheel_joint"]


def test_without_its_control_package_the_bicycle_model_is_found_from_the_geometry(cli, made):
    code, stderr, entry = sim(cli, made["bicycle_alone"], "--scenario", "drop")
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"]) == ("ackermann", "found from the tree")
    assert drive["left"] == ["rear_left_wheel_joint"]
    assert "rear_wheel_joint" in drive["not_wheels"]


def test_a_plugin_naming_a_fixed_joint_is_a_located_error(cli, made, monkeypatch):
    monkeypatch.chdir(made["folder"])
    result = cli("sim", "fixed_plugin.urdf", "--scenario", "drop")
    assert result.exit_code == 1
    line = line_of(made["fixed_plugin"], "<left_joint>castor_1_joint")
    assert (f"fixed_plugin.urdf:{line}: error: differential drive declaration names joint "
            "castor_1_joint: a fixed joint: it cannot turn a wheel; the robot cannot be driven "
            "as its package says [E306]") in result.stderr.splitlines()
    assert "[E303]" not in result.stderr  # said once
    # The control: the same robot with the plugin naming its wheels has no error.
    result = cli("sim", "plugin.urdf", "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert "[E30" not in result.stderr


def test_a_placeholder_speed_limit_is_not_driven_at(cli, made):
    code, stderr, entry = sim(cli, made["placeholder"], "--scenario", "drive")
    assert code == 0, stderr
    drive = entry["drive"]
    motor = drive["motors"]["wheel_left_joint"]
    assert (motor["velocity"], motor["velocity_from"]) == (200, "joint <limit velocity>")
    # 200 rad/s on 33 mm wheels is 6.6 m/s at the rim: driven as if no limit were given.
    assert motor["placeholder"] == ("a placeholder: 200 rad/s is 6.6 m/s at the rim (r·ω, r "
                                    "0.033 m), over the 5 m/s no wheeled robot exceeds")
    assert drive["command_speed"] == 10.0
    # --speed overrides every source, the joint's <limit> included.
    code, stderr, entry = sim(cli, made["placeholder"], "--scenario", "drop", "--speed", "12")
    motor = entry["drive"]["motors"]["wheel_left_joint"]
    assert (motor["velocity"], motor["velocity_from"]) == (12, "--speed")
    assert "placeholder" not in motor and entry["drive"]["command_speed"] == 6.0


def test_a_vehicle_sim_cannot_drive_fails_unless_only_drop_was_asked(cli, made):
    code, stderr, entry = sim(cli, made["tricycle"])
    assert code == 1
    why = ("a wheel on the centre line (front_wheel_joint): not a drive kind mcar sim drives "
           "(differential, skid-steer, ackermann, mecanum, bicycle)")
    assert entry["why_no_drive"] == why
    assert [(s["name"], s["status"], s["message"]) for s in entry["scenarios"]] == [
        ("drop", "passed", "ok"), ("drive", "failed", f"cannot drive this vehicle: {why}"),
        ("spin", "failed", f"cannot drive this vehicle: {why}")]
    assert f"error: drive failed: cannot drive this vehicle: {why}" in stderr
    code, stderr, entry = sim(cli, made["tricycle"], "--scenario", "drop")
    assert code == 0, stderr
    assert statuses(entry) == {"drop": "passed"}


MCAR_YAML = """sim:
  drive:
    "urdf/dummy.urdf": {kind: differential, left: wheel_left_joint,
                        right: [wheel_right_joint]}
"""


@pytest.fixture
def rover_package(tmp_path):
    """A package whose mcar.yaml sets the drive of its robot (the dummy-wheel car)."""
    package = tmp_path / "rover_description"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text(PACKAGE_XML.format("rover_description"))
    (package / "urdf" / "dummy.urdf").write_text(dummy_wheel())
    (package / "mcar.yaml").write_text(MCAR_YAML)
    return package


def test_mcar_yaml_sets_the_drive_and_the_options_override_it(cli, rover_package,
                                                              monkeypatch, run_mcar):
    monkeypatch.chdir(rover_package)
    code, stderr, entry = sim(cli, "urdf/dummy.urdf", "--scenario", "drop")
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"]) == ("differential", "mcar.yaml:3 sim.drive")
    assert drive["sources"] == {"wheel_left_joint": "mcar.yaml:3 sim.drive",
                                "wheel_right_joint": "mcar.yaml:3 sim.drive"}
    code, stderr, entry = sim(cli, "urdf/dummy.urdf", "--scenario", "drop", "--left",
                              "wheel_right_joint", "--right", "wheel_left_joint")
    assert entry["drive"]["chosen"] == "--left/--right"
    # ci reads the same key and gives the same drive.
    result = run_mcar("ci", ".", "--no-render", "--build-dir", rover_package.parent / "build")
    assert result.returncode == 0, result.stderr
    assert " differential 3/3 " in result.stdout


@pytest.mark.parametrize("setting, message", [
    ('{left: nope_joint, right: wheel_right_joint}',
     "mcar.yaml:3: error: sim.drive: --left/--right nope_joint: the robot has no joint of "
     "that name"),
    ("{kind: hovercraft}", "mcar.yaml:3: error: sim.drive 'urdf/dummy.urdf': kind "
     "'hovercraft' is not one of differential, skid-steer, ackermann"),
    ("{left: wheel_left_joint}", "mcar.yaml:3: error: sim.drive 'urdf/dummy.urdf': left and "
     "right go together: name the drive joints of each side"),
])
def test_a_wrong_mcar_yaml_drive_is_a_located_usage_error(cli, rover_package, monkeypatch,
                                                          setting, message):
    (rover_package / "mcar.yaml").write_text(f'sim:\n  drive:\n    "urdf/dummy.urdf": '
                                             f'{setting}\n')
    monkeypatch.chdir(rover_package)
    result = cli("sim", "urdf/dummy.urdf", "--scenario", "drop")
    assert result.exit_code == 2
    assert message in result.stderr, result.stderr
