"""The statics section's note where no proof runs: a vehicle sim drives no kind of is
still a vehicle (Curiosity, four of its six wheels on corner steering joints, was "not a
vehicle" to mcar specs while mcar sim and ci judged it one they cannot drive); a robot
that is none says so as before."""

from __future__ import annotations

from sim.robot_makers import arm, tricycle

NOTE = ": no tilt or climb proof (they hold and drive its wheels)"


def test_a_vehicle_without_a_drive_kind_is_not_called_no_vehicle(cli, tmp_path):
    (tmp_path / "tricycle.urdf").write_text(tricycle())
    result = cli("specs", tmp_path / "tricycle.urdf", "--no-proof")
    assert result.exit_code == 0, result.stderr
    (line,) = [x for x in result.stderr.splitlines() if x.endswith(NOTE)]
    assert line.endswith("tricycle.urdf: no drive sim drives (a wheel on the centre line "
                         "(front_wheel_joint): not a drive kind mcar sim drives (differential, "
                         "skid-steer, ackermann, mecanum, bicycle))" + NOTE)


def test_a_robot_that_is_no_vehicle_says_so(cli, tmp_path):
    (tmp_path / "arm.urdf").write_text(arm())
    result = cli("specs", tmp_path / "arm.urdf", "--no-proof")
    assert result.exit_code == 0, result.stderr
    assert [x for x in result.stderr.splitlines() if x.endswith(NOTE)][0].endswith(
        "arm.urdf: not a vehicle" + NOTE)
