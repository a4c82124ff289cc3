"""mcar sim --record: a GIF from a fixed camera in which the car visibly drives away."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image, ImageSequence


def _egl_available() -> bool:
    import ctypes.util

    return ctypes.util.find_library("EGL") is not None


@pytest.mark.skipif(not _egl_available(), reason="no EGL library (Debian: libegl1 "
                    "libegl-mesa0 libgl1-mesa-dri, which `make test` installs)")
def test_the_recording_shows_the_car_moving_over_a_still_floor(cli, repo, monkeypatch,
                                                               tmp_path):
    monkeypatch.chdir(repo)
    gif = tmp_path / "run.gif"
    result = cli("sim", "urdf/mobile_robot.xacro", "--scenario", "drive", "--record", gif)
    assert result.exit_code == 0, result.stderr
    frames = [np.asarray(f.convert("RGB"), dtype=int)
              for f in ImageSequence.Iterator(Image.open(gif))]
    assert len(frames) > 30 and frames[0].shape == (240, 320, 3)
    changed = np.abs(frames[-1] - frames[0]).sum(axis=2) > 60
    # The camera is fixed: only where the car was and where it is now changes ...
    assert 0.001 < changed.mean() < 0.15
    # ... and the car drove across the picture: the changes lie far apart.
    columns = np.flatnonzero(changed.any(axis=0))
    assert columns.max() - columns.min() > 320 / 4
    # While driving, every second of frames shows the car somewhere else.
    moving = [np.abs(frames[i + 15] - frames[i]).sum(axis=2).max() > 60
              for i in range(15, len(frames) - 15, 15)]
    assert all(moving)


def test_a_failed_recording_leaves_an_earlier_one(cli, repo, monkeypatch, tmp_path):
    monkeypatch.chdir(repo)
    gif = tmp_path / "run.mp4"
    gif.write_bytes(b"earlier")
    result = cli("sim", "urdf/mobile_robot.xacro", "--record", gif)
    assert result.exit_code == 2
    assert gif.read_bytes() == b"earlier"
