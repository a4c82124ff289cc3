"""mcar init --drive KIND: the new package's robot is one mcar sim drives, and mcar ci
passes it because it was simulated (its SIM cell "KIND 3/3"), before and after a part
made by `mcar new part` is used twice in it. One package per drive kind per module: sim
and ci cost seconds each."""

from __future__ import annotations

import json
import math
import re

import pytest
from conftest import mcar_process

KINDS = ("differential", "skid-steer", "ackermann")
# config.xacro's defaults: wheel_radius 0.05 m, wheel_speed 10 rad/s (sim commands half),
# track_width 0.26 m, wheelbase (Ackermann) 0.25 m.
RADIUS, OMEGA, TRACK, WHEELBASE = 0.05, 5.0, 0.26, 0.25
DRIVE_SECONDS = 3.0 - 0.5 / 2  # sim's drive: 3 s, the 0.5 s ramp counted half
TURNING = {"differential": "spin", "skid-steer": "spin", "ackermann": "turn"}
DRIVEN = {"differential": ["wheel_left_joint", "wheel_right_joint"],
          "skid-steer": ["wheel_front_left_joint", "wheel_rear_left_joint",
                         "wheel_front_right_joint", "wheel_rear_right_joint"],
          "ackermann": ["wheel_rear_left_joint", "wheel_rear_right_joint"]}


def _mcar(*args, cwd):
    return mcar_process(*args, cwd=cwd, timeout=300)


@pytest.fixture(scope="module", params=KINDS)
def made(request, mcar_bin, tmp_path_factory):
    """(kind, package folder, `mcar sim --format json` of it, `mcar ci` of it)."""
    kind = request.param
    folder = tmp_path_factory.mktemp(kind)
    init = _mcar("init", "my_bot_description", "--drive", kind, cwd=folder)
    assert init.returncode == 0, init.stderr
    package = folder / "my_bot_description"
    sim = _mcar("sim", "--format", "json", cwd=package)
    assert sim.returncode == 0, sim.stderr
    ci = _mcar("ci", "--strict", "--no-render", cwd=package)
    return kind, package, json.loads(sim.stdout), ci


def _robot(report):
    (robot,) = [f for f in report["files"] if f.get("drive")]
    return robot


def _figure(scenario, name):
    (figure,) = [f for f in scenario["figures"] if f["name"] == name]
    return figure


def test_the_new_robot_is_found_to_be_of_its_kind_and_driven(made):
    kind, _package, report, _ci = made
    robot = _robot(report)
    assert robot["file"] == "urdf/my_bot_description.urdf.xacro"
    assert robot["drive"]["kind"] == kind
    assert robot["drive"]["left"] + robot["drive"]["right"] == DRIVEN[kind]
    assert robot["drive"]["wheel_radius"] == pytest.approx(RADIUS)
    assert robot["drive"]["track"] == pytest.approx(TRACK)
    assert robot["drive"]["command_speed"] == pytest.approx(OMEGA)
    assert [s["name"] for s in robot["scenarios"]] == ["drop", "drive", TURNING[kind]]
    assert [s["status"] for s in robot["scenarios"]] == ["passed"] * 3


def test_it_drives_as_far_and_turns_as_fast_as_its_geometry_says(made):
    kind, _package, report, _ci = made
    drop, drive, turning = _robot(report)["scenarios"]
    assert _figure(drop, "height error")["value"] < 0.001
    along = float(re.match(r"([\d.]+) m of", _figure(drive, "distance error")["detail"])[1])
    assert along == pytest.approx(RADIUS * OMEGA * DRIVE_SECONDS, rel=0.02)
    assert _figure(drive, "heading change")["value"] < 2.0
    if kind == "differential":
        rate = float(re.match(r"([\d.]+) rad/s", _figure(turning, "yaw rate error")["detail"])[1])
        assert rate == pytest.approx(2 * RADIUS * OMEGA / TRACK, rel=0.05)
    elif kind == "skid-steer":  # slower than 2·r·ω/track: its tyres slide sideways
        rate = _figure(turning, "yaw rate")["value"]
        assert 0.2 * 2 * RADIUS * OMEGA / TRACK < rate < 2 * RADIUS * OMEGA / TRACK
    else:
        detail = _figure(turning, "radius error")["detail"]
        radius, angle = re.match(r"([\d.]+) m of .* tan ([\d.]+)°", detail).groups()
        assert float(radius) == pytest.approx(
            WHEELBASE / math.tan(math.radians(float(angle))), rel=0.1)


