"""Atomic writes: complete file or the old file, never a partial one or a stray temp file."""

from __future__ import annotations

import os

import pytest

from mobile_car.atomic import atomic_write
from mobile_car.errors import InputError


def test_writes_creates_folders_and_replaces(tmp_path):
    target = tmp_path / "a" / "b" / "out.urdf"
    atomic_write(target, "<robot/>")
    atomic_write(target, b"<robot name='x'/>")
    assert target.read_bytes() == b"<robot name='x'/>"
    assert os.listdir(target.parent) == ["out.urdf"]
    umask = os.umask(0)
    os.umask(umask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~umask


def test_failure_mid_write_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "out.urdf"
    target.write_text("old and good")

    def disk_full(fd):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", disk_full)
    with pytest.raises(InputError, match="No space left on device") as info:
        atomic_write(target, "new")
    assert info.value.file == str(target)
    assert target.read_text() == "old and good"
    assert os.listdir(tmp_path) == ["out.urdf"]


def test_interrupt_mid_write_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "out.png"
    target.write_bytes(b"old")

    def interrupted(fd):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "fsync", interrupted)
    with pytest.raises(KeyboardInterrupt):
        atomic_write(target, b"new")
    assert target.read_bytes() == b"old"
    assert os.listdir(tmp_path) == ["out.png"]


def test_a_pipe_or_device_is_written_in_place_not_replaced(tmp_path):
    """`mcar build x.xacro -o /dev/null` must not rename a file over /dev/null."""
    import stat
    import threading

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    atomic_write(fifo, "<robot name='r'/>")
    reader.join(timeout=10)
    assert received == [b"<robot name='r'/>"]
    assert stat.S_ISFIFO(fifo.stat().st_mode)
    assert os.listdir(tmp_path) == ["pipe"]


@pytest.mark.parametrize("mode", [0o600, 0o755, 0o444])
def test_a_rewritten_file_keeps_its_mode(tmp_path, mode):
    """A private (0600), executable (0755) or read-only (0444) output stays so when it is
    rebuilt; a read-only one is replaced as make would (the folder is writable)."""
    target = tmp_path / "out.urdf"
    target.write_text("old")
    target.chmod(mode)
    atomic_write(target, "new")
    assert (target.read_text(), target.stat().st_mode & 0o7777) == ("new", mode)


def test_a_file_in_the_path_is_named(tmp_path):
    blocker = tmp_path / "robot.urdf"
    blocker.write_text("<robot/>")
    with pytest.raises(InputError) as info:
        atomic_write(blocker / "sub" / "out.urdf", "new")
    assert info.value.message == f"cannot write: {blocker} is a file, not a folder"
    assert blocker.read_text() == "<robot/>"
