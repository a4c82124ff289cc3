"""mcar sim: the bundled car and its variants pass drop, drive and spin; each broken
description fails the scenario that shows its fault, with a message naming it."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET

import pytest

ROBOT = "urdf/mobile_robot.xacro"


def _sim(cli, *args):
    return cli("sim", *args, terminal_width=200)


def _statuses(stdout: str) -> dict[str, str]:
    return dict(re.findall(r"^  (drop|drive|spin|lint)\s+(PASSED|FAILED|SKIPPED)", stdout,
                           re.MULTILINE))


@pytest.mark.parametrize("variant", [None, "small", "large"])
def test_the_bundled_car_and_its_variants_pass(cli, repo, monkeypatch, variant):
    monkeypatch.chdir(repo)
    args = ["--config", f"urdf/variants/{variant}.yaml"] if variant else []
    result = _sim(cli, ROBOT, *args)
    assert result.exit_code == 0, result.stderr
    assert _statuses(result.stdout) == {"drop": "PASSED", "drive": "PASSED", "spin": "PASSED"}
    assert "drive wheels wheel_left_joint (left), wheel_right_joint (right)" in result.stdout
    assert result.stderr.endswith("mcar sim: 3 passed, 0 failed, 0 skipped in 1 file\n")


def test_json_and_junit_carry_the_same_numbers(cli, repo, monkeypatch):
    monkeypatch.chdir(repo)
    document = json.loads(_sim(cli, ROBOT, "--format", "json").stdout)
    xml = _sim(cli, ROBOT, "--format", "junit").stdout
    (entry,) = document["files"]
    assert document["exit_code"] == 0 and entry["drive"]["track"] == 0.165
    cases = {case.get("name"): case for case in ET.fromstring(xml).iter("testcase")}
    assert sorted(cases) == ["drive", "drop", "lint", "spin"]
    for scenario in entry["scenarios"]:
        text = cases[scenario["name"]].find("system-out").text
        shown = dict(re.findall(r"^(.+?): (\S+) ", text, re.MULTILINE))
        assert len(shown) == len(scenario["figures"]) >= 2
        for figure in scenario["figures"]:
            assert float(shown[figure["name"]]) == pytest.approx(figure["value"], rel=1e-5)
            assert figure["ok"] is True


# (file to edit, text, replacement, failing scenario, words of its message)
BROKEN = {
    "wheel axis along x": ("urdf/wheel/wheel.xacro", '<axis xyz="0 1 0"/>', '<axis xyz="1 0 0"/>',
                           "drive", "wheel_left_joint turns about (1 0 0), not across the car"),
    "wheel lifted": ("urdf/mobile_robot.xacro", '<origin xyz="0 ${wheel_y} 0"/>',
                     '<origin xyz="0 ${wheel_y} 0.01"/>', "drop",
                     "its geometry leans it 3.47 deg (bound 2 deg): wheel_left_link is 10.00 mm "
                     "above the floor the other parts rest on"),
    "castor lower than the wheels": (
        "urdf/mobile_robot.xacro", '<origin xyz="${caster_x} 0 ${caster_z}"/>',
        '<origin xyz="${caster_x} 0 ${caster_z - 0.005}"/>', "drop",
        "its geometry leans it 2.39 deg (bound 2 deg): caster_link reaches 5.00 mm below "
        "the drive wheels"),
    "DiffDrive separation": (
        "urdf/mobile_robot.gazebo.xacro", "<wheel_separation>${track_width}<",
        "<wheel_separation>${track_width + 0.02}<", "lint",
        "urdf/mobile_robot.gazebo.xacro:36: error: DiffDrive wheel_separation 0.185 m, but the "
        "drive wheels wheel_left_joint and wheel_right_joint are 0.165 m apart"),
    "DiffDrive radius": (
        "urdf/mobile_robot.gazebo.xacro", "<wheel_radius>${wheel_radius}<",
        "<wheel_radius>${wheel_radius * 1.1}<", "lint",
        "error: DiffDrive wheel_radius 0.03575 m, but the drive wheels' collision radius is "
        "0.0325 m [E302]"),
    "DiffDrive joints swapped": (
        "urdf/mobile_robot.gazebo.xacro", "<left_joint>wheel_left_joint<",
        "<left_joint>wheel_right_joint<", "lint",
        "error: DiffDrive left_joint wheel_right_joint: is the right wheel (y = -0.0825 m) "
        "[E303]"),
    "drive joint with effort 0": (
        "urdf/wheel/wheel.xacro", 'effort="${motor_stall_torque}"', 'effort="0"', "drive",
        "drove short; likely cause: the motors' effort limit (wheel_left_joint 0 N·m, "
        "wheel_right_joint 0 N·m): at it for 3.00 s of 3.00 s; the wheels rolled 0.0000 m"),
}


@pytest.mark.parametrize("case", sorted(BROKEN))
def test_a_broken_description_fails_the_scenario_that_shows_it(cli, package_copy, monkeypatch,
                                                               case):
    name, old, new, scenario, message = BROKEN[case]
    path = package_copy / name
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))
    monkeypatch.chdir(package_copy)
    result = _sim(cli, ROBOT)
    assert result.exit_code == 1, result.output
    assert _statuses(result.stdout)[scenario] == "FAILED"
    assert message in result.stderr
    passed = {s for s, status in _statuses(result.stdout).items() if status == "PASSED"}
    if scenario in ("drop", "lint"):  # the car still drives and turns: only that fails
        assert passed == {"drive", "spin"} | ({"drop"} if scenario == "lint" else set())


def test_the_tutorial_car_runs_drop_only_and_says_why(cli, repo, monkeypatch):
    monkeypatch.chdir(repo)
    result = _sim(cli, "urdf/tutorial/04_xacro.xacro", "--format", "json")
    assert result.exit_code == 1
    (entry,) = json.loads(result.stdout)["files"]
    why = ("not a vehicle: no wheels (no continuous joint: joint_base_wheel1 (fixed), "
           "joint_base_wheel2 (fixed), joint_base_wheel3 (fixed), joint_base_wheel4 (fixed))")
    assert entry["why_no_drive"] == why
    statuses = {s["name"]: (s["status"], s["message"]) for s in entry["scenarios"]}
    assert statuses["drive"] == statuses["spin"] == ("skipped", why)
    assert statuses["drop"][0] == "failed"
    assert statuses["drop"][1].startswith("no link has <collision> geometry")


def test_scenarios_can_be_chosen(cli, repo, monkeypatch):
    monkeypatch.chdir(repo)
    result = _sim(cli, ROBOT, "--scenario", "spin")
    assert result.exit_code == 0
    assert _statuses(result.stdout) == {"spin": "PASSED"}


@pytest.mark.parametrize("args, message", [
    (["--scenario", "fly"], "fly: the scenarios are drop, drive, spin"),
    (["--left", "wheel_left_joint"], "--left and --right go together"),
    (["--left", "nope", "--right", "wheel_right_joint"], "--left/--right nope: the robot has "
                                                         "no joint of that name"),
    (["--record", "run.mp4"], "--record run.mp4: no MP4 encoder is available here"),
])
def test_usage_errors_exit_2(cli, repo, monkeypatch, args, message):
    monkeypatch.chdir(repo)
    result = _sim(cli, ROBOT, *args)
    assert result.exit_code == 2
    assert message in result.stderr


def test_named_drive_wheels_are_used(cli, repo, monkeypatch):
    monkeypatch.chdir(repo)
    result = _sim(cli, ROBOT, "--left", "wheel_left_joint", "--right", "wheel_right_joint",
                  "--scenario", "drop")
    assert result.exit_code == 0
    assert "drive wheels wheel_left_joint (left), wheel_right_joint (right)" in result.stdout


def test_a_package_simulates_only_its_vehicles_one_line_per_kind_of_skip(cli, repo,
                                                                         monkeypatch):
    monkeypatch.chdir(repo)
    result = _sim(cli, "urdf", "--scenario", "drop")
    skipped = [line for line in result.stderr.splitlines() if "not simulated" in line]
    # The eleven files without wheels on one line, named in the package's order ...
    assert skipped[0] == (
        "mcar: not simulated, not a vehicle: no wheels: 11 files: "
        "urdf/chassis/steps/01_plate.xacro, urdf/chassis/steps/02_brackets.xacro, "
        "urdf/chassis/steps/03_second_plate.xacro, urdf/chassis/test_chassis.urdf.xacro, "
        "urdf/laser/test_laser.urdf.xacro, urdf/motor/test_motor.urdf.xacro, "
        "urdf/tutorial/01_skeleton.urdf, urdf/tutorial/02_visual.urdf, "
        "urdf/tutorial/03_color.urdf, urdf/tutorial/04_xacro.xacro, "
        "urdf/wheel_castor/test_wheel_castor.urdf.xacro")
    # ... and the wheel pair's test file, drive wheels on a bare base_link: a part.
    assert skipped[1] == (
        "mcar: urdf/wheel/test_wheel.urdf.xacro: not simulated: not a vehicle: nothing but "
        "its wheels to stand on (only wheel_left_link, wheel_right_link have collision "
        "geometry, no castor or body)")
    assert len(skipped) == 2
    assert result.stdout.count("  drop   PASSED") == 1
    assert "urdf/mobile_robot.xacro (mobile_robot)" in result.stdout
    assert result.exit_code == 0, result.stderr


def test_a_car_whose_castor_is_set_too_high_is_still_simulated_in_a_package(
        cli, package_copy, monkeypatch):
    # Its castor is off the floor, but it is a vehicle: drop fails it, it is not skipped.
    path = package_copy / "urdf/mobile_robot.xacro"
    old = '<origin xyz="${caster_x} 0 ${caster_z}"/>'
    assert old in path.read_text()
    path.write_text(path.read_text().replace(old, old.replace("}\"", " + 0.01}\"")))
    monkeypatch.chdir(package_copy)
    result = _sim(cli, "urdf", "--scenario", "drop")
    assert result.exit_code == 1
    assert _statuses(result.stdout) == {"drop": "FAILED"}
    assert "mobile_robot.xacro: error: drop failed:" in result.stderr


def test_a_root_without_mass_is_reported_at_its_line(cli, repo, monkeypatch):
    monkeypatch.chdir(repo)
    result = _sim(cli, "urdf/wheel/test_wheel.urdf.xacro")
    assert result.exit_code == 1
    assert re.search(r"urdf/wheel/test_wheel.urdf.xacro:\d+: error: root link \w+ and the "
                     r"links fixed to it have no mass: .* \[E305\]", result.stderr)


def test_the_summary_counts_the_files_that_could_not_be_simulated(cli, package_copy,
                                                                 monkeypatch):
    """A value config.xacro refuses stops every robot of the package before sim: the
    summary says so, rather than "0 passed ... in 0 files" alone."""
    config = package_copy / "urdf/config.xacro"
    old = '<xacro:property name="wheel_radius" value="0.0325"/>'
    assert old in config.read_text()
    config.write_text(config.read_text().replace(old, old.replace("0.0325", "32.5")))
    monkeypatch.chdir(package_copy)
    result = _sim(cli, "urdf/mobile_robot.xacro", "urdf/wheel/test_wheel.urdf.xacro",
                  "--scenario", "drop")
    assert result.exit_code == 1
    assert "outside its own range" in result.stderr
    assert result.stderr.endswith(
        "mcar sim: 0 passed, 0 failed, 0 skipped in 0 files; 2 files not simulated: their "
        "load or check failed (above)\n")
