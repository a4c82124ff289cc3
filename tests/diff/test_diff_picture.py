"""`mcar diff --picture`: old and new side by side, asserted on the picture's pixels."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from diff.test_diff import _git, _set_wheel_radius, commit_the_car, write
from PIL import Image

# A box on two wheels hung at a fixed height: a change of the wheels' radius changes
# nothing else, so every pixel the halves differ in must belong to a wheel.
CART = """<robot name="cart">
  <material name="blue"><color rgba="0.3 0.5 0.9 1"/></material>
  <material name="black"><color rgba="0.1 0.1 0.1 1"/></material>
  <link name="base_link">
    <visual><geometry><box size="0.4 0.2 0.08"/></geometry><material name="blue"/></visual>
  </link>
  <link name="wheel_left_link">
    <visual><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/>
    </geometry><material name="black"/></visual>
  </link>
  <link name="wheel_right_link">
    <visual><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/>
    </geometry><material name="black"/></visual>
  </link>
  <joint name="wheel_left_joint" type="fixed">
    <origin xyz="0 0.13 0"/><parent link="base_link"/><child link="wheel_left_link"/>
  </joint>
  <joint name="wheel_right_joint" type="fixed">
    <origin xyz="0 -0.13 0"/><parent link="base_link"/><child link="wheel_right_link"/>
  </joint>
</robot>
"""


def _draw(run_mcar, *args, cwd) -> tuple[int, np.ndarray, np.ndarray]:
    """Run mcar diff --picture; exit code and the old and new halves as RGB arrays."""
    from mobile_car.diff.picture import halves

    result = run_mcar("diff", *args, "--picture", "diff.png", cwd=cwd)
    if "no renderer can run here" in result.stderr:
        pytest.skip(result.stderr.strip())
    assert result.returncode in (0, 1), result.stderr
    with Image.open(cwd / "diff.png") as image:
        assert image.format == "PNG"
        old, new = (np.asarray(half.convert("RGB"), dtype=int) for half in halves(image))
    return result.returncode, old, new


def _magenta(pixels: np.ndarray) -> np.ndarray:
    """Where a half shows the highlight colour (lit or shaded): red and blue well above
    green, which none of the faded colours or the background reach."""
    red, green, blue = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return (red > green + 60) & (blue > green + 40)


def _box(mask: np.ndarray, grow: int = 3) -> tuple[int, int, int, int]:
    rows, columns = np.nonzero(mask)
    return rows.min() - grow, rows.max() + grow, columns.min() - grow, columns.max() + grow


def test_bigger_wheels_differ_only_at_the_wheels_drawn_in_the_highlight(run_mcar, tmp_path):
    write(tmp_path, "old.urdf", CART)
    write(tmp_path, "new.urdf", CART.replace('radius="0.05"', 'radius="0.065"'))
    code, old, new = _draw(run_mcar, "old.urdf", "new.urdf", cwd=tmp_path)
    assert code == 1
    highlight = _magenta(old) | _magenta(new)
    assert _magenta(new).sum() > 500 and _magenta(old).sum() > 300
    assert _magenta(new).sum() > _magenta(old).sum()  # the new wheels are bigger
    differ = np.abs(old - new).max(axis=2) > 8
    assert differ.sum() > 100
    top, bottom, left, right = _box(highlight)
    rows, columns = np.nonzero(differ)
    # Every changed pixel is at a wheel: the grid, the triad and the box are the same.
    assert rows.min() >= top and rows.max() <= bottom
    assert columns.min() >= left and columns.max() <= right
    # ...and the box between the wheels is not highlighted.
    assert not highlight[(top + bottom) // 2, (left + right) // 2]


def test_identical_robots_give_identical_halves_and_no_highlight(run_mcar, tmp_path):
    write(tmp_path, "old.urdf", CART)
    write(tmp_path, "new.urdf", CART.replace('xyz="0 0.13 0"', 'xyz="0.0 1.3e-1 0"'))
    code, old, new = _draw(run_mcar, "old.urdf", "new.urdf", cwd=tmp_path)
    assert code == 0
    assert np.array_equal(old, new)
    assert not _magenta(old).any()
    assert (np.abs(old - old[0, 0]).max(axis=2) > 30).sum() > 1000  # the cart was drawn


def test_a_wheel_radius_commit_highlights_the_new_wheels(run_mcar, package_copy):
    commit_the_car(package_copy)
    _set_wheel_radius(package_copy, "0.045")
    code, old, new = _draw(run_mcar, "HEAD", "urdf/mobile_robot.xacro", cwd=package_copy)
    assert code == 1
    assert _magenta(new).sum() > _magenta(old).sum() > 500
    assert (np.abs(old - new).max(axis=2) > 8).sum() > 1000
    assert _git(package_copy, "status", "--porcelain") == " M urdf/config.xacro\n?? diff.png\n"


@pytest.mark.parametrize(("picture", "message"), [
    ("diff.jpg", "mcar: error: --picture diff.jpg: mcar diff draws PNG pictures, not .jpg; "
                 "name it diff.png\n"),
    ("new.urdf", "mcar: error: --picture new.urdf: mcar diff draws PNG pictures, not .urdf; "
                 "name it new.png\n"),
])
def test_a_picture_name_that_is_not_png_is_refused(run_mcar, tmp_path, picture, message):
    write(tmp_path, "old.urdf", CART)
    write(tmp_path, "new.urdf", CART)
    result = run_mcar("diff", "old.urdf", "new.urdf", "--picture", picture, cwd=tmp_path)
    assert (result.returncode, result.stderr) == (2, message)
    assert (tmp_path / "new.urdf").read_text(encoding="utf-8") == CART


def test_the_picture_never_overwrites_an_input(run_mcar, tmp_path):
    write(tmp_path, "old.png", CART)  # a robot file named .png: refused, not replaced
    write(tmp_path, "new.urdf", CART)
    result = run_mcar("diff", "old.png", "new.urdf", "--picture", "old.png", cwd=tmp_path)
    assert result.returncode == 2
    assert "would overwrite old.png" in result.stderr, result.stderr
    assert (tmp_path / "old.png").read_text(encoding="utf-8") == CART


def test_a_picture_of_several_robots_is_refused(run_mcar, package_copy):
    commit_the_car(package_copy)
    result = run_mcar("diff", "HEAD", "--picture", "diff.png", cwd=package_copy)
    assert result.returncode == 2
    assert result.stderr.startswith("mcar: error: --picture draws one robot, but "), result.stderr
    assert not (package_copy / "diff.png").exists()
    assert Path(package_copy / "urdf").is_dir()
