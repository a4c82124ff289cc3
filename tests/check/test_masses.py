"""E119: a mass no built robot has fails the check, and so `mcar ci`, before a simulation
drives it (a TurtleBot3-sized two-wheeler with 1000 kg wheels drove in `mcar sim`). The
bounds are in mobile_car/check/masses.py; the corpus has a case per bound."""

from __future__ import annotations

from sim.robot_makers import heavy_wheels, two_wheeler

MESSAGE = ("small.urdf:15: error: link 'wheel_left_link' turns on a continuous joint (a "
           "wheel) and weighs 1000 kg, 1701 times the 0.588 kg of the robot without its "
           "wheels: no wheel built is over 5 times its robot (a unit or a digit wrong?) "
           "[E119]")


def test_ci_fails_a_two_wheeler_on_1000_kg_wheels(run_mcar, tmp_path):
    (tmp_path / "small.urdf").write_text(heavy_wheels(1000.0))
    result = run_mcar("ci", ".", "--no-render", "--build-dir", tmp_path / "out",
                      cwd=tmp_path)
    assert result.returncode == 1
    assert MESSAGE in result.stderr
    assert "small.urdf      4       3     1    2  -    -    FAILED (check)" in result.stdout


def test_the_same_robot_on_its_own_wheels_passes_the_check(cli, tmp_path):
    (tmp_path / "small.urdf").write_text(two_wheeler())  # wheels of 56 g
    result = cli("check", tmp_path / "small.urdf")
    assert result.exit_code == 0
    assert "E119" not in result.stderr

