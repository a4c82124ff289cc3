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


def _red_pixels(frame):
    """The robot body's pixels: red, where the floor's squares are grey."""
    r, g, b = frame[..., 0], frame[..., 1], frame[..., 2]
    return (r > 50) & (r > 2 * g) & (r > 2 * b)


@pytest.mark.skipif(not _egl_available(), reason="no EGL library (Debian: libegl1 "
                    "libegl-mesa0 libgl1-mesa-dri, which `make test` installs)")
def test_a_recorded_skid_steer_run_keeps_the_robot_in_frame_near_the_centre(cli, tmp_path):
    from sim.robot_makers import skid_steer

    robot = tmp_path / "rover.urdf"
    robot.write_text(skid_steer())  # a red body on four grey wheels
    gif = tmp_path / "run.gif"
    result = cli("sim", robot, "--record", gif)
    assert result.exit_code == 0, result.stderr
    frames = [np.asarray(f.convert("RGB"), dtype=int)
              for f in ImageSequence.Iterator(Image.open(gif))]
    assert len(frames) > 60  # drop, drive and spin (still frames are merged by the GIF)
    height, width = frames[0].shape[:2]
    centres = []
    for number, frame in enumerate(frames):
        red = _red_pixels(frame)
        ys, xs = np.nonzero(red)
        assert red.sum() > 300, f"frame {number}: the robot is not in the picture"
        # Wholly in frame, away from the edges, its middle near the picture's middle.
        assert xs.min() > 8 and xs.max() < width - 8, f"frame {number}"
        assert ys.min() > 8 and ys.max() < height - 8, f"frame {number}"
        centres.append((xs.mean() / width, ys.mean() / height))
    centres = np.array(centres)
    assert (centres > 0.2).all() and (centres < 0.8).all()
    # It moved across the picture while driving: the camera is still, the robot is not.
    assert centres[:, 0].max() - centres[:, 0].min() > 0.2


def test_a_recording_that_cannot_be_made_writes_nothing_and_says_why(cli, repo, monkeypatch,
                                                                    tmp_path):
    monkeypatch.chdir(repo)
    gif = tmp_path / "run.gif"
    # The tutorial car has no collision geometry: nothing is simulated, nothing recorded.
    result = cli("sim", "urdf/tutorial/04_xacro.xacro", "--record", gif)
    assert result.exit_code == 1
    assert not gif.exists()
    assert f"mcar: --record {gif}: not written: no link has <collision> geometry" \
        in result.stderr
