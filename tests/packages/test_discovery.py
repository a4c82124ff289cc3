"""Robot discovery on real layouts (issue 26): a robot is a file that can make a <robot>
with links and that no other file includes; macro files, included files, fragments and
other files are skipped with the reason `mcar ci -v` prints. The cases are the files of
tests/packages/discovery_cases/ (expected: discovery_expected.txt), and the released
packages of the shared real-robots folder, read in place."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from sim.test_sim_real_robots import real_robots

from mobile_car.packages.discover import discover

HERE = Path(__file__).resolve().parent
CASES = HERE / "discovery_cases"
FOLDER = real_robots()
needs_folder = pytest.mark.skipif(FOLDER is None, reason="the shared real-robots folder is "
                                  "absent (set MCAR_REAL_ROBOTS)")
# SOURCES.md of the real-robots folder: each package's robots, and its fragments (which
# must be skipped with a reason).
REAL = {
    "turtlebot3_description": (
        {"urdf/turtlebot3_burger.urdf", "urdf/turtlebot3_waffle.urdf",
         "urdf/turtlebot3_waffle_pi.urdf"},
        {"urdf/common_properties.urdf": "no <link>, and nothing that makes one: a fragment"}),
    "husky_description": (
        {"urdf/husky.urdf.xacro"},
        {"urdf/empty.urdf": "included by urdf/husky.urdf.xacro",
         "urdf/wheel.urdf.xacro": "included by urdf/husky.urdf.xacro"}),
    "mir_description": (
        {"urdf/mir.urdf.xacro"},
        {"urdf/include/mir_100_v1.urdf.xacro": "defines macros only, and includes only files "
                                               "that make no <link>"}),
    "jackal_description": (
        {"urdf/jackal.urdf.xacro"},
        {"urdf/empty.urdf": "included by urdf/jackal.urdf.xacro",
         "urdf/custom_example.urdf": "a fragment to include: its <robot> has no name",
         "urdf/configs/base": "not a .urdf or .xacro file",
         "urdf/configs/front_laser": "not a .urdf or .xacro file"}),
}


def _expected() -> dict[str, str]:
    rows = {}
    for text in (HERE / "discovery_expected.txt").read_text().splitlines():
        if text.strip() and not text.startswith("#"):
            name, outcome = (cell.strip() for cell in text.split("|", 1))
            rows[name] = outcome
    return rows


def _outcomes(root: Path) -> dict[str, str]:
    found = discover(root)
    outcomes = {path.relative_to(root).as_posix(): "robot" for path in found.robots}
    outcomes.update({s.path.relative_to(root).as_posix(): s.reason for s in found.skipped})
    return outcomes


def test_every_case_file_is_taken_or_skipped_as_expected():
    expected = _expected()
    files = {p.relative_to(CASES).as_posix() for p in (CASES / "urdf").rglob("*") if p.is_file()}
    assert set(expected) == files, "every case file has a row in discovery_expected.txt"
    assert _outcomes(CASES) == expected


def test_ci_lists_what_it_skipped_under_verbose_and_counts_it_otherwise(tmp_path, run_mcar):
    expected = _expected()
    quiet = run_mcar("ci", CASES, "--no-render", "--no-sim", "--build-dir", tmp_path / "b",
                     cwd=tmp_path)
    skipped = [name for name, outcome in expected.items() if outcome != "robot"]
    robots = sorted(name.removeprefix("urdf/") for name, o in expected.items() if o == "robot")
    table = quiet.stdout.splitlines()
    assert [row.split()[0] for row in table[1:]] == robots
    assert quiet.stderr.splitlines()[-2] == (f"mcar ci: skipped {len(skipped)} files that "
                                             "are not robots (-v lists them)")
    assert "mcar: skipped" not in quiet.stderr
    verbose = run_mcar("ci", CASES, "-v", "--no-render", "--no-sim", "--build-dir",
                       tmp_path / "b", cwd=tmp_path)
    listed = [line for line in verbose.stderr.splitlines() if line.startswith("mcar: skipped ")]
    shown = CASES.relative_to(tmp_path) if CASES.is_relative_to(tmp_path) else CASES
    assert listed == [f"mcar: skipped {shown}/{name}: {expected[name]}" for name in skipped]
    assert "(-v lists them)" not in verbose.stderr
    # A nameless plain URDF and a broken file are robots: checking them says what is wrong.
    assert re.search(r"plain_without_name\.urdf:1: error: <robot> has no name", verbose.stderr)
    assert re.search(r"broken\.urdf:3: error: not well-formed XML", verbose.stderr)


def test_a_urdf_beside_its_xacro_is_one_robot_and_ci_passes(tmp_path, run_mcar):
    """Panda ships panda.urdf beside panda.urdf.xacro: both mapped to build/panda.urdf,
    and ci refused the run (exit 2)."""
    package = tmp_path / "arm_description"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>arm_description</name>"
                                         "</package>")
    for name, body in (("arm.urdf.xacro", '<link name="${\'base\'}"/>'),
                       ("arm.urdf", '<link name="base"/>')):
        (package / "urdf" / name).write_text(
            f'<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</robot>')
    result = run_mcar("ci", "--no-render", "--no-sim", "-v", cwd=package)
    assert result.returncode == 0, result.stderr
    assert [row.split()[0] for row in result.stdout.splitlines()[1:]] == ["arm.urdf.xacro"]
    assert (package / "build" / "arm.urdf").read_text().count('<link name="base"/>') == 1
    assert ("mcar: skipped urdf/arm.urdf: the URDF of urdf/arm.urdf.xacro beside it (one "
            "robot: its xacro is built)") in result.stderr.splitlines()


def test_mcar_yaml_include_takes_only_the_robots_it_names(tmp_path):
    package = tmp_path / "two"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>two</name></package>")
    for name in ("a.urdf", "b.urdf"):
        (package / "urdf" / name).write_text(f'<robot name="{name}"><link name="l"/></robot>')
    (package / "mcar.yaml").write_text('robots:\n  include: ["urdf/b.*"]\n')
    assert _outcomes(package) == {"urdf/a.urdf": "left out by not in robots.include of "
                                                 "mcar.yaml:2",
                                  "urdf/b.urdf": "robot"}


def test_a_folder_with_no_robot_says_what_it_skipped(tmp_path, run_mcar):
    (tmp_path / "macros.xacro").write_text(
        '<robot name="lib" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro '
        'name="m"/></robot>')
    result = run_mcar("build", ".", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines()[0] == (
        ".: error: no robot files in this folder (looked in urdf/, robots/, xacro/, "
        "description/ or the folder itself); skipped 1 file that is not robots: macros.xacro "
        "(defines macros only: no <link> outside <xacro:macro>)")


@needs_folder
@pytest.mark.parametrize("package", sorted(REAL))
def test_ci_in_a_real_package_finds_its_robots_and_no_fragment(package, tmp_path, cli,
                                                               monkeypatch):
    robots, fragments = REAL[package]
    outcomes = _outcomes(FOLDER / package)
    assert {name for name, outcome in outcomes.items() if outcome == "robot"} == robots
    for name, reason in fragments.items():
        assert outcomes[name] == reason
    monkeypatch.chdir(FOLDER / package)
    result = cli("ci", "-v", "--no-render", "--no-sim", "--package-path", FOLDER,
                 "--build-dir", tmp_path / "build")
    rows = [row.split()[0] for row in result.stdout.splitlines()[1:]]
    assert rows == sorted(name.removeprefix("urdf/") for name in robots)
    lines = result.stderr.splitlines()
    for name, reason in fragments.items():
        assert f"mcar: skipped {name}: {reason}" in lines


def test_the_examples_of_docs_discovery_are_what_mcar_does(tmp_path):
    """The mcar.yaml of docs/discovery.md loads and leaves out what it says; its ci -v
    lines are the reasons discovery gives (Jackal's, held to the real package above)."""
    from mobile_car.load.xacro_use import note_text
    from mobile_car.packages.package_config import load_package_config

    text = (HERE.parents[1] / "docs" / "discovery.md").read_text()
    blocks = re.findall(r"```(\w*)\n(.*?)```", text, re.S)
    (yaml,) = [body for kind, body in blocks if kind == "yaml"]
    (tmp_path / "mcar.yaml").write_text(yaml)
    config = load_package_config(tmp_path)
    assert config.selects(tmp_path / "urdf" / "jackal.urdf.xacro") == (True, None)
    assert config.selects(tmp_path / "urdf" / "custom_example.urdf")[0] is False
    assert config.selects(tmp_path / "urdf" / "arm.xacro")[0] is False  # not included
    lines = [line for kind, body in blocks if not kind for line in body.splitlines()]
    jackal = REAL["jackal_description"][1]
    for line in lines:
        if line.startswith("mcar: skipped "):
            name, reason = line.removeprefix("mcar: skipped ").split(": ", 1)
            assert jackal[name] == reason
        else:
            assert line == ("mcar: urdf/turtlebot3_burger.urdf: "
                            + note_text("<xacro:arg>"))
