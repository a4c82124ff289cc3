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
