"""mcar specs' inertia section reads a link's collision meshes to take its inertia from
them: a description must not make it read a file outside its folders, a FIFO, or a mesh
over the limits. It reads only what ``mcar check`` found readable (check's MeshFile: a
path resolved once beneath the roots, a regular file, measured within
``MCAR_MAX_MESH_MB``/``MCAR_MAX_MESH_FACES``), through mobile_car.load.mesh_reader, the
one way to trimesh. Each attack is planted here; each control names the same mesh the
way that is allowed, and the section then reads it (a figure from its shape), so each
test can fail."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest
from hostile import cube_stl

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.specs.inertia import inertia_section


def robot_naming(filename: str) -> str:
    return f"""<?xml version="1.0"?>
<robot name="atk">
  <link name="base"/>
  <link name="probe">
    <collision><geometry><mesh filename="{filename}"/></geometry></collision>
    <inertial><mass value="6"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <joint name="j" type="fixed"><parent link="base"/><child link="probe"/></joint>
</robot>
"""


def section_for(folder: Path, filename: str):
    path = folder / "robot.urdf"
    path.write_text(robot_naming(filename))
    checked = check_input(RobotInput(path))
    return checked, inertia_section(checked)


@pytest.fixture
def package(tmp_path):
    inside = tmp_path / "pkg"
    inside.mkdir()
    outside = tmp_path / "outside"
    outside.mkdir()
    # a 1 m "secret" cube beside the package: 6 kg in it is 1 kg m² about each axis
    (outside / "secret.stl").write_bytes(cube_stl(1.0))
    return inside, outside


def test_a_mesh_outside_the_packages_folders_is_never_read(package):
    inside, outside = package
    for named in (f"file://{outside}/secret.stl", "../outside/secret.stl"):
        checked, found = section_for(inside, named)
        assert [d.rule for d in checked.diagnostics] == ["W215"]
        assert found.figure("inertia.probe") is None
        assert found.notes == [f"link probe: collision mesh {named} is not read (mcar check "
                               "says why); no inertia from its geometry"]


def test_control_the_same_mesh_inside_the_package_is_read(package):
    inside, outside = package
    (inside / "secret.stl").write_bytes((outside / "secret.stl").read_bytes())
    _checked, found = section_for(inside, "secret.stl")
    assert found.figure("inertia.probe").value == pytest.approx([1, 0, 0, 1, 0, 1], abs=1e-6)


class FifoWatch:
    """A writer standing by a FIFO while the section runs: the moment anything opens it
    for reading, the writer's open succeeds (it is noted) and closes, which gives that
    reader its end of file instead of a wait for ever."""

    def __init__(self, path: Path):
        self.path, self.opened, self.stop = path, threading.Event(), threading.Event()
        self.thread = threading.Thread(target=self._watch, daemon=True)

    def _watch(self):
        while not self.stop.is_set():
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_NONBLOCK)
            except OSError:  # ENXIO: no reader has it open
                self.stop.wait(0.001)
                continue
            self.opened.set()
            os.close(fd)
            return

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.stop.set()
        self.thread.join()


def test_a_fifo_named_as_a_mesh_is_not_opened(package):
    inside, _outside = package
    os.mkfifo(inside / "pipe.stl")
    with FifoWatch(inside / "pipe.stl") as watch:
        checked, found = section_for(inside, "pipe.stl")
    assert not watch.opened.is_set()
    assert [d.rule for d in checked.diagnostics] == ["W207"]
    assert found.figure("inertia.probe") is None
    assert found.notes == ["link probe: collision mesh pipe.stl is not read (mcar check says "
                           "why); no inertia from its geometry"]


def test_control_the_watch_sees_a_reader_open_the_fifo(tmp_path):
    os.mkfifo(tmp_path / "pipe.stl")
    with FifoWatch(tmp_path / "pipe.stl") as watch:
        fd = os.open(tmp_path / "pipe.stl", os.O_RDONLY | os.O_NONBLOCK)
        assert watch.opened.wait(10)
        os.close(fd)


def test_a_mesh_over_the_face_limit_is_not_read(package, monkeypatch):
    inside, outside = package
    (inside / "big.stl").write_bytes((outside / "secret.stl").read_bytes())
    monkeypatch.setenv("MCAR_MAX_MESH_FACES", "10")  # the cube has 12
    checked, found = section_for(inside, "big.stl")
    assert [d.rule for d in checked.diagnostics] == ["W210"]
    assert found.figure("inertia.probe") is None
    monkeypatch.setenv("MCAR_MAX_MESH_FACES", "12")  # control: within it, read
    (inside / "fits.stl").write_bytes((outside / "secret.stl").read_bytes())
    _checked, found = section_for(inside, "fits.stl")
    assert found.figure("inertia.probe").value == pytest.approx([1, 0, 0, 1, 0, 1], abs=1e-6)
