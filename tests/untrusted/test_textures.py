"""Textures and materials are inputs (issue 32, item 4): an OBJ's ``.mtl`` and the texture
it maps are never overwritten by an output, and editing either redraws the picture.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest
from PIL import Image

URDF = """<?xml version="1.0"?>
<robot name="textured">
  <link name="base">
    <visual><geometry><mesh filename="meshes/quad.obj"/></geometry></visual>
  </link>
</robot>
"""
OBJ = """mtllib quad.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl skin
f 1/1 2/2 3/3
f 1/1 3/3 4/4
"""
MTL = "newmtl skin\nKd 1 1 1\nmap_Kd tex.png\n"


def _package(tmp: Path, colour=(200, 30, 30)) -> Path:
    meshes = tmp / "meshes"
    meshes.mkdir()
    (meshes / "quad.obj").write_text(OBJ)
    (meshes / "quad.mtl").write_text(MTL)
    Image.new("RGB", (8, 8), colour).save(meshes / "tex.png")
    robot = tmp / "robot.urdf"
    robot.write_text(URDF)
    return robot


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.mark.parametrize("robot, output", [
    ("robot.urdf", "meshes/tex.png"),  # named as the output
    ("tex.urdf", "meshes/"),  # a picture named after its robot, in the mesh folder
])
def test_a_picture_may_not_overwrite_the_texture_it_reads(run_mcar, tmp_path, robot, output):
    _package(tmp_path)
    if robot != "robot.urdf":
        (tmp_path / robot).write_bytes((tmp_path / "robot.urdf").read_bytes())
    texture = tmp_path / "meshes" / "tex.png"
    before = _sha(texture)
    result = run_mcar("render", robot, "-o", output, "--renderer", "raycast",
                      "--size", "64x64", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines()[0] == (
        "meshes/tex.png: error: would overwrite meshes/tex.png, a file this run reads; "
        "write the output somewhere else")
    assert _sha(texture) == before


def test_editing_the_texture_or_the_material_redraws_the_picture(run_mcar, tmp_path,
                                                                  quiet_renderer):
    _package(tmp_path)
    args = ("render", "robot.urdf", "-o", "out/", *quiet_renderer, "--size", "64x64")
    first = run_mcar(*args, cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    picture = tmp_path / "out" / "robot.png"
    drawn = _sha(picture)
    again = run_mcar(*args, cwd=tmp_path)
    assert "1 unchanged" in again.stderr  # nothing changed: not redrawn
    Image.new("RGB", (8, 8), (30, 30, 200)).save(tmp_path / "meshes" / "tex.png")
    edited = run_mcar(*args, cwd=tmp_path)
    assert "1 rendered" in edited.stderr, edited.stderr
    assert _sha(picture) != drawn  # the new colour shows
    recoloured = _sha(picture)
    (tmp_path / "meshes" / "quad.mtl").write_text("newmtl skin\nKd 1 1 1\n")  # no texture
    edited = run_mcar(*args, cwd=tmp_path)
    assert "1 rendered" in edited.stderr, edited.stderr
    assert _sha(picture) != recoloured
