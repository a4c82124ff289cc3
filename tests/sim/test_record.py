"""mcar sim --record: a GIF that diagnoses: 640 x 480 by default, lit, from a camera that
follows the robot (it stays in the middle of every picture while the floor passes under
it), with an arrow over each driven wheel while it is commanded."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image, ImageSequence


def _egl_available() -> bool:
    import ctypes.util

    return ctypes.util.find_library("EGL") is not None


needs_egl = pytest.mark.skipif(not _egl_available(), reason="no EGL library (Debian: libegl1 "
                               "libegl-mesa0 libgl1-mesa-dri, which `make test` installs)")


def _frames(gif):
    return [np.asarray(f.convert("RGB"), dtype=int)
            for f in ImageSequence.Iterator(Image.open(gif))]


def _yellow(frame):
    """The command arrows' pixels: yellow, which neither the floor nor the robot is."""
    r, g, b = frame[..., 0], frame[..., 1], frame[..., 2]
    return (r > 180) & (g > 150) & (b < 90)


@pytest.fixture(scope="module")
def driven(tmp_path_factory):
    """A skid-steer rover (red body, grey wheels) driven and recorded at the default size:
    (exit code, stderr, frames, metres driven)."""
    import json

    from click.testing import CliRunner
    from mobile_car.cli.main import main
    from sim.robot_makers import skid_steer

    folder = tmp_path_factory.mktemp("record")
    (folder / "rover.urdf").write_text(skid_steer())
    gif = folder / "run.gif"
    result = CliRunner().invoke(main, ["sim", str(folder / "rover.urdf"), "--scenario",
                                       "drive", "--record", str(gif), "--format", "json"],
                                catch_exceptions=False)
    document = json.loads(result.stdout)
    (drive,) = document["files"][0]["scenarios"]
    detail = next(f["detail"] for f in drive["figures"] if f["name"] == "distance error")
    return result.exit_code, result.stderr, _frames(gif), float(detail.split(" m of")[0])


@needs_egl
def test_the_recording_is_640_by_480_and_lit(driven):
    code, stderr, frames, _ = driven
    assert code == 0, stderr
    assert frames[0].shape == (480, 640, 3)
    # 320 x 240 and 52 of 255 before (one spotlight 3 m up, a dim headlight)
    assert min(frame.mean() for frame in frames) > 130


@needs_egl
def test_the_camera_follows_the_robot_that_drove_a_metre(driven):
    _, _, frames, metres = driven
    assert metres >= 1.0
    for number in (0, -1):
        ys, xs = np.nonzero(_red_pixels(frames[number]))
        assert len(xs) > 2000, f"frame {number}: the robot is not in the picture"
        assert abs(xs.mean() / 640 - 0.5) < 0.1 and abs(ys.mean() / 480 - 0.5) < 0.15, number
    # the robot stays, the floor passes under it: the picture's top (floor only) changed
    top = slice(0, 80)
    assert np.abs(frames[-1][top] - frames[0][top]).sum(axis=2).mean() > 20


@needs_egl
def test_an_arrow_over_each_driven_wheel_shows_its_command(driven):
    _, _, frames, _ = driven
    assert _yellow(frames[0]).sum() == 0  # standing: no command yet
    ys, xs = np.nonzero(_yellow(frames[-1]))
    assert len(xs) > 400  # four arrows, one per driven wheel
    # above the robot: higher in the picture than its body's middle
    assert ys.mean() < np.nonzero(_red_pixels(frames[-1]))[0].mean()


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


@needs_egl
def test_a_recorded_spin_keeps_the_robot_near_the_centre_of_every_frame(cli, tmp_path):
    from sim.robot_makers import skid_steer

    robot = tmp_path / "rover.urdf"
    robot.write_text(skid_steer())  # a red body on four grey wheels
    gif = tmp_path / "run.gif"
    result = cli("sim", robot, "--scenario", "spin", "--record", gif, "--record-size",
                 "320x240")
    assert result.exit_code == 0, result.stderr
    frames = _frames(gif)
    assert len(frames) > 30  # 3 s of spin (still frames are merged by the GIF)
    height, width = frames[0].shape[:2]
    assert (height, width) == (240, 320)
    for number, frame in enumerate(frames):
        red = _red_pixels(frame)
        ys, xs = np.nonzero(red)
        assert red.sum() > 300, f"frame {number}: the robot is not in the picture"
        # Wholly in frame, away from the edges, its middle near the picture's middle.
        assert xs.min() > 8 and xs.max() < width - 8, f"frame {number}"
        assert ys.min() > 8 and ys.max() < height - 8, f"frame {number}"
        assert abs(xs.mean() / width - 0.5) < 0.15, f"frame {number}"
        assert abs(ys.mean() / height - 0.5) < 0.2, f"frame {number}"


@pytest.mark.parametrize("size", ["640", "0x480", "640x1300", "wide"])
def test_a_record_size_that_is_not_one_is_a_usage_error(cli, tmp_path, size):
    from sim.robot_makers import skid_steer

    (tmp_path / "rover.urdf").write_text(skid_steer())
    result = cli("sim", tmp_path / "rover.urdf", "--record", tmp_path / "run.gif",
                 "--record-size", size)
    assert result.exit_code == 2
    assert result.stderr.splitlines() == [
        f"mcar: error: --record-size {size}: " + (
            "each side from 16 to 1280 pixels" if "x" in size and size[0].isdigit()
            else "give WIDTHxHEIGHT in pixels, e.g. 640x480")]
    assert not (tmp_path / "run.gif").exists()


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
