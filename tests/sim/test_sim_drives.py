"""mcar sim's drive kinds on robots made at test time (tests/sim/robot_makers.py): a
four- and a six-wheel skid-steer robot, an Ackermann car driven by its rear wheels and one
driven by all four (a <transmission> on each), a mecanum base with roller links (plain
cylinders: test_sim_mecanum.py). Each is named with its wheel groups and proven by its
own scenarios against figures the test computes from the geometry it chose; --drive and
--left/--right pick what the tree allows, and refuse what it does not."""

from __future__ import annotations

import json
import math

import pytest
from sim.robot_makers import ackermann, mecanum, skid_multiplier, skid_steer, turning_radius

SKID = {"wheelbase": 0.4, "track": 0.45, "radius": 0.1}
CAR = {"wheelbase": 0.5, "track": 0.4, "radius": 0.08}


@pytest.fixture(scope="module")
def robots(tmp_path_factory):
    folder = tmp_path_factory.mktemp("drives")
    texts = {"skid4": skid_steer(**SKID), "skid6": skid_steer(3, **SKID),
             "car": ackermann(**CAR), "car4wd": ackermann(transmissions=True, **CAR),
             "mecanum": mecanum()}
    paths = {}
    for name, text in texts.items():
        paths[name] = folder / f"{name}.urdf"
        paths[name].write_text(text)
    return paths


@pytest.fixture(scope="module")
def reports(robots):
    """name -> (exit code, stderr, the JSON entry), each robot simulated once."""
    from click.testing import CliRunner
    from mobile_car.cli.main import main

    found = {}
    for name, path in robots.items():
        result = CliRunner().invoke(main, ["sim", str(path), "--format", "json"],
                                    catch_exceptions=False)
        found[name] = (result.exit_code, result.stderr, json.loads(result.stdout)["files"][0])
    return found


def figures(entry) -> dict[str, dict[str, float]]:
    return {s["name"]: {f["name"]: f["value"] for f in s["figures"]} for s in entry["scenarios"]}


@pytest.mark.parametrize("name, left, right", [
    ("skid4", ["front_left_wheel_joint", "rear_left_wheel_joint"],
     ["front_right_wheel_joint", "rear_right_wheel_joint"]),
    ("skid6", ["front_left_wheel_joint", "middle_left_wheel_joint", "rear_left_wheel_joint"],
     ["front_right_wheel_joint", "middle_right_wheel_joint", "rear_right_wheel_joint"]),
])
def test_a_skid_steer_robot_drives_straight_and_turns_in_place(reports, name, left, right):
    code, stderr, entry = reports[name]
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["left"], drive["right"]) == ("skid-steer", left, right)
    assert drive["track"] == pytest.approx(SKID["track"])
    # A skid-steer robot's tyres slip: its default torque is the one that slips them.
    motor = drive["motors"][left[0]]
    assert motor["effort"] == pytest.approx(20.0 * 9.81 * 0.1 / len(left + right), rel=1e-3)
    assert motor["effort_from"].endswith(f"(mu·m·g·r / {len(left + right)}, skid-steer)")
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == \
        [("drop", "passed"), ("drive", "passed"), ("spin", "passed")]
    assert figures(entry)["drive"]["distance error"] < 5
    spin = figures(entry)["spin"]
    ideal = 2 * SKID["radius"] * drive["command_speed"] / SKID["track"]
    # Clockwise (left wheels forward), slower than a two-wheel robot, about its middle.
    assert 0.2 * ideal < spin["yaw rate"] < ideal
    assert spin["turning centre"] < 0.01


def test_spin_measures_the_multiplier_coulomb_friction_gives(reports):
    _, _, entry = reports["skid4"]
    spin = next(s for s in entry["scenarios"] if s["name"] == "spin")
    rate = next(f["value"] for f in spin["figures"] if f["name"] == "yaw rate")
    multiplier = 2 * SKID["radius"] * entry["drive"]["command_speed"] / SKID["track"] / rate
    # Equal loads, a, b half the wheelbase and track: (a² + b²) / b² = 1.79.
    assert multiplier == pytest.approx(skid_multiplier(SKID["wheelbase"], SKID["track"]),
                                       rel=0.08)
    assert spin["findings"] == [
        f"effective track {multiplier * SKID['track']:.4f} m = {multiplier:.3f} × the "
        f"0.4500 m between the wheels (wheel_separation_multiplier {multiplier:.3f})"]


