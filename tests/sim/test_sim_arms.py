"""Arms are no vehicles: what mcar sim and its callers (a package's files, ci, an export's
manifest) decide of a robot whose joints turn without end about upright axes (Kinova
Gen3's joints 1, 3, 5 and 7 are continuous), made at test time."""

from __future__ import annotations

import json

from sim.robot_makers import swivel_arm, two_wheeler
from sim.sim_json import sim

SWIVELS = "continuous joints joint_1, joint_3 turn about upright axes (swivels)"


def test_an_arm_on_endless_upright_joints_is_no_vehicle_and_passes_its_drop(cli, tmp_path):
    # It was a vehicle with no drive: drive and spin failed, "cannot drive this vehicle".
    robot = tmp_path / "arm.urdf"
    robot.write_text(swivel_arm())
    code, stderr, entry = sim(cli, robot)
    assert code == 0, stderr
    assert entry["why_no_drive"] == f"not a vehicle: no wheels ({SWIVELS})"
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == [
        ("drop", "passed"), ("drive", "skipped"), ("spin", "skipped")]
    assert "cannot drive" not in stderr


def test_a_package_leaves_the_arm_out_and_still_drives_its_car(run_mcar, tmp_path):
    urdf = tmp_path / "urdf"
    urdf.mkdir()
    (urdf / "arm.urdf").write_text(swivel_arm())
    (urdf / "car.urdf").write_text(two_wheeler())
    result = run_mcar("sim", "urdf", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert f"mcar: urdf/arm.urdf: not simulated: not a vehicle: no wheels ({SWIVELS})" \
        in result.stderr.splitlines()
    assert result.stderr.splitlines()[-1] == "mcar sim: 3 passed, 0 failed, 0 skipped in 1 file"


def test_the_arms_export_is_no_vehicle_in_its_manifest(run_mcar, tmp_path):
    (tmp_path / "arm.urdf").write_text(swivel_arm())
    result = run_mcar("export", "arm.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    manifest = json.loads((tmp_path / "out/mcar-export.json").read_text())
    assert manifest["vehicle"] is False and manifest["drive"] is None


def reaching_arm(world: bool) -> str:
    """A 2 kg base with a 5 kg arm reaching 0.6 m out at its zero pose: on a floor it tips
    onto its hand (a UR arm at 0). With ``world``, its root is a link named world, which
    Gazebo welds in place (franka's panda with gazebo:=true)."""
    anchor = ('<link name="world"/><joint name="world_joint" type="fixed"><parent '
              'link="world"/><child link="base_link"/></joint>') if world else ""
    return f"""<?xml version="1.0"?>
<robot name="reach">{anchor}
  <link name="base_link">
    <collision><origin xyz="0 0 0.05"/><geometry><cylinder radius="0.06" length="0.1"/>
    </geometry></collision>
    <inertial><origin xyz="0 0 0.05"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="arm"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="100" velocity="1"/>
  </joint>
  <link name="arm">
    <collision><origin xyz="0.35 0 0" rpy="0 1.5708 0"/><geometry>
      <cylinder radius="0.03" length="0.6"/></geometry></collision>
    <inertial><origin xyz="0.35 0 0"/><mass value="5"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.15" iyz="0" izz="0.15"/></inertial>
  </link>
</robot>
"""


def test_a_robot_fixed_to_the_world_is_not_dropped_nor_tilted(cli, run_mcar, tmp_path):
    # Its drop used to fail: "pitch 1.07 deg (bound <= 1.00 deg)" (franka's panda), and
    # specs judged slopes it cannot meet: it is bolted down.
    robot = tmp_path / "reach.urdf"
    robot.write_text(reaching_arm(world=True))
    code, stderr, entry = sim(cli, robot)
    why = ("not a vehicle: fixed to the world (joint world_joint (fixed) holds base_link to "
           "link 'world')")
    assert code == 0, stderr
    assert entry["why_no_drive"] == why
    assert [(s["name"], s["status"], s["message"]) for s in entry["scenarios"]] == [
        (name, "skipped", why) for name in ("drop", "drive", "spin")]
    result = run_mcar("specs", "reach.urdf", "--no-proof", "--format", "json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert ("reach.urdf: no statics: fixed to the world (joint world_joint (fixed) holds "
            "base_link to link 'world')") in result.stderr
    assert "W505" not in result.stderr


def test_the_same_arm_on_the_floor_tips_and_its_drop_fails_saying_onto_what(cli, tmp_path):
    # It failed on its figures alone ("height error 1.41 mm; pitch 1.34 deg": UR5e),
    # with nothing to say it had lain down on its wrist.
    robot = tmp_path / "reach.urdf"
    robot.write_text(reaching_arm(world=False))
    code, stderr, entry = sim(cli, robot)
    assert code == 1
    drop = entry["scenarios"][0]
    assert drop["status"] == "failed"
    assert drop["message"].startswith(
        "tipped over onto arm, which the floor does not reach as it rests at 0 (a robot "
        "bolted down is fixed to a root link named world); ")


def test_an_arm_set_on_the_floor_stands_on_a_part_not_on_a_castor(run_mcar, tmp_path):
    # UR5e's W505 said "the contacts of base_link_inertia (castor)": a robot with no
    # wheels has no castor.
    (tmp_path / "reach.urdf").write_text(reaching_arm(world=False))
    result = run_mcar("specs", "reach.urdf", "--no-proof", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert ("reach.urdf: warning: its centre of mass is not inside the polygon it stands on "
            "(the contacts of base_link (part) at rest): it stands only balanced [W505]"
            ) in result.stderr.splitlines()
    assert "castor)" not in result.stdout + result.stderr
