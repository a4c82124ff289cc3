"""A colour is cosmetic: a material urdfdom, rviz and Gazebo load with a warning (undefined,
without a colour, an rgba they cannot read) is a warning in mcar (W216, W217), an error
only under --strict, and every export leaves out what urdfdom drops (the picture:
tests/render/test_render_colours.py)."""

from __future__ import annotations

import json

import pytest

ROBOT = """<robot name="colours">
  <material name="plain"/>
  <material name="hot"><color rgba="2 0 0 1"/></material>
  <link name="base">
    <visual><geometry><box size="0.3 0.2 0.1"/></geometry><material name="plain"/></visual>
    <visual><geometry><box size="0.1 0.1 0.2"/></geometry><material name="hot"/></visual>
    <visual><geometry><sphere radius="0.05"/></geometry>
      <material name="short"><color rgba="1 0 0"/></material></visual>
    <visual><geometry><sphere radius="0.04"/></geometry><material name="nowhere"/></visual>
    <collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision>
    <inertial><mass value="1"/>
      <inertia ixx="0.004" ixy="0" ixz="0" iyy="0.008" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>
"""


@pytest.fixture
def robot(tmp_path):
    path = tmp_path / "colours.urdf"
    path.write_text(ROBOT)
    return path


def test_colour_problems_are_warnings_naming_their_lines(cli, robot):
    result = cli("check", "--format", "json", robot)
    found = sorted((d["rule"], d["line"], d["severity"]) for d in
                   json.loads(result.stdout)["files"][0]["diagnostics"])
    assert found == [("W208", 11, "warning"), ("W216", 2, "warning"),
                     ("W216", 9, "warning"), ("W217", 3, "warning"), ("W217", 8, "warning")]
    assert result.exit_code == 0


def test_colour_problems_fail_under_strict(cli, robot):
    result = cli("check", "--strict", robot)
    assert result.exit_code == 1
    assert (f"{robot}:9: warning: link 'base' uses material 'nowhere', which is not "
            "defined with a colour before it (a top-level <material> or an earlier visual): "
            "drawn in the default grey, as urdfdom and rviz do [W216]") in result.stderr
    assert (f"{robot}:3: warning: material 'hot': rgba=\"2 0 0 1\" has a component "
            "outside 0..1; urdfdom drops the colour [W217]") in result.stderr


@pytest.mark.parametrize("to", ["mjcf", "usd", "urdf"])
def test_every_export_leaves_the_unreadable_colours_out(run_mcar, robot, tmp_path, to):
    result = run_mcar("export", robot.name, "--to", to, "-o", f"out_{to}", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert ("colours.urdf: warning: material 'short': rgba=\"1 0 0\" is not a colour urdfdom "
            "reads (W217): left out, drawn in the default grey") in result.stderr
    written = b"".join(p.read_bytes() for p in (tmp_path / f"out_{to}").rglob("*")
                       if p.is_file() and p.suffix in (".xml", ".usda", ".urdf"))
    assert b"2 0 0 1" not in written and b'"1 0 0"' not in written