@pytest.mark.parametrize("name, driven", [
    ("car", ["rear_left_wheel_joint", "rear_right_wheel_joint"]),
    ("car4wd", ["rear_left_wheel_joint", "front_left_wheel_joint", "rear_right_wheel_joint",
                "front_right_wheel_joint"]),
])
def test_an_ackermann_car_turns_on_the_circle_its_geometry_says(reports, name, driven):
    code, stderr, entry = reports[name]
    assert code == 0, stderr
    drive = entry["drive"]
    assert drive["kind"] == "ackermann"
    assert drive["steering"] == ["front_left_steering_joint", "front_right_steering_joint"]
    assert sorted(drive["left"] + drive["right"]) == sorted(driven)
    assert sorted(drive["free"]) == sorted(
        {"rear_left_wheel_joint", "rear_right_wheel_joint", "front_left_wheel_joint",
         "front_right_wheel_joint"} - set(driven))
    assert drive["wheelbase"] == pytest.approx(CAR["wheelbase"])
    assert drive["steering_angle_deg"] == pytest.approx(15)
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == \
        [("drop", "passed"), ("drive", "passed"), ("turn", "passed")]
    assert figures(entry)["drive"]["distance error"] < 5
    turn = next(s for s in entry["scenarios"] if s["name"] == "turn")
    detail = turn["figures"][0]["detail"]
    geometric = turning_radius(CAR["wheelbase"], 15)
    assert detail.endswith(f"of wheelbase / tan δ = 0.5000 m / tan 15.00° = {geometric:.4f} m")
    measured = float(detail.split(" m of ")[0])
    assert measured == pytest.approx(geometric, rel=0.10)


def test_the_text_report_names_the_groups_and_the_steering(cli, robots):
    result = cli("sim", robots["car"], "--scenario", "drop", terminal_width=200)
    assert result.exit_code == 0, result.stderr
    assert ("  ackermann drive wheels rear_left_wheel_joint (left), rear_right_wheel_joint "
            "(right), rolling free front_left_wheel_joint, front_right_wheel_joint; steering "
            "front_left_steering_joint, front_right_steering_joint: radius 0.08 m, track 0.4 m, "
            "wheelbase 0.5 m, command 6.25 rad/s") in result.stdout


def test_a_steering_angle_can_be_asked_for_within_the_joints_limits(cli, robots):
    result = cli("sim", robots["car"], "--scenario", "turn", "--steering-angle", "25",
                 "--format", "json")
    assert result.exit_code == 0, result.stderr
    (entry,) = json.loads(result.stdout)["files"]
    assert entry["drive"]["steering_angle_deg"] == pytest.approx(25)
    turn = entry["scenarios"][0]
    assert turn["figures"][0]["value"] < 10
    assert turn["figures"][1]["name"] == "steering error" and turn["figures"][1]["value"] < 1
    # The inner wheel would need atan(0.5 / (0.5 / tan 32° - 0.2)) = 39.8°, past the
    # joint's 0.6 rad (34.4°).
    far = cli("sim", robots["car"], "--scenario", "turn", "--steering-angle", "32")
    assert far.exit_code == 2
    assert ("--steering-angle 32: the inner wheel needs 39.8°, beyond "
            "front_left_steering_joint's limit of 34.4°") in far.stderr


