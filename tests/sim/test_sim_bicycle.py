"""A single-track vehicle (one steered wheel in front of an unsteered driven one, both on
the centre line: steer_bot's bicycle_bot) is the drive kind ``bicycle``, found from its
geometry or from the Ackermann controller its control package configures: drop, drive
with the steering held straight and turn on the circle wheelbase / tan δ, measured at
the rear wheel. It stands on its tyres' width: on the round tyres the other kinds roll on
it falls outward in the turn (the control below)."""

from __future__ import annotations

import json

import pytest
from sim.robot_makers import BICYCLE_CONTROLLER, ackermann, bicycle, tricycle
from sim.sim_json import sim

from mobile_car.sim import model as sim_model

PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')
GEOMETRY = "geometry: a wheel that touches the floor"
WHEELBASE = 0.4


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """name -> path: the bicycle alone, the same in a description package beside a
    control package configuring ackermann_steering_controller for its joints, an
    Ackermann car and a tricycle."""
    folder = tmp_path_factory.mktemp("bicycle")
    paths = {"alone": folder / "bike.urdf", "car": folder / "car.urdf",
             "tricycle": folder / "tricycle.urdf"}
    paths["alone"].write_text(bicycle(wheelbase=WHEELBASE))
    paths["car"].write_text(ackermann())
    paths["tricycle"].write_text(tricycle())
    for package in ("bike_description", "bike_control"):
        (folder / package / "config").mkdir(parents=True)
        (folder / package / "package.xml").write_text(PACKAGE_XML.format(package))
    paths["yaml"] = folder / "bike_control" / "config" / "ctrl_ackermann.yaml"
    paths["yaml"].write_text(BICYCLE_CONTROLLER)
    paths["declared"] = folder / "bike_description" / "bike.urdf"
    paths["declared"].write_text(bicycle(wheelbase=WHEELBASE))
    paths["folder"] = folder
    return paths


def figures(entry, scenario: str) -> dict[str, float]:
    found = next(s for s in entry["scenarios"] if s["name"] == scenario)
    return {f["name"]: f["value"] for f in found["figures"]}


@pytest.fixture(scope="module")
def found_run(made):
    from click.testing import CliRunner
    from mobile_car.cli.main import main
    result = CliRunner().invoke(main, ["sim", str(made["alone"]), "--format", "json"],
                                catch_exceptions=False)
    return result.exit_code, result.stderr, json.loads(result.stdout)["files"][0]


def test_a_single_track_is_a_bicycle_found_from_its_geometry(found_run):
    code, stderr, entry = found_run
    assert code == 0, stderr
    drive = entry["drive"]
    assert (drive["kind"], drive["chosen"]) == ("bicycle", "found from the tree")
    assert (drive["centre"], drive["left"], drive["right"]) == (["rear_wheel_joint"], [], [])
    assert (drive["free"], drive["steering"]) == (["front_wheel_joint"],
                                                  ["front_steering_joint"])
    assert drive["wheelbase"] == pytest.approx(WHEELBASE)
    assert drive["steering_angle_deg"] == pytest.approx(15)
    assert drive["sources"] == {"rear_wheel_joint": GEOMETRY}
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == [
        ("drop", "passed"), ("drive", "passed"), ("turn", "passed")]
    assert figures(entry, "drive")["distance error"] < 2
    turn = figures(entry, "turn")
    assert turn["radius error"] < 10 and turn["steering error"] < 1


def test_the_text_report_names_the_centre_line_wheels(cli, made):
    result = cli("sim", made["alone"], "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert ("  bicycle drive wheels rear_wheel_joint (centre line), rolling free "
            "front_wheel_joint; steering front_steering_joint: radius 0.05 m, wheelbase "
            "0.4 m, command 10 rad/s;") in result.stdout


def test_an_ackermann_controller_naming_a_real_steered_wheel_declares_a_bicycle(cli, made):
    code, stderr, entry = sim(cli, made["declared"], "--scenario", "drop", "--package-path",
                              made["folder"])
    assert code == 0, stderr
    drive = entry["drive"]
    line = next(n for n, text in enumerate(BICYCLE_CONTROLLER.splitlines(), 1)
                if "rear_wheel:" in text)
    assert (drive["kind"], drive["chosen"]) == ("bicycle", "declared")
    assert drive["sources"] == {
        "rear_wheel_joint": f"controller YAML {made['yaml']}:{line}"}


def test_a_bicycle_does_not_spin(cli, made):
    code, stderr, entry = sim(cli, made["alone"], "--scenario", "spin")
    assert code == 0, stderr
    assert [(s["name"], s["status"], s["message"]) for s in entry["scenarios"]] == [
        ("spin", "skipped", "a bicycle does not turn in place: turn proves its steering")]


@pytest.mark.parametrize("robot, kind, message", [
    ("car", "bicycle", "--drive bicycle: 2 steering joint(s) (front_left_steering_joint, "
                       "front_right_steering_joint), not one bicycle wheel"),
    ("alone", "differential", "--drive differential: 0 wheels on the left, 0 on the right"),
    ("tricycle", "bicycle", "--drive bicycle: the wheels are not all on the centre line "
                            "(rear_left_wheel_joint, rear_right_wheel_joint beside it)"),
])
def test_drive_picks_a_bicycle_only_where_the_wheels_are_one(cli, made, robot, kind, message):
    result = cli("sim", made[robot], "--drive", kind, "--scenario", "drop")
    assert result.exit_code == 2
    assert message in result.stderr, result.stderr


def test_on_round_tyres_a_single_track_falls_in_the_turn(cli, made, monkeypatch):
    """The control: a bicycle's wheels made spheres (the other kinds' point contact) have
    no width to stand on, and the turn's sideways force at the contact, below its centre
    of mass, tips it over: the circle it ends on is no turn's."""
    def round_every_tyre(mj, spec, drive, parts, friction):
        for wheel in drive.wheels:
            sim_model._round_tyre(spec, wheel, mj)
    monkeypatch.setattr(sim_model, "rolling_contacts", round_every_tyre)
    code, _stderr, entry = sim(cli, made["alone"], "--scenario", "turn")
    assert code == 1
    assert figures(entry, "turn")["radius error"] > 50


def test_mcar_yaml_may_name_the_bicycle_kind(cli, tmp_path, monkeypatch):
    package = tmp_path / "bike_description"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text(PACKAGE_XML.format("bike_description"))
    (package / "urdf" / "bike.urdf").write_text(bicycle())
    (package / "mcar.yaml").write_text('sim:\n  drive:\n    "urdf/bike.urdf": '
                                       '{kind: bicycle}\n')
    monkeypatch.chdir(package)
    code, stderr, entry = sim(cli, "urdf/bike.urdf", "--scenario", "drop")
    assert code == 0, stderr
    assert (entry["drive"]["kind"], entry["drive"]["chosen"]) == (
        "bicycle", "mcar.yaml:3 sim.drive")


def test_a_steering_joint_turning_past_a_right_angle_limits_nothing(cli, tmp_path):
    """bicycle_bot's front_steer_joint turns ±180°: 90% of it is past 90°, where tan
    changes sign; the turn keeps its 15° and turns left."""
    path = tmp_path / "bike.urdf"
    path.write_text(bicycle(steer_limit=3.1416))
    code, stderr, entry = sim(cli, path, "--scenario", "turn")
    assert code == 0, stderr
    assert entry["drive"]["steering_angle_deg"] == pytest.approx(15)
    assert figures(entry, "turn")["radius error"] < 10
