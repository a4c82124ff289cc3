"""`mcar ci` simulates every vehicle of the package (the car and its variants) as `mcar sim`
does, one JUnit testcase per scenario; other robot files are "not simulated", saying why;
a broken drive fails the run at its scenario (its replay: test_ci_noop.py)."""

from __future__ import annotations

import re
from xml.etree import ElementTree as ET

from conftest import REPO

VEHICLES = ("mobile_robot.xacro", "mobile_robot.xacro @ large", "mobile_robot.xacro @ small")
SIM_CASES = ("lint", "drop", "drive", "spin")
EFFORT = ('effort="${motor_stall_torque}"', 'effort="0"')
EFFORT_MESSAGE = ("drove short; likely cause: the motors' effort limit (wheel_left_joint 0 N·m, "
                  "wheel_right_joint 0 N·m): at it for 3.00 s of 3.00 s; the wheels rolled "
                  "0.0000 m of the")


def cases(xml: str) -> dict[tuple[str, str], ET.Element]:
    return {(case.get("classname"), case.get("name")): case
            for case in ET.fromstring(xml).iter("testcase")}


def break_the_drive(package):
    """Motors of no effort: the car stands, but its wheels cannot reach their speed."""
    wheel = package / "urdf/wheel/wheel.xacro"
    text = wheel.read_text()
    assert EFFORT[0] in text
    wheel.write_text(text.replace(*EFFORT))


def test_the_vehicles_pass_each_scenario_and_the_parts_say_why_not(run_mcar, tmp_path):
    result = run_mcar("ci", REPO, "--no-render", "--format", "junit", "--build-dir",
                      tmp_path / "out", cwd=tmp_path, timeout=300)
    assert result.returncode == 0, result.stderr
    found = cases(result.stdout)
    for label in VEHICLES:
        for name in SIM_CASES:
            case = found[(f"mcar.sim.{name}", label)]
            assert case.find("failure") is None and case.find("skipped") is None
        assert "distance error: " in found[("mcar.sim.drive", label)].find("system-out").text
    wheel = found[("mcar.sim", "wheel/test_wheel.urdf.xacro")].find("skipped")
    assert wheel.get("message") == (
        "not simulated: not a vehicle: nothing but its wheels to stand on (only "
        "wheel_left_link, wheel_right_link have collision geometry, no castor or body)")
    tutorial = found[("mcar.sim", "tutorial/04_xacro.xacro")].find("skipped")
    assert tutorial.get("message").startswith("not simulated: not a vehicle: no wheels (no "
                                              "continuous joint: joint_base_wheel1 (fixed)")
    simulated = {label for (classname, label) in found if classname.startswith("mcar.sim.")}
    assert simulated == set(VEHICLES)


def test_a_drive_joint_of_no_effort_fails_the_drive_scenario(run_mcar, package_copy, tmp_path):
    break_the_drive(package_copy)
    result = run_mcar("ci", package_copy, "--no-render", "--build-dir", tmp_path / "out",
                      "--junit-xml", tmp_path / "report.xml", cwd=tmp_path, timeout=300)
    assert result.returncode == 1, result.stderr
    found = cases((tmp_path / "report.xml").read_text())
    for label in VEHICLES:
        failure = found[("mcar.sim.drive", label)].find("failure")
        assert EFFORT_MESSAGE in failure.get("message")
        assert "distance error: 100 % (bound <= 2 %) FAIL" in failure.text
        assert "(bound >= 98 %) FAIL" in failure.text.splitlines()[-1]
        for name in ("lint", "drop"):  # it stands, but neither drives nor turns
            assert found[(f"mcar.sim.{name}", label)].find("failure") is None
        assert found[("mcar.check", label)].find("failure") is None
    failed = {key for key, case in found.items() if case.find("failure") is not None}
    assert failed == {(f"mcar.sim.{name}", label) for label in VEHICLES
                      for name in ("drive", "spin")}
    assert f"mobile_robot.xacro @ small: error: sim drive failed: {EFFORT_MESSAGE}" \
        in result.stderr
    rows = {row.split("  ")[0].strip(): row for row in result.stdout.splitlines()[1:]}
    assert rows["mobile_robot.xacro"].endswith("FAILED (sim)")
    assert rows["wheel/test_wheel.urdf.xacro"].endswith(" ok")
    # ", gazebo" where the Gazebo helper is installed (tests/gazebo/test_gazebo_ci.py)
    assert re.search(r"mcar ci: 12 of 15 files passed \(build, check --strict(, gazebo)?, "
                     r"sim\)", result.stderr)

    github = run_mcar("ci", package_copy, "--no-render", "--format", "github",
                      "--build-dir", tmp_path / "out", cwd=tmp_path, timeout=300)
    assert github.returncode == 1
    annotations = [line for line in github.stdout.splitlines() if line.startswith("::")]
    assert len(annotations) == 6 and all(a.startswith("::error file=") for a in annotations)
    drive = [a for a in annotations if "mobile_robot.xacro,title=mcar ci sim::drive "
             f"failed: {EFFORT_MESSAGE}" in a]
    assert len(drive) == 3


def test_no_sim_runs_no_simulation(run_mcar, package_copy, tmp_path):
    break_the_drive(package_copy)
    result = run_mcar("ci", package_copy, "--no-render", "--no-sim", "--junit-xml",
                      tmp_path / "report.xml", "--build-dir", tmp_path / "out", cwd=tmp_path,
                      timeout=300)
    assert result.returncode == 0, result.stderr
    found = cases((tmp_path / "report.xml").read_text())
    assert ("mcar.check", "mobile_robot.xacro") in found
    assert not [key for key in found if key[0].startswith("mcar.sim")]
    assert re.search(r"passed \(build, check --strict(, gazebo)?\) in", result.stderr)
