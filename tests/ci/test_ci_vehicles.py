"""`mcar ci` never passes a vehicle it did not watch move: on packages generated under
tmp_path, a skid-steer robot and an Ackermann car are simulated with their own scenarios,
a vehicle sim cannot drive (a fifth wheel on its centre line) fails the run with the
reason until the package's mcar.yaml opts it out, and an arm is "not a vehicle", said plainly."""

from __future__ import annotations

import re
from xml.etree import ElementTree as ET

import pytest
from sim.robot_makers import ackermann, arm, centre_wheel, skid_steer

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>{name}</name><version>0.0.1</version>
<description>generated for mcar's tests</description>
<maintainer email="t@example.com">t</maintainer><license>BSD</license></package>
"""


def make_package(root, name, robots: dict[str, str], config: str | None = None):
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(PACKAGE_XML.format(name=name))
    for file, text in robots.items():
        (root / "urdf" / file).write_text(text)
    if config is not None:
        (root / "mcar.yaml").write_text(config)
    return root


def cases(path) -> dict[tuple[str, str], ET.Element]:
    return {(case.get("classname"), case.get("name")): case
            for case in ET.parse(path).getroot().iter("testcase")}


def ci(run_mcar, package, tmp_path, name="report"):
    report = tmp_path / f"{name}.xml"
    result = run_mcar("ci", package, "--strict", "--no-render", "--build-dir",
                      tmp_path / f"{name}-build",
                      "--junit-xml", report, cwd=tmp_path, timeout=300)
    return result, cases(report)


def test_skid_steer_and_ackermann_vehicles_are_simulated_with_their_scenarios(
        run_mcar, tmp_path):
    package = make_package(tmp_path / "rover_description", "rover_description",
                           {"rover.urdf": skid_steer(), "car.urdf": ackermann()})
    result, found = ci(run_mcar, package, tmp_path)
    assert result.returncode == 0, result.stderr
    for name in ("lint", "drop", "drive", "spin"):
        case = found[(f"mcar.sim.{name}", "rover.urdf")]
        assert case.find("failure") is None and case.find("skipped") is None
    for name in ("lint", "drop", "drive", "turn"):
        case = found[(f"mcar.sim.{name}", "car.urdf")]
        assert case.find("failure") is None and case.find("skipped") is None
    assert ("mcar.sim.spin", "car.urdf") not in found  # an Ackermann car does not spin
    assert "radius error: " in found[("mcar.sim.turn", "car.urdf")].find("system-out").text
    # (", gazebo" where the Gazebo helper is installed: tests/gazebo hold that step)
    assert re.search(r"mcar ci: 2 of 2 files passed \(build, check --strict(, gazebo)?, sim\)",
                     result.stderr), result.stderr
    # The table's SIM column: each vehicle's kind and the scenarios it passed.
    rows = {row.split()[0]: row for row in result.stdout.splitlines()[1:]}
    assert " skid-steer 3/3 " in rows["rover.urdf"] and " ackermann 3/3 " in rows["car.urdf"]


@pytest.fixture
def odd_package(tmp_path):
    return make_package(tmp_path / "base_description", "base_description",
                        {"centre_wheel.urdf": centre_wheel(), "arm.urdf": arm()})


def test_a_vehicle_sim_cannot_drive_fails_ci_with_the_reason(run_mcar, odd_package,
                                                             tmp_path):
    result, found = ci(run_mcar, odd_package, tmp_path)
    assert result.returncode == 1, result.stderr
    reason = "cannot drive this vehicle: a wheel on the centre line (centre_wheel_joint)"
    assert f"centre_wheel.urdf: error: sim {reason}" in result.stderr
    assert "mcar.yaml sim: skip: {GLOB: REASON} opts a robot out" in result.stderr
    drop = found[("mcar.sim.drop", "centre_wheel.urdf")]
    assert drop.find("failure") is None and drop.find("skipped") is None  # it stood
    for name in ("drive", "spin"):  # but nobody watched it move: failures, not skips
        failure = found[(f"mcar.sim.{name}", "centre_wheel.urdf")].find("failure")
        assert failure is not None and failure.get("message").startswith(reason)
    # The arm has no wheels: not a vehicle, said so, and no failure.
    skipped = found[("mcar.sim", "arm.urdf")].find("skipped")
    assert skipped.get("message") == (
        "not simulated: not a vehicle: no wheels (no continuous joint: base_joint (fixed), "
        "arm_1_joint (revolute), arm_2_joint (revolute), arm_3_joint (revolute))")
    assert "mcar: arm.urdf: not simulated: not a vehicle: no wheels" in result.stderr
    rows = {row.split()[0]: row for row in result.stdout.splitlines()[1:]}
    assert rows["centre_wheel.urdf"].split()[5:] == ["cannot", "drive", "-", "FAILED", "(sim)"]
    assert rows["arm.urdf"].split()[5:] == ["not", "a", "vehicle", "-", "ok"]


def test_a_package_opts_a_robot_out_in_mcar_yaml_and_ci_prints_why(run_mcar, odd_package,
                                                                   tmp_path):
    (odd_package / "mcar.yaml").write_text(
        'sim:\n  skip:\n    "urdf/centre*.urdf": "a centre wheel: driven on the real robot"\n')
    result, found = ci(run_mcar, odd_package, tmp_path)
    assert result.returncode == 0, result.stderr
    assert ("mcar: centre_wheel.urdf: not simulated: a centre wheel: driven on the real robot "
            "(mcar.yaml:2)") in result.stderr
    skipped = found[("mcar.sim", "centre_wheel.urdf")].find("skipped")
    assert skipped.get("message").startswith("not simulated: a centre wheel")
    assert not [key for key in found if key[0].startswith("mcar.sim.")]
    assert "  opted out  " in next(row for row in result.stdout.splitlines()
                                   if row.startswith("centre_wheel.urdf"))
    # The opt-out is part of what a no-op run compares: removed, the robot fails again.
    again = run_mcar("ci", odd_package, "--no-render", "--build-dir",
                     tmp_path / "report-build", cwd=tmp_path, timeout=300)
    assert again.returncode == 0 and "a centre wheel: driven on" in again.stderr
    (odd_package / "mcar.yaml").unlink()
    after = run_mcar("ci", odd_package, "--no-render", "--build-dir",
                     tmp_path / "report-build", cwd=tmp_path, timeout=300)
    assert after.returncode == 1
    assert "centre_wheel.urdf: error: sim cannot drive this vehicle" in after.stderr


def test_a_mistake_in_mcar_yaml_stops_ci_before_anything_is_built(run_mcar, odd_package,
                                                                  tmp_path):
    (odd_package / "mcar.yaml").write_text("sim:\n  skipp: {}\n")
    result = run_mcar("ci", odd_package, "--no-render", "--build-dir", tmp_path / "out",
                      cwd=tmp_path, timeout=300)
    assert result.returncode == 2
    assert result.stderr.strip().endswith(
        "mcar.yaml:2: error: unknown key 'sim.skipp': sim takes skip, drive")
    assert not (tmp_path / "out").exists()


def test_wheels_on_revolute_joints_limited_to_1e16_are_simulated_as_sim_does(
        run_mcar, tmp_path):
    """Neobotix MP-400 and swerve bases limit their wheels' revolute joints to ±1e16:
    urdfdom, KDL and mcar sim turn them without end, but ci called the robot "not a
    vehicle: no wheels" and passed it unsimulated."""
    from sim.robot_makers import two_wheeler

    unlimited = two_wheeler(limit='\n    <limit lower="-1e16" upper="1e16" effort="1" '
                                  'velocity="20"/>').replace('type="continuous"',
                                                             'type="revolute"')
    package = make_package(tmp_path / "neo_description", "neo_description",
                           {"base.urdf": unlimited})
    report = tmp_path / "report.xml"
    result = run_mcar("ci", package, "--no-render", "--build-dir", tmp_path / "build",
                      "--junit-xml", report, cwd=tmp_path, timeout=300)
    found = cases(report)
    assert result.returncode == 0, result.stderr
    for name in ("lint", "drop", "drive", "spin"):
        case = found[(f"mcar.sim.{name}", "base.urdf")]
        assert case.find("failure") is None and case.find("skipped") is None
    assert "not a vehicle" not in result.stderr
    (row,) = result.stdout.splitlines()[1:]
    assert " differential 3/3 " in row
