"""What check knows of a mesh (that it loads, its box) is kept in the user's cache folder,
sealed (mobile_car/load/mesh_facts.py). The cache spares reading: the next check of the
same files opens none of them, a fresh copy of a COLLADA is known by its bytes. It is an
input like any other: a planted record (a CI cache shared with a pull request's jobs)
sealed with another key is not believed; the control shows the same record, sealed with
the user's own key, would be. An edited mesh is read again; a damaged record, or a FIFO
where a record should be, is passed over."""

from __future__ import annotations

import json
import math
import os
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import REPO

MESHES = REPO / "tests" / "load" / "meshes_as_rviz"
# Checks the robot in a fresh process and prints its extents, and whether it needed
# trimesh or numpy (that is, whether it read a mesh).
CHECK = """
import json, sys
from pathlib import Path
from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions
result = check_input(RobotInput(Path(sys.argv[1])), LoadOptions())
print(json.dumps({"extents": result.extents,
                  "rules": [d.rule for d in result.diagnostics],
                  "read": sorted(m for m in ("trimesh", "numpy") if m in sys.modules)}))
"""


def _stl(path: Path, triangles: int, corner=(0.4, 0.2, 0.1)) -> Path:
    """A binary STL of ``triangles`` copies of one triangle spanning a box from the origin
    to ``corner``, its header starting "solid" as an ASCII STL's does."""
    x, y, z = corner
    record = struct.pack("<12x9f2x", 0, 0, 0, x, y, 0, 0, 0, z)
    path.write_bytes(b"solid but binary".ljust(80) + struct.pack("<I", triangles) +
                     record * triangles)
    return path


# Above what a run reads without records (mesh_facts.DIRECT_TRIANGLES): recorded.
LARGE = 10_001


def _robot(folder: Path, mesh: str) -> Path:
    robot = folder / "r.urdf"
    robot.write_text(f'<robot name="r"><link name="a"><visual><geometry><mesh filename='
                     f'"{mesh}"/></geometry></visual></link></robot>\n')
    return robot


