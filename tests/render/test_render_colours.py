"""A part whose colour urdfdom cannot use (W216, W217: warnings) is drawn, in the default
grey, as rviz draws it: `mcar render` writes the picture."""

from __future__ import annotations

ROBOT = """<robot name="colours">
  <material name="plain"/>
  <material name="hot"><color rgba="2 0 0 1"/></material>
  <link name="base">
    <visual><geometry><box size="0.3 0.2 0.1"/></geometry><material name="plain"/></visual>
    <visual><geometry><box size="0.1 0.1 0.2"/></geometry><material name="hot"/></visual>
    <visual><geometry><sphere radius="0.05"/></geometry>
      <material name="short"><color rgba="1 0 0"/></material></visual>
  </link>
</robot>
"""
# The same robot, its body blue: the control that shows a colour mcar can use is drawn.
COLOURED = ROBOT.replace('<material name="plain"/>\n', '<material name="plain">'
                         '<color rgba="0 0 1 1"/></material>\n', 1)


def test_the_picture_is_drawn_grey(cli, tmp_path, px, monkeypatch, needs_gl):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "grey.urdf").write_text(ROBOT)
    result = cli("render", "grey.urdf", "-o", "grey.png", "--size", "160x120")
    assert result.exit_code == 0, result.output
    (tmp_path / "blue.urdf").write_text(COLOURED)
    assert cli("render", "blue.urdf", "-o", "blue.png", "--size", "160x120").exit_code == 0
    grey, blue = (px.read_png(tmp_path / name).astype(int) for name in ("grey.png", "blue.png"))

    def bluish(image):
        return ((image[..., 2] > image[..., 0] + 60) & (image[..., 2] > image[..., 1] + 40)).sum()

    # (the corner triad draws a few blue and red pixels in both)
    assert bluish(blue) > 1000 and bluish(grey) < 100  # the body is there, in grey
    reddish = (grey[..., 0] > grey[..., 2] + 60).sum()
    assert reddish < 100  # rgba 2 0 0 1 and 1 0 0 left out, as urdfdom does
