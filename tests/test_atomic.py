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
