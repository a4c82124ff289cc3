"""A URDF whose <collision>s or <visual>s share a name (Neobotix MP-400's four castors,
each "caster_wheel"): MuJoCo makes the repeats unnamed geoms and said so itself, a
"WARNING: Geom with duplicate name ..." line on stderr among mcar's, three times in
every mcar sim, specs and export. mcar drops the repeated names first: the same model,
no stray line."""

from __future__ import annotations

import re

from sim.robot_makers import two_wheeler


def robot(tmp_path):
    text = two_wheeler().replace("<collision>", '<collision name="tyre">')
    assert text.count('name="tyre"') >= 3
    (tmp_path / "robot.urdf").write_text(text)
    return "robot.urdf"


def test_sim_specs_and_export_print_only_their_own_lines(run_mcar, tmp_path):
    name = robot(tmp_path)
    for args in (("sim", name), ("specs", name),
                 ("export", name, "--to", "mjcf", "-o", "out")):
        result = run_mcar(*args, cwd=tmp_path, timeout=300)
        assert result.returncode == 0, result.stderr
        assert "WARNING" not in result.stderr, (args, result.stderr)
    geoms = re.findall(r"<geom [^>]*>", (tmp_path / "out/two_wheeler.xml").read_text())
    assert sum('name="tyre"' in geom for geom in geoms) == 1  # the first keeps its name
