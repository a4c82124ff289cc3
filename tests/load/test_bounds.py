"""Every read is bounded: each attack of bounds/cases/*.case runs the real `mcar` under a
2 GB address-space limit and a generous timeout, and must end with its exit code and one
line naming the file (no MemoryError, no RecursionError, no hang).

A case file holds ``command:`` (words; ``{name}`` is made by the maker of that name
below, at test time: FIFOs, links to devices, compression bombs), ``exit:``, and
``names:``, the text the one error line must hold (none for exit 0: nothing on stderr)
and optionally ``stdin: endless``.
"""

from __future__ import annotations

import bz2
import gzip
import io
import os
import re
import resource
import subprocess
import tarfile
import threading
import zipfile
from pathlib import Path

import pytest

from tests.conftest import MCAR

BOUNDS = Path(__file__).parent / "bounds"
CASES = sorted(BOUNDS.glob("cases/*.case"))
ADDRESS_SPACE = 2 * 1024 ** 3
TIMEOUT = 120
# Lines every run may add after its error: summaries, and the error's own indented
# context (xacro's "when processing file: ..."), not further errors.
_SUMMARY = re.compile(r"^(mcar check: |\d+ pictures? in |  when processing file: |size: )")
_MESH_URDF = """<?xml version="1.0"?>
<robot name="bomb">
  <link name="base">
    <visual>
      <geometry>
        <mesh filename="{mesh}"/>
      </geometry>
    </visual>
  </link>
</robot>
"""
_GIGABYTES_OF_ZEROS = 3


def _endless(write) -> threading.Thread:
    """A writer of endless lines until the reader goes away."""
    def run():
        try:
            while True:
                write(b"<robot>\n" * 8192)
        except (BrokenPipeError, OSError, ValueError):
            pass

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread


def make_fifo(tmp: Path, cleanups: list) -> Path:
    fifo = tmp / "endless.urdf"
    os.mkfifo(fifo)

    def feed():
        with open(fifo, "wb") as pipe:  # blocks until mcar opens it
            _endless(pipe.write).join()

    threading.Thread(target=feed, daemon=True).start()

    def release():  # if mcar never opened it, let the writer's open() return and fail
        fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
        os.close(fd)

    cleanups.append(release)
    return fifo


def _robot_with(tmp: Path, mesh_name: str, mesh: bytes) -> Path:
    (tmp / mesh_name).write_bytes(mesh)
    robot = tmp / "robot.urdf"
    robot.write_text(_MESH_URDF.format(mesh=mesh_name), encoding="utf-8")
    return robot


def _zeros_stream(compress) -> bytes:
    """GB of zeros in a few KB: one compressed 64 MB member, repeated (bz2 and gzip
    read concatenated streams as one)."""
    one = compress(bytes(64 << 20))
    return one * (_GIGABYTES_OF_ZEROS * 16)


def make_bz2_bomb(tmp: Path, cleanups: list) -> Path:
    return _robot_with(tmp, "bomb.stl.bz2", _zeros_stream(bz2.compress))


