"""Dimension overrides reach the pictures: --set and the shipped variants render."""

from __future__ import annotations

import pytest
from conftest import REPO

ROBOT = "urdf/mobile_robot.xacro"
VARIANTS = sorted((REPO / "urdf" / "variants").glob("*.yaml"))
SMALL_SIZE = ("--size", "320x240", "--view", "side", "--no-grid", "--no-axes",
              "--background", "#ffffff")


def test_set_changes_the_picture_where_the_wheels_are(render, px, quiet_renderer):
    default = render(ROBOT, *SMALL_SIZE, *quiet_renderer)
    bigger = render(ROBOT, *SMALL_SIZE, *quiet_renderer, "--set", "wheel_radius=0.05")
    changed = px.differing_pixels(default, bigger)
    assert changed.mean() > 0.02
    # bigger wheels lift the whole car: its silhouette grows taller in the side view
    height = [px.silhouette_box(px.foreground(p))[3] for p in (default, bigger)]
    assert height[1] > height[0]


@pytest.mark.parametrize("variant", VARIANTS, ids=[v.stem for v in VARIANTS])
def test_variants_render(render, px, quiet_renderer, variant):
    picture = render(ROBOT, *SMALL_SIZE, *quiet_renderer, "--config", variant)
    assert picture.shape == (240, 320, 3)
    assert 0.1 < px.foreground(picture).mean() < 0.9


def test_bad_override_draws_nothing(cli, in_repo, tmp_path):
    out = tmp_path / "robot.png"
    result = cli("render", ROBOT, "-o", out, "--set", "wheel_radus=0.05")
    assert result.exit_code == 2
    assert "unknown dimension 'wheel_radus' (did you mean 'wheel_radius'?)" in result.output
    assert not out.exists()
