"""Hostile mesh files: every mesh is measured before it is read (issue 32, item 2).

Each attack is made in tmp_path at test time and given to the installed ``mcar`` as a
subprocess: a zipped COLLADA (``.zae``) inflating far past ``MCAR_MAX_MESH_MB``, a sparse
2 GB STL, an OBJ of 1.5 million faces on 3 vertices, a binary STL whose header lies, a
PLY claiming 10**9 faces. Over a limit: a one-line warning at the ``<mesh>``'s line that
names the limit and its variable, a magenta box in the picture, a quick exit, bounded
memory, the inputs untouched. A header that contradicts its file is a broken mesh (W207).
"""

from __future__ import annotations

import hashlib
import os
import struct
import subprocess
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.conftest import MCAR

URDF = """<?xml version="1.0"?>
<robot name="victim">
  <link name="base">
    <visual><geometry><box size="0.6 0.4 0.2"/></geometry></visual>
  </link>
  <link name="arm">
    <visual>
      <geometry>
        <mesh filename="{mesh}"/>
      </geometry>
    </visual>
  </link>
  <joint name="fix" type="fixed">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.4"/>
  </joint>
</robot>
"""
MESH_LINE = 9  # the <mesh> element's line in URDF
SECONDS = 30  # generous for a loaded 2-core machine; these ran in 2-6 s
PEAK_MB = 1024  # the .zae's 256 MB cap, decompressed, plus numpy and trimesh


def _robot(tmp: Path, mesh_name: str) -> Path:
    robot = tmp / "robot.urdf"
    robot.write_text(URDF.format(mesh=mesh_name), encoding="utf-8")
    return robot


def _zae_bomb(tmp: Path) -> Path:
    """A .zae whose one member inflates to 512 MB of zeros (twice the cap), written in a
    stream: the test never holds more than one 16 MB block."""
    path = tmp / "bomb.zae"
    block = bytes(16 << 20)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as archive:
        with archive.open("bomb.dae", "w", force_zip64=True) as member:
            for _ in range(32):
                member.write(block)
    return path


def _sparse_stl(tmp: Path) -> Path:
    path = tmp / "sparse.stl"
    with open(path, "wb") as handle:
        handle.truncate(2 << 30)  # 2 GB, no block written
    return path


def _many_faces_obj(tmp: Path) -> Path:
    path = tmp / "many.obj"
    with open(path, "wb") as handle:
        handle.write(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + b"f 1 2 3\n" * 1_500_000)
    return path


def _claiming_ply(tmp: Path) -> Path:
    path = tmp / "claims.ply"
    path.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                     b"property float y\nproperty float z\nelement face 1000000000\n"
                     b"property list uchar int vertex_indices\nend_header\n"
                     b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    return path


def _lying_stl(tmp: Path) -> Path:
    """A binary STL whose header says 10**9 triangles; it holds three."""
    path = tmp / "lies.stl"
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 10**9) + triangle * 3)
    return path


def _digests(folder: Path) -> dict[str, str]:
    """Each input's hash; a 2 GB sparse file by its size (hashing it would be the test's cost)."""
    found = {}
    for path in folder.iterdir():
        if path.suffix == ".png":
            continue
        size = path.stat().st_size
        found[path.name] = str(size) if size > 64 << 20 else \
            hashlib.sha256(path.read_bytes()).hexdigest()
    return found


def _run(*args, cwd: Path, env=None) -> tuple[subprocess.CompletedProcess, float, int]:
    """mcar ARGS under /usr/bin/time: (result, seconds, peak resident MB)."""
    if not os.path.exists("/usr/bin/time"):
        pytest.skip("/usr/bin/time is not installed (Debian package time)")
    full_env = {**os.environ, **(env or {})}
    full_env.pop("ROS_PACKAGE_PATH", None)
    started = time.monotonic()
    result = subprocess.run(["/usr/bin/time", "-f", "peak-kb %M", str(MCAR), *map(str, args)],
                            cwd=cwd, capture_output=True, text=True, env=full_env,
                            timeout=300)
    seconds = time.monotonic() - started
    lines = result.stderr.splitlines()
    peak = [line for line in lines if line.startswith("peak-kb ")]
    result.stderr = "\n".join(line for line in lines if not line.startswith(
        ("peak-kb ", "Command exited with non-zero status")))
    return result, seconds, int(peak[-1].split()[1]) // 1024


