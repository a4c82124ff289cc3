"""A collision mesh MuJoCo cannot read as it is is read and converted once a run, however
many <mesh> elements name it (Unitree Go1 names calf.dae four times, and specs' ray
scenes ask again for the same visuals): the file MuJoCo reads is the same."""

from __future__ import annotations

import os

from mobile_car.load import mesh_reader
from mobile_car.sim.meshes import mujoco_mesh

TRIANGLE = """solid t
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex {x} 0 0
  vertex 0 1 0
 endloop
endfacet
endsolid t
"""


def test_a_mesh_named_three_times_is_read_once_and_again_after_an_edit(tmp_path, monkeypatch):
    read = []
    original = mesh_reader.load_mesh

    def counted(path, *args, **kwargs):
        read.append(os.path.basename(path))
        return original(path, *args, **kwargs)

    monkeypatch.setattr(mesh_reader, "load_mesh", counted)
    monkeypatch.setenv("MCAR_CACHE_DIR", str(tmp_path / "cache"))
    ascii_stl = tmp_path / "part.stl"  # ASCII: converted to binary STL for MuJoCo
    ascii_stl.write_text(TRIANGLE.format(x=1))
    first = mujoco_mesh(ascii_stl)
    assert [mujoco_mesh(ascii_stl) for _ in range(2)] == [first, first]
    assert read == ["part.stl"]
    assert first.read_bytes()[80:84] == (1).to_bytes(4, "little")  # one triangle
    ascii_stl.write_text(TRIANGLE.format(x=2))
    os.utime(ascii_stl, ns=(1, 1))
    second = mujoco_mesh(ascii_stl)
    assert read == ["part.stl", "part.stl"] and second != first
