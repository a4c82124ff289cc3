"""mcar specs' sensors section reads the robot's visual meshes too (render's assembly for
the trimesh cast, sim's mesh preparation for MuJoCo's proof, which before this read only
collision meshes). A description names a "visual" outside its folders
(``../outside/secret.stl``, ``file:///``...): it is refused by the one resolver
(PackageSearch.resolve_uri) before trimesh or MuJoCo opens it, left out with a note, and
never shapes a figure. The planted file is a cube that would block the lidar: the control
puts the same cube inside the robot's folder, and the sector appears in both engines."""

from __future__ import annotations

import shutil

from hostile import cube_stl
from specs.sensor_robots import LIDAR_Z, lidar_link, link, ray_sensor, robot, sensors_of, values


def _robot(filename: str) -> str:
    visual = (f'<visual><origin xyz="0.2 0 {LIDAR_Z}"/><geometry><mesh filename="{filename}"/>'
              "</geometry></visual>")
    return robot(lidar_link(), link("cube", "base_link", (0, 0, 0), visual),
                 ray_sensor("lidar_link"))


def test_a_visual_mesh_outside_the_robot_folders_is_never_read_for_its_sensors(tmp_path):
    outside, package = tmp_path / "outside", tmp_path / "robot"
    outside.mkdir()
    package.mkdir()
    (outside / "secret.stl").write_bytes(cube_stl(0.1, b"MCAR-SECRET"))
    for name in ("../outside/secret.stl", f"file://{outside}/secret.stl"):
        _, section = sensors_of(package / "robot.urdf", _robot(name))
        assert values(section)["sensors.scanner.blocked"] == [], name
        proof = section.figure("sensors.scanner.blocked").proof
        assert proof.agrees and proof.measured == []
        assert "link cube: a visual mesh not read is left out of what its sensors see" in \
            section.notes
        refused = f"sensors' proof: link cube: mesh {name} left out:"
        assert any(note.startswith(refused) for note in section.notes), section.notes
    # Control: the same cube inside the robot's folder blocks the scan in both engines.
    shutil.copy(outside / "secret.stl", package / "cube.stl")
    _, control = sensors_of(package / "robot.urdf", _robot("cube.stl"))
    sectors = values(control)["sensors.scanner.blocked"]
    assert len(sectors) == 1 and control.figure("sensors.scanner.blocked").proof.measured == \
        sectors


def test_without_proofs_mujoco_alone_refuses_the_outside_mesh_and_the_oversized_one(
        tmp_path, monkeypatch):
    # `mcar specs --no-proof`: MuJoCo's cast is the figure, trimesh never runs; the same
    # resolver and limits (sim/meshes.py) keep the planted cube out.
    outside, package = tmp_path / "outside", tmp_path / "robot"
    outside.mkdir()
    package.mkdir()
    (outside / "secret.stl").write_bytes(cube_stl(0.1, b"MCAR-SECRET"))
    shutil.copy(outside / "secret.stl", package / "cube.stl")
    for name in ("../outside/secret.stl", f"file://{outside}/secret.stl"):
        _, section = sensors_of(package / "robot.urdf", _robot(name), {"proof": False})
        figure = section.figure("sensors.scanner.blocked")
        assert figure.value == [] and figure.proof is None, name
        assert "by MuJoCo's ray casting" in figure.source
        assert any(note.startswith(f"sensors: link cube: mesh {name} left out:")
                   for note in section.notes), section.notes
    monkeypatch.setenv("MCAR_MAX_MESH_FACES", "10")  # the cube has 12
    _, section = sensors_of(package / "robot.urdf", _robot("cube.stl"), {"proof": False})
    assert values(section)["sensors.scanner.blocked"] == []
    assert any(note.startswith("sensors: link cube: mesh cube.stl left out:")
               for note in section.notes), section.notes
    # Control: within the limit, inside the folder, MuJoCo sees the cube block the scan.
    monkeypatch.setenv("MCAR_MAX_MESH_FACES", "12")
    _, control = sensors_of(package / "robot.urdf", _robot("cube.stl"), {"proof": False})
    assert len(values(control)["sensors.scanner.blocked"]) == 1
    assert "by MuJoCo's ray casting" in control.figure("sensors.scanner.blocked").source
