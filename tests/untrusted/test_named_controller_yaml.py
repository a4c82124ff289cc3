"""A controllers file the description names in ``<parameters>`` may not lead mcar out of
the robot's folders.

gz_ros2_control's demos name their controllers' YAML by an absolute path outside any
``X_control`` package, and mcar sim reads it (tests/sim/test_sim_control_yaml.py). A pull
request writes that path: a runner's file outside the checkout, a link in the package that
leads out of it, a file in the repository's ``.git``. None is opened: its wheel names and
multiplier (here carrying a planted mark) appear nowhere, sim falls back on the geometry
and says the file was not read. The control names the same file inside the package.
"""

from __future__ import annotations

import os

import pytest
from sim.test_sim_control_yaml import NAMED_YAML, _demo

MARK = "MCAR-SECRET-9b02e1"


@pytest.mark.parametrize("where", ["inside", "outside", "link", "git"])
def test_a_named_controllers_file_out_of_the_robots_folders_is_not_read(
        cli, tmp_path, monkeypatch, where):
    package = tmp_path / "robot_demos"
    secret = tmp_path / "runner" / "controllers.yaml"
    named = {"inside": package / "config" / "controllers.yaml", "outside": secret,
             "link": package / "config" / "linked.yaml",
             "git": package / ".git" / "controllers.yaml"}[where]
    robot = _demo(tmp_path, named)
    marked = NAMED_YAML.replace("front_left_wheel_joint", f"front_left_wheel_joint_{MARK}")
    if where == "link":  # the package's file is a link to the runner's
        secret.parent.mkdir(parents=True)
        secret.write_text(marked)
        named.unlink()
        os.symlink(secret, named)
    else:
        named.write_text(marked)
    monkeypatch.chdir(tmp_path)
    result = cli("sim", robot.relative_to(tmp_path), "--scenario", "spin",
                 terminal_width=200)
    if where == "inside":  # read: its (marked) names reach the report, E306 naming one
        assert result.exit_code == 1, result.stderr
        assert f"names joint front_left_wheel_joint_{MARK}" in result.stderr
        return
    assert result.exit_code == 0, result.stderr
    assert MARK not in result.stdout + result.stderr
    assert "wheel_separation_multiplier 1.9" not in result.stdout
    assert "from geometry: a wheel that touches the floor" in result.stdout
    assert "controllers.yaml: not read (" in result.stderr or \
        "linked.yaml: not read (" in result.stderr, result.stderr
