"""``mcar specs`` reads each mesh file once a run (load/mesh_cache.py): sim's model, the
sensors' scene of the robot and the ray proof each read the visual meshes, render's reader
and sim's, once for every <mesh> naming them (Unitree Go1: 26 reads of 6 COLLADA files);
the figures are those of a run that keeps nothing."""

from __future__ import annotations

import contextlib

import trimesh
from specs.sensor_robots import lidar_link, link, ray_sensor, robot

from mobile_car.check.checker import check_input
from mobile_car.load import mesh_cache, mesh_reader
from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions

MESH = '<visual><geometry><mesh filename="post.dae"/></geometry></visual>'


def _figures(sections) -> list:
    return [(f.key, repr(f.value), f.source) for s in sections for f in s.figures]


def test_three_posts_of_one_collada_file_are_read_once_with_the_same_figures(
        tmp_path, monkeypatch):
    from mobile_car.specs.compute import compute

    monkeypatch.setenv("MCAR_CACHE_DIR", str(tmp_path / "cache"))
    dae = trimesh.creation.box([0.04, 0.04, 0.3]).export(file_type="dae")
    (tmp_path / "post.dae").write_bytes(dae if isinstance(dae, bytes) else dae.encode())
    posts = [link(f"post_{n}", "base_link", (x, 0.06, 0.3), MESH)
             for n, x in enumerate((-0.1, 0.0, 0.1))]
    path = tmp_path / "robot.urdf"
    path.write_text(robot(lidar_link(), ray_sensor("lidar_link"), *posts))
    checked = check_input(RobotInput(path), LoadOptions())
    read = []
    reading = mesh_reader._read

    def counted(mesh, shown, kwargs, textures):
        read.append((mesh.name, textures))
        return reading(mesh, shown, kwargs, textures)

    monkeypatch.setattr(mesh_reader, "_read", counted)
    kept = _figures(compute(checked, {"proof": True}))
    # once for the readers of its geometry alone (sim's), once with its textures (the
    # sensors' scene, render's reader): a scene read without its images is not one to
    # draw, and one read with them makes a texture atlas when joined into one mesh
    assert sorted(read) == [("post.dae", False), ("post.dae", True)]
    assert any(key.startswith("sensors.") for key, _, _ in kept)
    read.clear()
    monkeypatch.setattr(mesh_cache, "kept", contextlib.nullcontext)
    assert _figures(compute(checked, {"proof": True})) == kept
    assert len(read) > 3, read  # (every reader, every <mesh>)
