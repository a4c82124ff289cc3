"""A wheel whose collision geometry is a mesh rolls on its tread: its radius is its
farthest point from the axle, not the bounding sphere of its box. AgileX Tracer's
121 x 84 mm tyre mesh was a 95 mm wheel for 60.5 mm, and drive and spin failed on a "36%
wheel slip" that was the radius's (Scout Mini's 142 mm for 81 mm, Hunter 2's 243 mm for
164 mm). Robot made here: robot_makers' two-wheeler, its tyres an STL cylinder."""

from __future__ import annotations

import json

import pytest
from sim.robot_makers import two_wheeler

RADIUS, WIDTH = 0.033, 0.02  # the two-wheeler's tyres


def test_a_mesh_tyre_rolls_on_its_own_radius(cli, tmp_path):
    import trimesh

    trimesh.creation.cylinder(radius=RADIUS, height=WIDTH, sections=64).export(
        tmp_path / "tyre.stl")
    robot = two_wheeler().replace(
        f'<collision><geometry><cylinder radius="{RADIUS}" length="{WIDTH}"/></geometry>',
        '<collision><geometry><mesh filename="tyre.stl"/></geometry>')
    assert robot.count("tyre.stl") == 2
    (tmp_path / "robot.urdf").write_text(robot)
    result = cli("sim", tmp_path / "robot.urdf", "--format", "json")
    entry = json.loads(result.stdout)["files"][0]
    assert entry["drive"]["wheel_radius"] == pytest.approx(RADIUS, rel=1e-6)
    assert result.exit_code == 0, result.stdout + result.stderr
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == \
        [("drop", "passed"), ("drive", "passed"), ("spin", "passed")]