def _magenta(picture: Path) -> int:
    """Pixels of the placeholder: strong red and blue, little green (shaded magenta)."""
    with Image.open(picture) as image:
        rgb = np.asarray(image.convert("RGB")).astype(int)
    red, green, blue = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return int(((red > 120) & (blue > 120) & (green < 0.5 * np.minimum(red, blue))).sum())


OVER_LIMIT = [
    (_zae_bomb, "bomb.zae", "decompresses to more than 256 MB; set MCAR_MAX_MESH_MB to raise "
     "the limit"),
    (_sparse_stl, "sparse.stl", "2048 MB, over the limit of 256 MB for a mesh file; set "
     "MCAR_MAX_MESH_MB to raise it"),
    (_many_faces_obj, "many.obj", "faces, over the limit of 1000000 for a mesh; set "
     "MCAR_MAX_MESH_FACES to raise it"),
    (_claiming_ply, "claims.ply", "1000000000 faces, over the limit of 1000000 for a mesh; "
     "set MCAR_MAX_MESH_FACES to raise it"),
]


@pytest.mark.parametrize(("make", "name", "reason"), OVER_LIMIT,
                         ids=[case[1] for case in OVER_LIMIT])
def test_a_mesh_over_a_limit_is_a_located_warning_and_a_magenta_box(tmp_path, make, name,
                                                                    reason, quiet_renderer):
    make(tmp_path)
    robot = _robot(tmp_path, name)
    before = _digests(tmp_path)
    result, seconds, peak_mb = _run("render", robot, "-o", "out.png", *quiet_renderer,
                                    "--size", "320x240", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    warning, summary = result.stderr.splitlines()
    assert warning.startswith(f"robot.urdf:{MESH_LINE}: warning: mesh '{name}' not read: ")
    assert warning.endswith(f"{reason}; drawn as a magenta box [W210]")
    assert summary.startswith("1 picture in ")
    assert seconds < SECONDS
    assert peak_mb < PEAK_MB
    assert _magenta(tmp_path / "out.png") > 200  # the box, seen from above at the side
    after = _digests(tmp_path)
    assert {name: after.get(name) for name in before} == before


def test_without_the_marker_the_picture_has_no_magenta(tmp_path, quiet_renderer):
    """The pixel test above can fail: a robot without the over-limit mesh shows none."""
    robot = _robot(tmp_path, "none.stl")
    robot.write_text(robot.read_text().replace(
        '<mesh filename="none.stl"/>', '<box size="0.2 0.2 0.2"/>'))
    result, _, _ = _run("render", robot, "-o", "out.png", *quiet_renderer, "--size", "320x240",
                        cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert _magenta(tmp_path / "out.png") == 0


def test_check_warns_the_same_way_without_reading_the_mesh(tmp_path):
    _many_faces_obj(tmp_path)
    _sparse_stl(tmp_path)
    robot = _robot(tmp_path, "many.obj")
    result, seconds, peak_mb = _run("check", "-q", robot, cwd=tmp_path)
    assert result.returncode == 0  # a warning
    assert result.stderr.splitlines()[0] == (
        f"robot.urdf:{MESH_LINE}: warning: mesh 'many.obj' not read: at least 1048573 faces, "
        "over the limit of 1000000 for a mesh; set MCAR_MAX_MESH_FACES to raise it; drawn "
        "as a magenta box [W210]")
    assert peak_mb < 200  # trimesh (and numpy) never loaded: the scan stops early
    robot.write_text(URDF.format(mesh="sparse.stl"))
    result, seconds, peak_mb = _run("check", "-q", robot, cwd=tmp_path)
    assert "2048 MB, over the limit of 256 MB" in result.stderr
    assert seconds < 10 and peak_mb < 200  # refused by its size, not read


def test_the_limits_can_be_raised(tmp_path):
    _many_faces_obj(tmp_path)
    robot = _robot(tmp_path, "many.obj")
    result, _, _ = _run("check", "-q", robot, cwd=tmp_path,
                        env={"MCAR_MAX_MESH_FACES": "2e6"})
    assert result.returncode == 0 and "W2" not in result.stderr  # read, and sound
    result, _, _ = _run("check", "-q", robot, cwd=tmp_path, env={"MCAR_MAX_MESH_FACES": "-1"})
    assert result.returncode == 2
    assert result.stderr.strip() == ("mcar: error: MCAR_MAX_MESH_FACES=-1: must be between 1 "
                                     "and 1e+10 faces")


def test_a_binary_stl_whose_header_lies_is_a_broken_mesh(tmp_path, quiet_renderer):
    _lying_stl(tmp_path)
    robot = _robot(tmp_path, "lies.stl")
    before = _digests(tmp_path)
    result, seconds, _ = _run("render", robot, "-o", "out.png", *quiet_renderer, cwd=tmp_path)
    assert result.returncode == 0  # drawn, the mesh as a marker: a warning, as in check
    assert result.stderr.splitlines()[0] == (
        f"robot.urdf:{MESH_LINE}: warning: mesh 'lies.stl' cannot be loaded: its binary STL "
        "header says 1000000000 triangles, and the file of 234 bytes holds at most 3 [W207]")
    assert _magenta(tmp_path / "out.png") > 200
    after = _digests(tmp_path)
    assert {name: after.get(name) for name in before} == before


def test_collada_nodes_instancing_nodes_are_counted_not_expanded(tmp_path):
    """30 library nodes each instancing the next twice: 2**30 copies of one triangle."""
    nodes = "".join(
        f'<node id="n{i}"><instance_node url="#n{i + 1}"/><instance_node url="#n{i + 1}"/>'
        f'</node>' for i in range(30))
    dae = ('<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/'
           'COLLADASchema" version="1.4.1"><library_geometries><geometry id="g"><mesh>'
           '<triangles count="1"><p>0 1 2</p></triangles></mesh></geometry>'
           f'</library_geometries><library_nodes>{nodes}<node id="n30"><instance_geometry '
           'url="#g"/></node></library_nodes><library_visual_scenes><visual_scene id="s">'
           '<node><instance_node url="#n0"/></node></visual_scene></library_visual_scenes>'
           '</COLLADA>')
    (tmp_path / "nested.dae").write_text(dae)
    robot = _robot(tmp_path, "nested.dae")
    result, seconds, _ = _run("check", "-q", robot, cwd=tmp_path)
    assert f"not read: {2**30} faces, over the limit of 1000000" in result.stderr
    assert seconds < SECONDS


def test_collada_entities_are_never_expanded(tmp_path, quiet_renderer):
    """A billion laughs in a COLLADA: mcar parses it without entities and hands pycollada
    (whose parser allows huge trees) its root element only, the references unexpanded: a
    broken mesh at once, in bounded memory, the rest of the robot drawn."""
    entities = "".join(f'<!ENTITY e{i} "{f"&e{i - 1};" * 10 if i else "lol"}">'
                       for i in range(10))
    box = (Path(__file__).parents[1] / "load" / "meshes_as_rviz" / "box_zup.dae").read_text()
    (tmp_path / "laughs.dae").write_text(box.replace(
        "<COLLADA ", f"<!DOCTYPE COLLADA [{entities}]>\n<COLLADA ", 1).replace(
        "<asset>", "<asset><contributor><author>&e9;</author></contributor>", 1))
    robot = _robot(tmp_path, "laughs.dae")
    result, seconds, peak_mb = _run("render", robot, "-o", "out.png", *quiet_renderer,
                                    cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stderr.startswith(f"robot.urdf:{MESH_LINE}: warning: mesh 'laughs.dae' "
                                    "cannot be loaded: ")
    assert seconds < SECONDS and peak_mb < 400
    assert _magenta(tmp_path / "out.png") > 200
