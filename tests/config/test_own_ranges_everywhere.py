"""config.xacro's own ranges hold wherever the robot is loaded (issue 30, item 2).

A value typed in config.xacro in the wrong unit (``wheel_radius`` 32.5: millimetres typed
as metres) used to build, check and render a 65 m wheel with exit 0; only `mcar config`
said it was outside its range. Every command loads through the one loader, which now
judges the ranges of a config.xacro the robot read: each command below stops with the
same located line as `mcar config` and exit 1 (diff's 1 means "changed", so a robot it
cannot load is its 2, as its help says).
"""

from __future__ import annotations

import pytest

MESSAGE = ("urdf/config.xacro:47: error: property 'wheel_radius': its value 32.5 is outside "
           "its own range 5 mm..0.5 m; did you mean 32.5 mm (written 0.0325)?")

# command words, exit code; each runs in the package with the slip in config.xacro.
COMMANDS = [
    (["config"], 1),
    (["build"], 1),
    (["build", "urdf/mobile_robot.xacro"], 1),
    (["check"], 1),
    (["check", "urdf/mobile_robot.xacro"], 1),
    (["render", "urdf/mobile_robot.xacro", "--renderer", "raycast", "--size", "80x60"], 1),
    (["tree", "urdf/mobile_robot.xacro"], 1),
    (["sim", "urdf/mobile_robot.xacro"], 1),
    (["ci", "--no-render", "--no-sim", "--no-gazebo"], 1),
    (["view", "--no-browser", "urdf/mobile_robot.xacro"], 1),
    (["sweep", "--vary", "wheel_mass=60g,70g", "-o", "points.csv"], 1),
    (["diff", "urdf/wheel/test_wheel.urdf.xacro", "urdf/mobile_robot.xacro"], 2),
]


@pytest.fixture
def slipped(package_copy, monkeypatch):
    config = package_copy / "urdf" / "config.xacro"
    text = config.read_text()
    right = '<xacro:property name="wheel_radius" value="0.0325"/>'
    assert text.splitlines()[46].strip().startswith(right)
    config.write_text(text.replace(right, right.replace("0.0325", "32.5")))
    monkeypatch.chdir(package_copy)
    return package_copy


@pytest.mark.parametrize("words, code", COMMANDS, ids=[" ".join(w[:2]) for w, _ in COMMANDS])
def test_an_out_of_range_value_in_config_xacro_stops_every_command(cli, slipped, words, code):
    result = cli(*words)
    assert result.exit_code == code, result.output
    lines = [line.removesuffix(" [E140]") for line in result.stderr.splitlines()]
    assert MESSAGE in lines, result.stderr
    assert "Traceback" not in result.output
    if words[0] == "build":
        assert not list((slipped / "build").rglob("mobile_robot.urdf"))
    if words[0] == "tree":  # not "has no single kinematic tree": the tree was never read
        assert lines[-1] == ("mcar tree: urdf/mobile_robot.xacro was not read into a robot "
                             "(the error above)")
    if words[0] == "sim":
        assert lines[-1].endswith("; 1 file not simulated: its load or check failed (above)")


def test_ci_says_the_build_failed_because_of_it(cli, slipped):
    result = cli("ci", "--no-render", "--no-sim", "--no-gazebo", "urdf/mobile_robot.xacro")
    assert result.exit_code == 1, result.output
    assert "FAILED (build)" in result.output


def test_a_config_xacro_not_in_mcars_form_is_left_alone(cli, tmp_path, monkeypatch):
    """Only ranged, documented properties are judged: someone else's config.xacro (no
    'UNIT LO..HI; SOURCE: meaning' comments) builds as xacro builds it."""
    (tmp_path / "config.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="wheel_radius" value="32.5"/>  <!-- the wheel -->\n</robot>\n')
    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="config.xacro"/>\n'
        '  <link name="base_link"/>\n</robot>\n')
    monkeypatch.chdir(tmp_path)
    result = cli("build", "robot.urdf.xacro", "-o", "out")
    assert result.exit_code == 0, result.output