def _check(robot: Path, cache: Path) -> dict:
    done = subprocess.run([sys.executable, "-c", CHECK, str(robot)], capture_output=True,
                          text=True, env={**os.environ, "MCAR_CACHE_DIR": str(cache)},
                          timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.mark.parametrize("mesh", ["box_mm.dae", "large.stl"])
def test_the_second_check_reads_no_mesh(tmp_path, mesh):
    if mesh.endswith(".stl"):
        _stl(tmp_path / mesh, LARGE)
    else:
        shutil.copy(MESHES / mesh, tmp_path / mesh)
    robot = _robot(tmp_path, mesh)
    first = _check(robot, tmp_path / "cache")
    assert first["read"] and first["extents"] == pytest.approx([0.4, 0.2, 0.1])
    second = _check(robot, tmp_path / "cache")
    assert second == {**first, "read": []}


def test_a_copy_elsewhere_is_known_by_its_bytes(tmp_path):
    """A fresh clone, or a CI job that keeps the cache: new inodes, the same bytes."""
    for name in ("one", "two"):
        (tmp_path / name).mkdir()
        shutil.copy(MESHES / "box_mm.dae", tmp_path / name / "box_mm.dae")
    assert _check(_robot(tmp_path / "one", "box_mm.dae"), tmp_path / "cache")["read"]
    again = _check(_robot(tmp_path / "two", "box_mm.dae"), tmp_path / "cache")
    assert "trimesh" not in again["read"]  # hashed, not parsed
    assert again["extents"] == pytest.approx([0.4, 0.2, 0.1])


def test_an_edited_mesh_is_read_again(tmp_path):
    mesh = tmp_path / "part.dae"
    mesh.write_bytes((MESHES / "box_mm.dae").read_bytes())
    robot = _robot(tmp_path, "part.dae")
    assert _check(robot, tmp_path / "cache")["extents"] == pytest.approx([0.4, 0.2, 0.1])
    mesh.write_bytes(mesh.read_bytes().replace(b'meter="0.001"', b'meter="0.002"'))
    assert _check(robot, tmp_path / "cache")["extents"] == pytest.approx([0.8, 0.4, 0.2])


def _forge(cache: Path, key_cache: Path) -> int:
    """Rewrite every record in ``cache`` to say the mesh is 100 m across and loads, sealed
    with the key kept in ``key_cache``; the number of records rewritten."""
    from mobile_car import record_seal

    saved = os.environ.get(record_seal.CACHE_DIR_ENV)
    os.environ[record_seal.CACHE_DIR_ENV] = str(key_cache)
    count = 0
    try:
        for path in (cache / "mesh-facts").glob("*.json"):
            document = json.loads(path.read_text())
            section = next(key for key in document if key != "seal")
            document[section]["facts"]["bounds"] = [[0, 0, 0], [100.0, 1.0, 1.0]]
            document[section]["facts"]["problem"] = None
            path.write_text(record_seal.sealed_text(section, document[section]))
            count += 1
    finally:
        if saved is None:
            os.environ.pop(record_seal.CACHE_DIR_ENV)
        else:
            os.environ[record_seal.CACHE_DIR_ENV] = saved
    return count


def test_a_planted_record_is_not_believed(tmp_path):
    shutil.copy(MESHES / "box_mm.dae", tmp_path / "box_mm.dae")
    robot = _robot(tmp_path, "box_mm.dae")
    victim = tmp_path / "victim"
    assert _check(robot, victim)["extents"] == pytest.approx([0.4, 0.2, 0.1])
    attacker = tmp_path / "attacker"
    _check(robot, attacker)  # the attacker's own key, made by their own run
    assert _forge(victim, attacker) == 2  # the record by path and the one by content
    planted = _check(robot, victim)
    assert planted["extents"] == pytest.approx([0.4, 0.2, 0.1]) and planted["read"]


def test_control_the_same_record_under_the_user_s_key_is_believed(tmp_path):
    shutil.copy(MESHES / "box_mm.dae", tmp_path / "box_mm.dae")
    robot = _robot(tmp_path, "box_mm.dae")
    cache = tmp_path / "cache"
    _check(robot, cache)
    assert _forge(cache, cache) == 2
    forged = _check(robot, cache)
    assert forged["extents"] == pytest.approx([100.0, 1.0, 1.0]) and forged["read"] == []
    assert forged["rules"] == ["W211"]  # and check judges the size it was told


def test_a_damaged_record_or_a_fifo_in_its_place_is_passed_over(tmp_path):
    _stl(tmp_path / "part.stl", LARGE)
    robot = _robot(tmp_path, "part.stl")
    cache = tmp_path / "cache"
    _check(robot, cache)
    [record] = (cache / "mesh-facts").glob("*.json")
    record.write_text('{"seal": "0", "mesh-path": [')
    assert _check(robot, cache)["extents"] == pytest.approx([0.4, 0.2, 0.1])
    [record] = (cache / "mesh-facts").glob("*.json")
    record.unlink()
    os.mkfifo(record)
    assert _check(robot, cache)["extents"] == pytest.approx([0.4, 0.2, 0.1])  # no wait


def test_a_small_binary_stl_is_read_with_no_record_and_no_keeper(tmp_path):
    """Believing a record needs the seal keeper, a new process: a small binary STL is
    read instead (without numpy), and no key, keeper or record is made for it."""
    shutil.copy(MESHES / "solid_header.stl", tmp_path / "part.stl")
    robot = _robot(tmp_path, "part.stl")
    for _run in range(2):
        assert _check(robot, tmp_path / "cache") == {
            "extents": pytest.approx([0.4, 0.2, 0.1]), "rules": [], "read": []}
    assert not (tmp_path / "cache").exists()


def test_control_a_large_binary_stl_is_recorded(tmp_path):
    _stl(tmp_path / "part.stl", LARGE)
    assert _check(_robot(tmp_path, "part.stl"), tmp_path / "cache")["read"] == ["numpy"]
    assert len(list((tmp_path / "cache" / "mesh-facts").glob("*.json"))) == 1
    assert (tmp_path / "cache" / "record-key").is_file()


@pytest.mark.parametrize("corner", [(0.4, -0.2, 3e38), (0.4, math.nan, 0.1),
                                    (math.inf, 0.2, 0.1)])
def test_the_small_stl_box_is_numpy_s(tmp_path, corner):
    """The box read in Python is the one numpy finds, a NaN or an infinity included
    (then none: the mesh has no finite box)."""
    np = pytest.importorskip("numpy")
    from mobile_car.load import mesh_facts

    path = _stl(tmp_path / "part.stl", 3, corner)
    points = np.frombuffer(path.read_bytes()[84:], dtype=np.dtype(
        {"names": ["c"], "formats": [("<f4", (9,))], "offsets": [12], "itemsize": 50}))
    points = points["c"].reshape(-1, 3)
    low, high = points.min(axis=0).tolist(), points.max(axis=0).tolist()
    finite = all(map(math.isfinite, low + high))
    expected = (tuple(low), tuple(high)) if finite else None
    assert mesh_facts._small_stl_bounds(path, 3) == expected