def test_the_default_steering_angle_keeps_the_inner_wheel_within_its_limit(cli, tmp_path):
    path = tmp_path / "tight.urdf"
    path.write_text(ackermann(steer_limit=0.2, **CAR))  # 11.5° at most
    result = cli("sim", path, "--scenario", "turn", "--format", "json")
    assert result.exit_code == 0, result.stderr
    (entry,) = json.loads(result.stdout)["files"]
    delta = math.radians(entry["drive"]["steering_angle_deg"])
    radius = CAR["wheelbase"] / math.tan(delta)
    inner = math.degrees(math.atan(CAR["wheelbase"] / (radius - CAR["track"] / 2)))
    assert inner == pytest.approx(0.9 * math.degrees(0.2), rel=1e-3)


def test_drive_and_spin_do_not_fit_every_kind(cli, robots):
    result = cli("sim", robots["car"], "--scenario", "spin", "--format", "json")
    (entry,) = json.loads(result.stdout)["files"]
    assert entry["scenarios"][0]["status"] == "skipped"
    assert entry["scenarios"][0]["message"] == ("an Ackermann car does not turn in place: turn "
                                                "proves its steering")
    result = cli("sim", robots["skid4"], "--scenario", "turn", "--format", "json")
    (entry,) = json.loads(result.stdout)["files"]
    assert entry["scenarios"][0]["message"] == ("turn steers an Ackermann car: spin proves a "
                                                "skid-steer robot's turning")


def test_drive_picks_a_kind_the_tree_allows(cli, robots):
    # The car driven on all four wheels as skid-steer: its steering welded straight.
    result = cli("sim", robots["car"], "--drive", "skid-steer", "--scenario", "drive",
                 "--format", "json")
    assert result.exit_code == 0, result.stderr
    (entry,) = json.loads(result.stdout)["files"]
    assert (entry["drive"]["kind"], entry["drive"]["chosen"]) == ("skid-steer", "--drive")
    assert entry["drive"]["steering"] == [] and len(entry["drive"]["left"]) == 2
    assert entry["held"] == ["front_left_steering_joint", "front_right_steering_joint"]
    # Two of the skid-steer robot's wheels driven, the others rolling free.
    named = cli("sim", robots["skid4"], "--left", "rear_left_wheel_joint", "--right",
                "rear_right_wheel_joint", "--scenario", "drop", "--format", "json")
    assert named.exit_code == 0, named.stderr
    (entry,) = json.loads(named.stdout)["files"]
    assert (entry["drive"]["kind"], entry["drive"]["chosen"]) == ("differential",
                                                                  "--left/--right")
    assert sorted(entry["drive"]["free"]) == ["front_left_wheel_joint",
                                              "front_right_wheel_joint"]


@pytest.mark.parametrize("robot, args, message", [
    ("skid4", ["--drive", "ackermann"], "--drive ackermann: no steering joints: no revolute "
                                        "joint about an upright axis above a wheel"),
    ("skid4", ["--drive", "differential"], "--drive differential: 2 wheels on the left, 2 on "
                                           "the right; name the two driven ones with --left "
                                           "JOINT --right JOINT"),
    ("car", ["--left", "front_left_steering_joint", "--right", "rear_right_wheel_joint"],
     "--left/--right front_left_steering_joint: a steering joint (it turns "
     "front_left_wheel_joint) cannot drive a wheel"),
    ("skid4", ["--left", "front_left_wheel_joint,rear_left_wheel_joint", "--right",
               "front_right_wheel_joint", "--drive", "skid-steer"],
     "--drive skid-steer drives two or more wheels a side"),
])
def test_what_the_tree_does_not_allow_is_a_usage_error(cli, robots, robot, args, message):
    result = cli("sim", robots[robot], *args, "--scenario", "drop")
    assert result.exit_code == 2
    assert message in result.stderr


def test_a_mecanum_base_with_roller_links_is_driven_as_mecanum(reports):
    # Its two rollers a wheel make the kind plain (rollers on the wheels' rims) but no
    # rolling surface, nor an X pattern: the wheels grip at 45° in the usual X pattern.
    code, stderr, entry = reports["mecanum"]
    assert code == 0, stderr
    assert entry["drive"]["kind"] == "mecanum"
    assert entry["drive"]["declared"] == "rollers on the wheels' rims"
    assert entry["drive"]["grip_from"] == ("the usual X pattern (the roller links make no X "
                                           "or O pattern)")
    assert entry["drive"]["castors"] == []  # its rollers are its wheels', not castors
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == \
        [("drop", "passed"), ("drive", "passed"), ("strafe", "passed"), ("spin", "passed")]


PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')


def rover_package(root, control_yaml: str) -> None:
    """rover_description (a skid steer) and rover_control/config/control.yaml beside it."""
    for name in ("rover_description", "rover_control"):
        (root / name).mkdir()
        (root / name / "package.xml").write_text(PACKAGE_XML.format(name))
    (root / "rover_description" / "rover.urdf").write_text(skid_steer(**SKID))
    (root / "rover_control" / "config").mkdir()
    (root / "rover_control" / "config" / "control.yaml").write_text(control_yaml)
CONTROL_YAML = """# as diff_drive_controller reads it (ROS 2)
rover_base_controller:
  ros__parameters:
    left_wheel_names: ["front_left_wheel_joint", "rear_left_wheel_joint"]
    right_wheel_names: ["front_right_wheel_joint", "rear_right_wheel_joint"]
    wheel_separation: 0.45
    wheel_separation_multiplier: 1.7
other_robot_controller:
  ros__parameters:
    left_wheel_names: ["left_joint"]
    wheel_separation_multiplier: 3.0
"""


def test_spin_compares_with_the_multiplier_of_the_x_control_package(cli, tmp_path, monkeypatch):
    rover_package(tmp_path, CONTROL_YAML)
    (tmp_path / "rover_control" / "config" / "broken.yaml").write_text("a: [\n")
    monkeypatch.chdir(tmp_path)
    result = cli("sim", "rover_description/rover.urdf", "--package-path", tmp_path,
                 "--scenario", "spin", terminal_width=200)
    assert result.exit_code == 0, result.stderr
    findings = [line.strip() for line in result.stdout.splitlines()[-2:]]
    multiplier = float(findings[0].split("(wheel_separation_multiplier ")[1].rstrip(")"))
    off = 100 * (multiplier - 1.7) / 1.7
    # The controller that drives these wheels, not the other robot's in the same file.
    assert findings[1] == ("rover_control/config/control.yaml:7: wheel_separation_multiplier "
                           f"1.7; measured {abs(off):.1f}% {'over' if off >= 0 else 'under'} it")
    # A file that cannot be read is said, and fails nothing.
    assert "mcar: rover_description/rover.urdf: rover_control/config/broken.yaml: not read " \
           "(while parsing" in result.stderr


GZ_DIFF_DRIVE = """
  <gazebo><plugin filename="gz-sim-diff-drive-system" name="gz::sim::systems::DiffDrive">
    <left_joint>front_left_wheel_joint</left_joint><left_joint>{left}</left_joint>
    <right_joint>front_right_wheel_joint</right_joint>
    <right_joint>rear_right_wheel_joint</right_joint>
    <wheel_separation>0.8</wheel_separation><wheel_radius>0.1</wheel_radius>
  </plugin></gazebo>"""


def test_a_skid_steer_diff_drive_plugin_is_checked_per_wheel(cli, tmp_path):
    # gz-sim's DiffDrive takes a joint per wheel; a skid-steer robot's separation is its
    # effective track (0.8 m here, 1.8 x the wheels' 0.45 m): no E301 for that.
    good = tmp_path / "good.urdf"
    good.write_text(skid_steer(extra=GZ_DIFF_DRIVE.format(left="rear_left_wheel_joint"),
                               **SKID))
    result = cli("sim", good, "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert "[E30" not in result.stderr
    swapped = tmp_path / "swapped.urdf"
    swapped.write_text(skid_steer(extra=GZ_DIFF_DRIVE.format(left="rear_right_wheel_joint"),
                                  **SKID))
    result = cli("sim", swapped, "--scenario", "drop")
    assert result.exit_code == 1
    assert ("error: DiffDrive left_joint rear_right_wheel_joint: is the right wheel "
            "(y = -0.225 m) [E303]") in result.stderr
