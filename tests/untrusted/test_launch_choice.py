"""A control package's launch files may not lead mcar out of the repository.

Where a robot names no controller file and its control package ships one per variant,
mcar reads the package's Python launch files as text to learn which file the build runs
(mobile_car/sim/control_variants.py): never run, never imported. A pull request commits
those files, and may commit them as links: to a file of the runner's
(``launch/controller.launch.py -> /home/runner/...``) or into the repository's ``.git``.
Such a link is not read: its text chooses nothing, and mcar says it cannot tell which file
runs (N405). The control keeps the same text inside the package: it is read and chooses.
"""

from __future__ import annotations

import os

import pytest
from check.test_stack_rules import CONTROL, LAUNCH, diff_control, warnings
from sim.robot_makers import two_wheeler
from specs.stack_package import write_package

LINKED = "bot_control/launch/controller.launch.py"


def _package(root):
    variant = diff_control(radius=0.03).replace("diff_cont", "mecanum_cont")
    robot = two_wheeler().replace(
        '<robot name="two_wheeler">', '<robot name="two_wheeler" xmlns:xacro='
        '"http://www.ros.org/wiki/xacro"><xacro:arg name="variant" default="false"/>')
    write_package(root, robot, {CONTROL: diff_control(),
                                "bot_control/config/variant.yaml": variant})
    (root / ".git").mkdir()  # the repository holding the package


@pytest.mark.parametrize("where", ["inside", "outside", "git"])
def test_a_launch_file_linked_out_of_the_repository_is_not_read(run_mcar, tmp_path, where):
    root = tmp_path / "repo"
    _package(root)
    launch = root / LINKED
    launch.parent.mkdir(parents=True)
    if where == "inside":  # the control: the launch's text is the package's own
        launch.write_text(LAUNCH)
    else:
        target = (tmp_path / "runner" / "secret.py" if where == "outside"
                  else root / ".git" / "hooks.py")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(LAUNCH)
        os.symlink(target, launch)
    result = run_mcar("check", "bot_description/robot.urdf", "variant:=true",
                      "--package-path", root, cwd=root)  # (not -q: notes too)
    assert result.returncode == 0, result.stderr
    if where == "inside":  # chosen: the variant's file, compared as a warning
        assert warnings(result, "N405") == []
        assert len(warnings(result, "W511")) == 1
    else:  # the link chose nothing: mcar cannot tell, and says so
        assert warnings(result, "W511") == []
        assert [line.split(": note:")[0] for line in warnings(result, "N405")] == [
            "bot_control/config/variant.yaml:6"]
