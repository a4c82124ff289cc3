"""`mcar render --joint NAME=VALUE`: posed pictures, and the joint values it refuses."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

ARM = Path(__file__).parents[1] / "view" / "arm" / "arm.urdf.xacro"
SIDE = ("--view", "side", "--size", "400x300", "--no-grid", "--no-axes", "-q")


def _rows(picture: np.ndarray, colour) -> np.ndarray:
    """The rows (top = 0) holding a pixel within 40 levels of ``colour``."""
    near = np.abs(picture.astype(int) - np.array(colour)).max(axis=2) <= 40
    return np.nonzero(near.any(axis=1))[0]


def _arm_above_base(picture: np.ndarray) -> float:
    """How far the red arm reaches above the grey base's top, in base heights."""
    grey, red = _rows(picture, (128, 128, 128)), _rows(picture, (215, 40, 40))
    assert len(grey) and len(red), "the base or the arm is not in the picture"
    return (grey.min() - red.min()) / (grey.max() - grey.min() + 1)


def test_a_raised_shoulder_lifts_the_arm_above_the_base(cli, tmp_path, px, quiet_renderer):
    zero, raised = tmp_path / "zero.png", tmp_path / "raised.png"
    assert cli("render", ARM, "-o", zero, *SIDE, *quiet_renderer).exit_code == 0
    result = cli("render", ARM, "-o", raised, "--joint", "shoulder=-60deg", *SIDE,
                 *quiet_renderer)
    assert result.exit_code == 0, result.output
    at_zero, lifted = px.read_png(zero), px.read_png(raised)
    assert not np.array_equal(at_zero, lifted)
    # At zero the arm lies level with the base's top; turned 60° about y it stands up.
    assert _arm_above_base(at_zero) < 0.5
    assert _arm_above_base(lifted) > 1.5


def test_the_same_pose_in_radians_and_degrees_is_the_same_picture(cli, tmp_path, px,
                                                                   quiet_renderer):
    degrees, radians = tmp_path / "deg.png", tmp_path / "rad.png"
    for out, value in ((degrees, "90deg"), (radians, "1.5707963267948966")):
        result = cli("render", ARM, "-o", out, "--joint", f"wrist={value}", *SIDE,
                     *quiet_renderer)
        assert result.exit_code == 0, result.output
    assert np.array_equal(px.read_png(degrees), px.read_png(radians))


@pytest.mark.parametrize("word, message", [
    ("shouldr=0.1", "--joint shouldr: no joint of that name; did you mean 'shoulder'?"),
    ("shoulder=2", "--joint shoulder: 2 is outside the joint's limits, -1.5 to 1.5 rad"),
    ("shoulder=5cm", "--joint shoulder: '5cm' has the wrong unit: expected rad, got cm"),
    ("elbow=0.2", "--joint elbow: it mimics 'shoulder'; set that joint instead"),
])
def test_a_joint_value_the_robot_cannot_take_is_a_usage_error(run_mcar, tmp_path, word,
                                                              message):
    out = tmp_path / "x.png"
    result = run_mcar("render", ARM.name, "-o", out, "--joint", word, *SIDE, cwd=ARM.parent)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [f"{ARM.name}: error: {message}"]
    assert not out.exists()


def test_joint_words_must_be_name_equals_value(run_mcar, tmp_path):
    result = run_mcar("render", ARM, "-o", tmp_path / "x.png", "--joint", "shoulder")
    assert result.returncode == 2
    assert "Invalid value for '--joint': 'shoulder' is not NAME=VALUE" in result.stderr


def test_joint_takes_one_robot_file(run_mcar, tmp_path):
    folder = tmp_path / "arms"
    shutil.copytree(ARM.parent, folder)
    shutil.copy(folder / ARM.name, folder / "second.urdf.xacro")
    result = run_mcar("render", folder, "-o", tmp_path / "out", "--joint", "shoulder=0.1")
    assert result.returncode == 2
    assert result.stderr.strip() == ("mcar: error: --joint poses one robot, and there are 2 "
                                     "robot files to draw: name one INPUT file")