def make_zip_bomb(tmp: Path, cleanups: list) -> Path:
    """512 MB (twice the cap; deflating more would slow the test for nothing)."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        with archive.open("bomb.stl", "w", force_zip64=True) as member:
            for _ in range(8):
                member.write(bytes(64 << 20))
    return _robot_with(tmp, "bomb.zip", buffer.getvalue())


def make_targz_bomb(tmp: Path, cleanups: list) -> Path:
    info = tarfile.TarInfo("bomb.stl")
    info.size = _GIGABYTES_OF_ZEROS << 30
    header = info.tobuf(format=tarfile.GNU_FORMAT)
    # The member's zeros are the repeated gzip member; the header goes first.
    return _robot_with(tmp, "bomb.tar.gz",
                       gzip.compress(header) + _zeros_stream(gzip.compress))


def make_deep_json(tmp: Path, cleanups: list) -> Path:
    path = tmp / "deep.json"
    path.write_text('{"wheel_radius": ' + "[" * 50000 + "]" * 50000 + "}\n")
    return path


def make_deep_yaml(tmp: Path, cleanups: list) -> Path:
    path = tmp / "deep.yaml"
    path.write_text("wheel_radius: " + "[" * 50000 + "]" * 50000 + "\n")
    return path


def make_zero_xacro(tmp: Path, cleanups: list) -> Path:
    link = tmp / "zero.urdf.xacro"
    link.symlink_to("/dev/zero")
    return link


def make_zero_include(tmp: Path, cleanups: list) -> Path:
    (tmp / "zero.xacro").symlink_to("/dev/zero")
    robot = tmp / "robot.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     '<xacro:include filename="zero.xacro"/><link name="a"/></robot>\n')
    return robot


def make_zero_package(tmp: Path, cleanups: list) -> Path:
    (tmp / "pkg" / "urdf").mkdir(parents=True)
    (tmp / "pkg" / "package.xml").symlink_to("/dev/zero")
    robot = tmp / "pkg" / "urdf" / "box.urdf"
    robot.write_bytes((BOUNDS / "data" / "box.urdf").read_bytes())
    return robot


def make_zero_manifest(tmp: Path, cleanups: list) -> Path:
    folder = tmp / "renders"
    folder.mkdir()
    (folder / ".mcar-render.json").symlink_to("/dev/zero")
    return folder


MAKERS = {name[len("make_"):]: maker for name, maker in globals().items()
          if name.startswith("make_")}


def read_case(path: Path) -> dict[str, str]:
    fields = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        key, _, value = line.partition(":")
        fields[key.strip()] = value.strip()
    return fields


def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


@pytest.mark.parametrize("case", CASES, ids=[case.stem for case in CASES])
def test_attack_is_refused_within_bounds(case, tmp_path):
    fields = read_case(case)
    cleanups: list = []
    words = []
    for word in fields["command"].split():
        for name in re.findall(r"\{(\w+)\}", word):
            made = str(BOUNDS / "data") if name == "data" else str(MAKERS[name](tmp_path,
                                                                                  cleanups))
            word = word.replace("{" + name + "}", made)
        words.append(word)
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH") and not k.startswith("MCAR_")}
    endless = fields.get("stdin") == "endless"
    read_end, write_end = os.pipe() if endless else (subprocess.DEVNULL, None)
    process = subprocess.Popen([str(MCAR), *words], cwd=tmp_path, env=env, stdin=read_end,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               preexec_fn=_limit_memory)
    if endless:
        os.close(read_end)
        _endless(lambda data: os.write(write_end, data))
    try:
        _out, err = process.communicate(timeout=TIMEOUT)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
        if endless:
            os.close(write_end)
        for cleanup in cleanups:
            cleanup()
    stderr = err.decode("utf-8", errors="replace")
    assert "Traceback" not in stderr and "internal error" not in stderr, stderr
    assert process.returncode == int(fields["exit"]), stderr
    lines = [line for line in stderr.splitlines() if not _SUMMARY.match(line)]
    if fields.get("names"):
        assert len(lines) == 1, stderr
        assert fields["names"] in lines[0], stderr
    else:
        assert lines == [], stderr


def test_compressed_meshes_within_the_cap_still_load(run_mcar, tmp_path, quiet_renderer):
    """What the cap must not break: a gzip'd and a zipped STL are checked and drawn."""
    trimesh = pytest.importorskip("trimesh")
    stl = trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(file_type="stl")
    for name, data in (("box.stl.gz", gzip.compress(stl)), ("box.stl.bz2", bz2.compress(stl))):
        robot = _robot_with(tmp_path, name, data)
        result = run_mcar("check", "--strict", robot, cwd=tmp_path)
        assert result.returncode == 0, result.stderr
        result = run_mcar("render", robot, "-o", "out.png", *quiet_renderer, "--size", "64x64",
                          "-q", cwd=tmp_path)
        assert result.returncode == 0, result.stderr
