"""An edit that keeps a file's size and puts its mtime back is still an edit
(mobile_car/freshness.py).

The attack: after a green ``mcar ci``, a robot file, a xacro it includes or a mesh is
broken by an edit of the same size whose modification time is put back (``cp -p``,
``rsync -t``, ``touch -r``, ``tar x``, a restored cache). The records keyed each input by
size and mtime, so ``mcar ci`` replayed "ok" in 0.1 s for a robot ``mcar check``
rejects, and ``mcar render`` kept the old picture. Each edit is caught: ci fails as check
does, render draws again. The control: without the edit (the mtime alone set back, or
the file touched), the second run is a no-op that writes nothing.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import REPO

PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${name}">
      <visual><geometry><mesh filename="package://p/meshes/m.stl"/></geometry></visual>
    </link>
  </xacro:macro>
</robot>
"""
ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <xacro:part name="a"/>
  <xacro:part name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""
CI = ("ci", "--no-sim", "--no-gazebo", "--no-render")
RENDER = ("render", "--renderer", "raycast", "--size", "64x48")


def _broken_stl(data: bytes) -> bytes:
    """The same bytes with another triangle count: its size now contradicts it (W207)."""
    return data[:80] + (7).to_bytes(4, "little") + data[84:]


# What each edit does, all of the same size: the joint names a link that does not exist;
# the included macro makes <lank>s, so there are no links; the mesh holds no geometry.
EDITS = {
    "robot": ("urdf/r.urdf.xacro", lambda d: d.replace(b'child link="b"', b'child link="x"'),
              "child link 'x' is not defined"),
    "include": ("urdf/parts.xacro", lambda d: d.replace(b"link", b"lank"),
                "the robot has no <link>"),
    "mesh": ("meshes/m.stl", _broken_stl, "cannot be loaded: it holds no geometry"),
}


@pytest.fixture
def package(tmp_path) -> Path:
    """A robot with an include and a mesh that passes `mcar check --strict`; ci strict."""
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "meshes").mkdir()
    (package / "package.xml").write_text("<package><name>p</name></package>\n")
    (package / "mcar.yaml").write_text("ci:\n  strict: true\n")
    (package / "urdf" / "parts.xacro").write_text(PARTS)
    (package / "urdf" / "r.urdf.xacro").write_text(ROBOT)
    shutil.copy(REPO / "meshes" / "motor.stl", package / "meshes" / "m.stl")
    old = 1_600_000_000_000_000_000  # the files are old: no stamp is racy
    for path in package.rglob("*"):
        os.utime(path, ns=(old, old))
    return package


def edit_keeping_size_and_mtime(path: Path, change) -> None:
    """Rewrite ``path`` in place as an editor would, then put its times back as
    ``cp -p`` or ``touch -r`` would."""
    info = path.stat()
    data = change(path.read_bytes())
    assert len(data) == info.st_size and data != path.read_bytes()
    path.write_bytes(data)
    os.utime(path, ns=(info.st_atime_ns, info.st_mtime_ns))
    assert (path.stat().st_size, path.stat().st_mtime_ns) == (info.st_size, info.st_mtime_ns)


def built(package: Path) -> int:
    return (package / "build" / "r.urdf").stat().st_mtime_ns


@pytest.mark.parametrize("which", EDITS)
def test_a_same_size_edit_with_its_mtime_put_back_fails_ci_as_check_does(run_mcar, package,
                                                                         which):
    first = run_mcar(*CI, cwd=package)
    assert first.returncode == 0, first.stderr
    name, change, problem = EDITS[which]
    edit_keeping_size_and_mtime(package / name, change)

    checked = run_mcar("check", "--strict", "urdf/r.urdf.xacro", cwd=package)
    assert checked.returncode == 1 and problem in checked.stderr
    again = run_mcar(*CI, cwd=package)
    assert again.returncode == 1, again.stdout + again.stderr
    assert "FAILED (check)" in again.stdout and problem in again.stderr


