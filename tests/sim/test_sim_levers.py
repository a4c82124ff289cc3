"""Levers high in the air are no wheels: what mcar sim and its callers (a package's files,
ci, an export's manifest) decide of a robot whose only endless joints about level axes
turn links far above the floor (the parallel-linkage levers of ABB's IRB 2400, continuous
joints mimicking joint_3, 0.6 m and 1.3 m up its 1.6 m arm), made at test time, against
the same robot with those joints at the floor, which is a vehicle."""

from __future__ import annotations

import json

from sim.robot_makers import box_inertia, two_wheeler
from sim.sim_json import sim

LEVERS = ("continuous joints lever_left_joint, lever_right_joint turn about level axes high "
          "above the floor (levers)")


def levers(axle_height: float) -> str:
    """A 5 kg base 0.1 m high with a 1 m column, and two 0.05 m discs beside the base on
    continuous joints about y ``axle_height`` up: at 0.9, levers near the column's top;
    at 0.05, wheels that reach the floor, the base standing on them and its front edge."""
    discs = "".join(f"""
  <joint name="lever_{side}_joint" type="continuous">
    <parent link="base_link"/><child link="lever_{side}"/>
    <origin xyz="0 {y} {axle_height}"/><axis xyz="0 1 0"/>
  </joint>
  <link name="lever_{side}">
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.04"/>
    </geometry></collision>
    <inertial><mass value="0.5"/>{box_inertia(0.5, 0.1, 0.04, 0.1)}</inertial>
  </link>""" for side, y in (("left", 0.2), ("right", -0.2)))
    return f"""<?xml version="1.0"?>
<robot name="levers">
  <link name="base_link">
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/></geometry>
    </collision>
    <collision><origin xyz="0 0 0.55"/><geometry><box size="0.05 0.05 0.9"/></geometry>
    </collision>
    <inertial><origin xyz="0 0 0.05"/><mass value="5"/>{box_inertia(5, 0.3, 0.3, 0.1)}
    </inertial>
  </link>{discs}
</robot>
"""


def test_levers_high_up_are_no_wheels_and_the_robot_passes_its_drop(cli, tmp_path):
    # It was a vehicle with no drive: "cannot drive this vehicle" (ABB's IRB 2400/12-155).
    robot = tmp_path / "levers.urdf"
    robot.write_text(levers(axle_height=0.9))
    code, stderr, entry = sim(cli, robot)
    assert code == 0, stderr
    assert entry["why_no_drive"] == f"not a vehicle: no wheels ({LEVERS})"
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == [
        ("drop", "passed"), ("drive", "skipped"), ("spin", "skipped")]
    assert "cannot drive" not in stderr


def test_the_same_joints_at_the_floor_are_wheels(cli, tmp_path):
    robot = tmp_path / "levers.urdf"
    robot.write_text(levers(axle_height=0.05))
    code, stderr, entry = sim(cli, robot, "--scenario", "drop")
    assert code == 0, stderr
    assert entry["why_no_drive"] is None
    assert entry["drive"]["kind"] == "differential"


def test_a_package_leaves_the_levers_out_and_still_drives_its_car(run_mcar, tmp_path):
    urdf = tmp_path / "urdf"
    urdf.mkdir()
    (urdf / "levers.urdf").write_text(levers(axle_height=0.9))
    (urdf / "car.urdf").write_text(two_wheeler())
    result = run_mcar("sim", "urdf", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert f"mcar: urdf/levers.urdf: not simulated: not a vehicle: no wheels ({LEVERS})" \
        in result.stderr.splitlines()
    assert result.stderr.splitlines()[-1] == "mcar sim: 3 passed, 0 failed, 0 skipped in 1 file"


def test_ci_passes_the_levers_as_no_vehicle(run_mcar, tmp_path):
    package = tmp_path / "lever_description"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text(
        "<package format='3'><name>lever_description</name></package>")
    (package / "urdf/levers.urdf").write_text(levers(axle_height=0.9))
    result = run_mcar("ci", package, "--no-render", "--no-gazebo", "--build-dir",
                      tmp_path / "build", cwd=tmp_path, timeout=300)
    assert result.returncode == 0, result.stderr
    assert (f"mcar: levers.urdf: not simulated: not a vehicle: no wheels ({LEVERS})"
            in result.stderr.splitlines()), result.stderr
    row = result.stdout.splitlines()[1].split()
    assert row[0] == "levers.urdf" and row[-5:] == ["not", "a", "vehicle", "-", "ok"], \
        result.stdout


def test_the_exports_say_which_is_a_vehicle_in_their_manifests(run_mcar, tmp_path):
    for height, vehicle in ((0.9, False), (0.05, True)):
        folder = tmp_path / f"at_{height}"
        folder.mkdir()
        (folder / "levers.urdf").write_text(levers(axle_height=height))
        result = run_mcar("export", "levers.urdf", "--to", "mjcf", "-o", "out", cwd=folder)
        assert result.returncode == 0, result.stderr
        manifest = json.loads((folder / "out/mcar-export.json").read_text())
        assert manifest["vehicle"] is vehicle, height


def test_a_large_robots_rest_pose_tells_levers_from_wheels_alike(tmp_path):
    # From 2,000 links the check's rest pose is numpy's (rest_pose_arrays.ArraysPose).
    from mobile_car.check.checker import LARGE_ROBOT, check_input
    from mobile_car.load.inputs import RobotInput
    from mobile_car.sim.vehicle import not_a_vehicle

    studs = "".join(f"""
  <joint name="stud_{i}_joint" type="fixed"><parent link="base_link"/>
    <child link="stud_{i}"/><origin xyz="0 0 0.1"/></joint>
  <link name="stud_{i}"><collision><geometry><box size="0.01 0.01 0.01"/></geometry>
  </collision></link>""" for i in range(LARGE_ROBOT))
    verdicts = []
    for height in (0.9, 0.05):
        robot = tmp_path / f"levers_{height}.urdf"
        robot.write_text(levers(axle_height=height).replace("</robot>", studs + "</robot>"))
        checked = check_input(RobotInput(robot))
        assert type(checked.rest).__name__ == "ArraysPose"
        verdicts.append(not_a_vehicle(checked.robot, checked.rest))
    assert [str(v) if v else None for v in verdicts] == [
        f"not a vehicle: no wheels ({LEVERS})", None]


def test_one_disc_at_the_floor_and_one_high_up_is_one_wheel_and_a_lever(tmp_path):
    # ABB's IRB 6640 balances its arm on a cylinder and piston, each on a continuous joint:
    # the cylinder's lowest point is near the floor, the piston's high up.
    from mobile_car.check.checker import check_input
    from mobile_car.load.inputs import RobotInput
    from mobile_car.sim.vehicle import not_a_vehicle

    text = levers(axle_height=0.9)
    low = text.index('<origin xyz="0 -0.2 0.9"/>')
    robot = tmp_path / "lopsided.urdf"
    robot.write_text(text[:low] + '<origin xyz="0 -0.2 0.05"/>' + text[low + 26:])
    checked = check_input(RobotInput(robot))
    assert str(not_a_vehicle(checked.robot, checked.rest)) == (
        "not a vehicle: one wheel (lever_right on a continuous joint; continuous joint "
        "lever_left_joint turns about a level axis high above the floor (a lever))")
