"""`mcar ci`: the whole package built, strictly checked and rendered; reports for CI servers."""

from __future__ import annotations

from xml.etree import ElementTree as ET

from conftest import REPO

from mobile_car.packages.discover import robot_files  # the same discovery mcar ci uses


def expected_labels() -> list[str]:
    base = REPO / "urdf"
    files = robot_files(REPO)
    labels = [p.relative_to(base).as_posix() for p in files]
    top = [p.relative_to(base).as_posix() for p in files if p.parent == base]
    for variant in sorted((base / "variants").glob("*.yaml")):
        labels += [f"{name} @ {variant.stem}" for name in top]
    return labels


def test_green_on_the_bundled_package_with_pictures(run_mcar, tmp_path):
    result = run_mcar("ci", "--bundled", cwd=tmp_path, timeout=300)
    assert result.returncode == 0, result.stderr
    labels = expected_labels()
    rows = result.stdout.splitlines()
    assert rows[0].split() == ["FILE", "LINKS", "JOINTS", "WARN", "ERR", "SIM", "PNG",
                               "RESULT"]
    assert [row.split()[0] for row in rows[1:]] == [label.split(" @ ")[0] for label in labels]
    assert all(row.endswith(" ok") for row in rows[1:])
    robot_row = next(r for r in rows if r.startswith("mobile_robot.xacro "))
    assert robot_row.split()[1:5] == ["16", "15", "0", "0"]
    assert f"mcar ci: {len(labels)} of {len(labels)} files passed" in result.stderr
    assert (tmp_path / "build" / "variants" / "small" / "mobile_robot.urdf").is_file()
    pictures = {p.relative_to(tmp_path / "renders").as_posix()
                for p in (tmp_path / "renders").rglob("*.png")}
    assert {"index.png", "mobile_robot.png", "wheel/test_wheel.png",
            "variants/large/mobile_robot.png"} <= pictures
    assert len(pictures) == len(labels) + 1


def test_red_with_a_junit_report_naming_the_broken_part(run_mcar, package_copy, tmp_path):
    wheel = package_copy / "urdf" / "wheel" / "wheel.xacro"
    text = wheel.read_text()
    wheel.write_text(text.replace("<visual>", "<visul>", 1).replace("</visual>", "</visul>", 1))
    line = next(i for i, text in enumerate(wheel.read_text().splitlines(), 1)
                if "<visul>" in text)
    result = run_mcar("ci", package_copy, "--format", "junit", "--no-render",
                      "--build-dir", tmp_path / "out", cwd=tmp_path)
    assert result.returncode == 1
    suite = ET.fromstring(result.stdout).find("testsuite")
    failed = {(case.get("classname"), case.get("name")): case.find("failure")
              for case in suite.iter("testcase") if case.find("failure") is not None}
    uses_wheel = {"wheel/test_wheel.urdf.xacro", "mobile_robot.xacro",
                  "mobile_robot.xacro @ large", "mobile_robot.xacro @ small"}
    assert set(failed) == {("mcar.check", name) for name in uses_wheel}
    report = failed[("mcar.check", "wheel/test_wheel.urdf.xacro")].text
    assert f"wheel.xacro:{line}: warning: unknown element <visul>" in report
    assert "did you mean 'visual'?" in report
    assert int(suite.get("failures")) == len(uses_wheel)
    passed = [c for c in suite.iter("testcase") if c.find("failure") is None]
    assert ("mcar.build", "laser/test_laser.urdf.xacro") in \
        {(c.get("classname"), c.get("name")) for c in passed}


def test_github_annotations_point_at_the_source_line(run_mcar, package_copy, tmp_path):
    laser = package_copy / "urdf" / "laser" / "laser.xacro"
    text = laser.read_text()
    assert "<visual>" in text
    laser.write_text(text.replace("<visual>", "<visual>\n<bogus/>", 1))
    result = run_mcar("ci", package_copy, "--format", "github", "--no-render",
                      "--build-dir", tmp_path / "out", cwd=tmp_path)
    assert result.returncode == 1
    annotations = [line for line in result.stdout.splitlines() if line.startswith("::")]
    assert annotations and all(a.startswith("::warning file=") for a in annotations)
    assert any("laser.xacro,line=" in a and "bogus" in a for a in annotations)


def test_build_failure_skips_the_later_steps_and_others_go_on(run_mcar, package_copy,
                                                             tmp_path):
    motor = package_copy / "urdf" / "motor" / "test_motor.urdf.xacro"
    motor.write_text(motor.read_text().replace("</robot>", "<link name='${nope}'/></robot>"))
    result = run_mcar("ci", package_copy, "--format", "junit", "--build-dir", tmp_path / "b",
                      "--render-dir", tmp_path / "r", cwd=tmp_path,
                      timeout=300)
    assert result.returncode == 1
    cases = {(c.get("classname"), c.get("name")): c
             for c in ET.fromstring(result.stdout).iter("testcase")}
    build = cases[("mcar.build", "motor/test_motor.urdf.xacro")].find("failure")
    assert "name 'nope' is not defined" in build.get("message")
    for step in ("check", "render"):
        assert cases[(f"mcar.{step}", "motor/test_motor.urdf.xacro")].find("skipped") is not None
    assert (tmp_path / "r" / "wheel" / "test_wheel.png").is_file()
    assert not (tmp_path / "r" / "motor").exists()


def test_missing_package_exits_2(run_mcar, tmp_path):
    result = run_mcar("ci", tmp_path / "nowhere", cwd=tmp_path)
    assert result.returncode == 2
    assert "nowhere: error: no such file" in result.stderr
