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