def test_ci_passes_it_because_it_was_simulated(made):
    kind, _package, _report, ci = made
    assert ci.returncode == 0, ci.stderr
    row = next(line for line in ci.stdout.splitlines()
               if line.startswith("my_bot_description.urdf.xacro"))
    assert f" {kind} 3/3 " in row
    parts = {"differential": 3, "skid-steer": 2, "ackermann": 3}[kind]
    assert f"mcar ci: {parts} of {parts} files passed" in ci.stderr


def test_a_new_part_used_twice_keeps_it_driving(made, mcar_bin):
    """`mcar new part` makes a macro that takes a name and reflect: the robot file calls
    it for a left and a right one (two links, no clash), and the robot still drives."""
    kind, package, _report, _ci = made
    part = _mcar("new", "part", "bumper", cwd=package)
    assert part.returncode == 0, part.stderr
    robot = package / "urdf" / "my_bot_description.urdf.xacro"
    text = robot.read_text()
    calls = """
  <xacro:include filename="$(find my_bot_description)/urdf/bumper/bumper.xacro"/>
  <xacro:bumper name="left" reflect="1" parent="base_link" length="0.05" height="0.02">
    <origin xyz="0 0 ${base_z + base_height / 2 + 0.01}"/>
  </xacro:bumper>
  <xacro:bumper name="right" reflect="-1" parent="base_link" length="0.05" height="0.02">
    <origin xyz="0 0 ${base_z + base_height / 2 + 0.01}"/>
  </xacro:bumper>
</robot>"""
    robot.write_text(text.replace("</robot>", calls))
    built = _mcar("build", robot, cwd=package)
    assert built.returncode == 0, built.stderr
    assert '<link name="bumper_left_link">' in built.stdout
    assert '<link name="bumper_right_link">' in built.stdout
    sim = _mcar("sim", robot, cwd=package)
    assert sim.returncode == 0, sim.stdout + sim.stderr
    assert "mcar sim: 3 passed, 0 failed, 0 skipped in 1 file" in sim.stderr + sim.stdout
    ci = _mcar("ci", "--strict", "--no-render", cwd=package)
    assert ci.returncode == 0, ci.stderr
    assert f" {kind} 3/3 " in ci.stdout
    assert re.search(r"^bumper/test_bumper\.urdf\.xacro .* not a vehicle +- +ok$", ci.stdout,
                     re.M), ci.stdout


def test_a_wrong_drive_kind_is_a_usage_error(run_mcar, tmp_path):
    bad = run_mcar("init", "demo", "--drive", "tank", cwd=tmp_path)
    assert bad.returncode == 2
    assert "Invalid value for '--drive': 'tank' is not one of 'differential', " \
           "'skid-steer', 'ackermann'" in bad.stderr
    assert not (tmp_path / "demo").exists()


CROSS_CHECKS = {
    "differential": ("castor_radius=1cm", "the castor ball does not reach the base: "
                     "2 * castor_radius (0.02 m) must be at least base_clearance (0.03 m)"),
    "skid-steer": ("wheelbase=8cm", "the front and rear wheels overlap: wheelbase (0.08 m) "
                   "must exceed 2 * wheel_radius (0.1 m)"),
    "ackermann": ("wheelbase=8cm", "the front and rear wheels overlap: wheelbase (0.08 m) "
                  "must exceed 2 * wheel_radius (0.1 m)"),
}


def test_config_refuses_dimensions_that_do_not_fit_together(made, mcar_bin):
    kind, package, _report, _ci = made
    robot = "urdf/my_bot_description.urdf.xacro"
    setting, message = CROSS_CHECKS[kind]
    for args, why in ((("--set", setting), message),
                      (("--set", "base_width=25cm"), "the wheels overlap the base: their "
                       "inner faces (track_width - wheel_width = 0.23 m apart) must be further "
                       "apart than base_width (0.25 m)")):
        built = _mcar("build", robot, *args, "-o", "-", cwd=package)
        assert (built.returncode, built.stdout) == (2, "")
        assert built.stderr == f"mcar: error: the dimensions do not fit together: {why}\n"


def test_the_cli_offers_the_drive_kinds_the_scaffold_makes_and_sim_detects():
    from mobile_car.cli.init import DRIVES as OFFERED

    from mobile_car.scaffold import DRIVES
    from mobile_car.sim.drives import KINDS

    assert tuple(OFFERED) == tuple(DRIVES)
    # every kind the scaffold makes, sim detects; sim also detects mecanum and bicycle,
    # which mcar init does not make
    assert KINDS == (*DRIVES, "mecanum", "bicycle")