def test_cp_p_and_touch_r_of_a_broken_copy_are_caught(run_mcar, package, tmp_path):
    """The real tools: a broken copy given the original's times by `touch -r`, then copied
    over it with `cp -p`."""
    for tool in ("cp", "touch"):
        if shutil.which(tool) is None:
            pytest.skip(f"{tool} is not installed")
    assert run_mcar(*CI, cwd=package).returncode == 0
    robot = package / "urdf" / "r.urdf.xacro"
    broken = tmp_path / "r.urdf.xacro"
    broken.write_bytes(robot.read_bytes().replace(b'child link="b"', b'child link="x"'))
    subprocess.run(["touch", "-r", str(robot), str(broken)], check=True)
    subprocess.run(["cp", "-p", str(broken), str(robot)], check=True)
    assert robot.stat().st_mtime_ns == 1_600_000_000_000_000_000

    again = run_mcar(*CI, cwd=package)
    assert again.returncode == 1, again.stdout + again.stderr
    assert "child link 'x' is not defined" in again.stderr


def test_without_an_edit_the_second_run_is_a_no_op(run_mcar, package):
    """The control: the times put back (or changed) on unchanged bytes build nothing."""
    assert run_mcar(*CI, cwd=package).returncode == 0
    before = built(package)
    for name, _, _ in EDITS.values():  # (their ctimes change)
        os.utime(package / name, ns=(1_600_000_000_000_000_000,) * 2)
    (package / "urdf" / "parts.xacro").touch()  # (its mtime changes)
    again = run_mcar(*CI, "-q", cwd=package)
    assert again.returncode == 0, again.stderr
    assert built(package) == before


def test_render_draws_again_after_a_same_size_mesh_edit(run_mcar, package):
    assert run_mcar(*RENDER, cwd=package).returncode == 0
    picture = package / "renders" / "r.png"
    drawn = picture.read_bytes()
    unchanged = run_mcar(*RENDER, cwd=package)
    assert "1 picture in renders: 0 rendered, 1 unchanged" in unchanged.stderr  # the control

    edit_keeping_size_and_mtime(package / "meshes" / "m.stl", _broken_stl)
    again = run_mcar(*RENDER, cwd=package)
    assert "1 picture in renders: 1 rendered" in again.stderr, again.stderr
    assert picture.read_bytes() != drawn  # the mesh that cannot be read is a marker now


def test_a_file_over_the_hashed_size_is_known_by_its_whole_identity(tmp_path):
    """Above HASHED_BYTES a file is not hashed while its identity holds: a same-size edit
    with the mtime put back still changes its ctime (in place) or its inode (a copy
    renamed over it, as rsync -t does), and then its bytes are compared."""
    import time

    from mobile_car.freshness import HASHED_BYTES, Stamper, stamp_current

    mesh = tmp_path / "big.stl"
    mesh.write_bytes(bytes(HASHED_BYTES + 1))
    old = 1_600_000_000_000_000_000
    os.utime(mesh, ns=(old, old))
    # The stamp must not be racy: the file's last change is before the run started.
    while time.time_ns() <= mesh.stat().st_ctime_ns:
        time.sleep(0.001)
    [stamp] = Stamper().stamps([mesh])
    assert stamp_current(list(stamp)) == (True, False)  # the control: a no-op

    copy = tmp_path / "copy.stl"  # rsync -t: a new file with the old times, renamed in
    copy.write_bytes(b"\1" + bytes(HASHED_BYTES))
    os.utime(copy, ns=(old, old))
    os.replace(copy, mesh)
    assert stamp_current(list(stamp)) == (False, False)

    mesh.write_bytes(bytes(HASHED_BYTES + 1))  # the bytes back: same content, refreshed
    os.utime(mesh, ns=(old, old))
    again = list(stamp)
    assert stamp_current(again) == (True, True) and again[1] != stamp[1]

    # In place, the mtime put back: the change time moves on (once the clock has ticked).
    while time.time_ns() <= mesh.stat().st_ctime_ns + 20_000_000:
        time.sleep(0.001)
    with open(mesh, "r+b") as handle:
        handle.write(b"\2")
    os.utime(mesh, ns=(old, old))
    assert stamp_current(list(again)) == (False, False)


def test_a_missing_mesh_is_stamped_as_missing_and_its_arrival_is_a_change(run_mcar, package):
    mesh = package / "meshes" / "m.stl"
    kept = mesh.read_bytes()
    mesh.unlink()
    first = run_mcar(*CI, cwd=package)
    assert first.returncode == 1 and "[W207]" in first.stderr, first.stderr
    before = built(package)
    again = run_mcar(*CI, cwd=package)  # still missing: the verdict is replayed
    assert again.returncode == 1 and "[W207]" in again.stderr
    assert built(package) == before

    mesh.write_bytes(kept)
    arrived = run_mcar(*CI, cwd=package)
    assert arrived.returncode == 0, arrived.stderr
    assert "[W207]" not in arrived.stderr
