"""Macro calls without the xacro: prefix: xacro 2 copies them into the URDF unexpanded,
so mcar build refuses them, located, instead of writing a robot without its parts."""

from __future__ import annotations

from pathlib import Path

SEED = Path(__file__).resolve().parent / "seed" / "mobile_robot_unprefixed.xacro"
HEAD = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def test_the_seed_listing_is_refused_at_its_first_unprefixed_call(run_mcar, tmp_path):
    result = run_mcar("build", SEED, "-o", tmp_path / "out.urdf", cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == (
        f"{SEED}:17: error: <chassis> calls macro 'chassis' without the xacro: prefix; "
        "xacro 2 copies it into the URDF unexpanded: write <xacro:chassis ...>")
    assert not (tmp_path / "out.urdf").exists()


def test_an_unprefixed_call_that_expands_without_error_is_refused(run_mcar, tmp_path):
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(HEAD + '<xacro:macro name="part" params="n"><link name="${n}"/>'
                     '</xacro:macro>\n<link name="base"/>\n<part n="arm"/>\n</robot>\n')
    for command in ("build", "check", "render"):
        result = run_mcar(command, robot, cwd=tmp_path)
        assert result.returncode == 1, (command, result.stderr)
        assert ("r.urdf.xacro:4: error: <part> calls macro 'part' without the xacro: "
                "prefix") in result.stderr, (command, result.stderr)


def test_macros_named_like_urdf_or_inside_extensions_are_not_calls(run_mcar, tmp_path):
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(HEAD + '<xacro:macro name="inertial"><mass value="1"/></xacro:macro>\n'
                     '<xacro:macro name="camera"><x/></xacro:macro>\n'
                     '<link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
                     'ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n'
                     '<gazebo><sensor name="c" type="camera"><camera/></sensor></gazebo>\n'
                     '</robot>\n')
    result = run_mcar("build", robot, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "<camera/>" in result.stdout and "<inertial>" in result.stdout


def test_check_names_the_macro_in_a_urdf_that_kept_an_unprefixed_call(cli, tmp_path):
    (tmp_path / "package.xml").write_text(
        '<package format="3"><name>demo</name><version>0.1.0</version><description>d'
        '</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>'
        "</package>")
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="chassis" '
        'params="name"><link name="${name}"/></xacro:macro></robot>')
    built = tmp_path / "urdf" / "robot.urdf"  # what xacro 2 wrote for <chassis name="body"/>
    built.write_text('<robot name="r">\n<link name="base"/>\n<chassis name="body"/>\n'
                     "<wheel/>\n</robot>\n")
    result = cli("check", "-q", built)
    assert result.exit_code == 0  # W201 is a warning: --strict makes it fail
    lines = result.stderr.splitlines()
    assert lines[0].endswith(
        "robot.urdf:3: warning: unknown element <chassis> in <robot>: the macro 'chassis' of "
        "this package, called without the xacro: prefix? xacro 2 copies such calls "
        "unexpanded: write <xacro:chassis ...> [W201]")
    assert lines[1].endswith("robot.urdf:4: warning: unknown element <wheel> in <robot> [W201]")


def test_an_sdf_element_named_like_a_macro_is_not_blamed_when_xacro_stops(run_mcar, tmp_path):
    # Husarion Panther: a macro 'imu' writes a <gazebo><sensor> holding SDF's <imu>; when
    # xacro stopped on a missing include, that <imu> was reported as an unprefixed call.
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(HEAD + '<xacro:macro name="imu" params="frame">\n'
                     '  <gazebo reference="${frame}">\n'
                     '    <sensor name="imu" type="imu"><imu><noise/></imu></sensor>\n'
                     '  </gazebo>\n'
                     '</xacro:macro>\n'
                     '<link name="base"/>\n'
                     '<xacro:imu frame="base"/>\n'
                     '<xacro:include filename="missing.urdf.xacro"/>\n'
                     '</robot>\n')
    result = run_mcar("build", robot, cwd=tmp_path)
    assert result.returncode == 1
    assert "calls macro" not in result.stderr
    assert result.stderr.splitlines()[0] == (
        "r.urdf.xacro:9: error: cannot read missing.urdf.xacro: No such file or directory")


def test_an_unprefixed_call_is_located_past_an_sdf_element_of_its_name(run_mcar, tmp_path):
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(HEAD + '<xacro:macro name="imu" params="n"><link name="${n}"/>'
                     '</xacro:macro>\n<link name="base"/>\n'
                     '<gazebo><sensor name="s" type="imu"><imu/></sensor></gazebo>\n'
                     '<imu n="arm"/>\n</robot>\n')
    result = run_mcar("build", robot, cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == (
        "r.urdf.xacro:5: error: <imu> calls macro 'imu' without the xacro: prefix; xacro 2 "
        "copies it into the URDF unexpanded: write <xacro:imu ...>")
