"""``mcar ci`` where the Gazebo helper is installed: with -v, one line per robot meant for
Gazebo (a <gazebo> block) saying what Gazebo simulates and which libsdformat said so; a
dropped link failing its file, parts' test files skipped saying why, and the step replayed
by a no-op run."""

from __future__ import annotations

import re
from xml.etree import ElementTree as ET

LINE = re.compile(r"mcar: mobile_robot\.xacro: gazebo: 3 links of 16 \(13 lumped\), "
                  r"0\.7056 kg, as in the URDF \(libsdformat \d+\.\d+\.\d+\)")


def gazebo_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if ": gazebo: " in line]


def test_ci_says_what_gazebo_simulates_and_replays_it(run_mcar, gazebo, package_copy,
                                                      tmp_path):
    args = ("ci", package_copy, "--no-render", "--no-sim", "--build-dir", tmp_path / "out",
            "--junit-xml", tmp_path / "report.xml")
    first = run_mcar(*args, env=gazebo, cwd=tmp_path, timeout=300)
    assert first.returncode == 0, first.stderr
    assert gazebo_lines(first.stderr) == []  # the per-file lines only with -v
    assert "note:" not in first.stderr  # the lumping is in the report, not on the terminal
    assert "(build, check --strict, gazebo) in" in first.stderr
    suite = ET.parse(tmp_path / "report.xml").getroot().find("testsuite")
    cases = {(c.get("classname"), c.get("name")): c for c in suite.iter("testcase")}
    car = cases[("mcar.gazebo", "mobile_robot.xacro")]
    assert car.find("failure") is None
    assert car.find("system-out").text.count("[N401]") == 13
    assert cases[("mcar.gazebo", "wheel/test_wheel.urdf.xacro")].find("skipped").get(
        "message") == "not for Gazebo: no <gazebo> element"
    again = run_mcar(*args, "-v", env=gazebo, cwd=tmp_path, timeout=300)
    assert again.returncode == 0
    lines = gazebo_lines(again.stderr)  # the car and its two variants, replayed
    assert len(lines) == 3 and LINE.fullmatch(lines[0]), lines
    assert (tmp_path / "report.xml").read_text().count('classname="mcar.gazebo"') == \
        sum(1 for key in cases if key[0] == "mcar.gazebo")


def test_a_link_gazebo_drops_fails_the_file(run_mcar, gazebo, package_copy, tmp_path):
    wheel = package_copy / "urdf" / "wheel" / "wheel.xacro"
    text = wheel.read_text()
    start = text.index("<xacro:cylinder_inertial")
    end = text.index("</xacro:cylinder_inertial>", start) + len("</xacro:cylinder_inertial>")
    wheel.write_text(text[:start] + text[end:])  # wheels without mass: W206, and in Gazebo?
    result = run_mcar("ci", package_copy / "urdf" / "mobile_robot.xacro", "--no-strict",
                      "--no-render", "--no-sim", "--build-dir", tmp_path / "out",
                      "--format", "junit", env=gazebo, cwd=tmp_path, timeout=300)
    assert result.returncode == 1, result.stderr
    suite = ET.fromstring(result.stdout).find("testsuite")
    failed = {c.get("classname"): c.find("failure") for c in suite.iter("testcase")}
    assert failed["mcar.check"] is None  # a warning, not strict
    failure = failed["mcar.gazebo"]
    assert failure.get("message").startswith("mobile_car_description/urdf/wheel/wheel.xacro:")
    assert "error: Gazebo leaves out link 'wheel_left_link' (no <inertial>), with its joint " \
           "'wheel_left_joint'" in failure.text
    assert "error: Gazebo leaves out link 'wheel_right_link'" in failure.text
    # the wheels weighed nothing, so no mass is lost: but the drive plugin has no wheels
    assert "note: Gazebo simulates 1 link: 0.6256 kg, as in the URDF (libsdformat " \
        in failure.text
    plugin = [line for line in failure.text.splitlines() if line.endswith("[W232]")
              and "<left_joint>" in line]
    assert len(plugin) == 1 and "warning: plugin 'gz::sim::systems::DiffDrive': <left_joint> " \
        "names joint 'wheel_left_joint', which Gazebo does not have (left out with link " \
        "'wheel_left_link')" in plugin[0]
