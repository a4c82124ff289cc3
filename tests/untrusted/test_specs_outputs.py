"""The files `mcar specs` writes (--stack DIR, --picture FILE.png) never land on a file the
run read. A pull request commits a link where a CI script's output goes: `stack` ->
the package's own Nav2 params folder, `specs.png` -> the robot file. Each is refused (exit
2, one line naming the file it would overwrite) and the package's file stays as it was;
the control writes to a plain folder and file."""

from __future__ import annotations

import os

from sim.robot_makers import two_wheeler
from specs.stack_package import DIFF_CONTROL, write_package

NAV2 = "local_costmap:\n  local_costmap:\n    ros__parameters:\n      robot_radius: 0.3\n"
PARAMS = "bot_navigation/params/nav2.yaml"


def package(root):
    control = DIFF_CONTROL.format(left="wheel_left_joint", right="wheel_right_joint",
                                  separation=0.16, radius=0.033)
    return write_package(root, two_wheeler(), {"bot_control/config/control.yaml": control,
                                               PARAMS: NAV2})


def specs(run_mcar, root, *args):
    return run_mcar("specs", "--no-proof", "bot_description/robot.urdf", "--package-path",
                    root, *args, cwd=root)


def test_a_stack_folder_linked_to_the_packages_params_is_refused(run_mcar, tmp_path):
    package(tmp_path)
    os.symlink(tmp_path / "bot_navigation" / "params", tmp_path / "stack")
    result = specs(run_mcar, tmp_path, "--stack", "stack")
    assert result.returncode == 2, result.stderr
    refused = [line for line in result.stderr.splitlines() if "would overwrite" in line]
    assert len(refused) == 1 and "nav2.yaml" in refused[0], result.stderr
    assert (tmp_path / PARAMS).read_text() == NAV2
    assert sorted(os.listdir(tmp_path / "bot_navigation" / "params")) == ["nav2.yaml"]


def test_control_a_plain_stack_folder_is_written(run_mcar, tmp_path):
    package(tmp_path)
    result = specs(run_mcar, tmp_path, "--stack", "stack")
    assert result.returncode == 0, result.stderr
    assert sorted(os.listdir(tmp_path / "stack")) == ["controllers.yaml", "nav2.yaml"]
    assert (tmp_path / PARAMS).read_text() == NAV2


def test_a_picture_linked_to_the_robot_file_is_refused(run_mcar, tmp_path):
    robot = package(tmp_path)
    before = robot.read_bytes()
    os.symlink(robot, tmp_path / "specs.png")
    result = specs(run_mcar, tmp_path, "--picture", "specs.png", "--renderer", "raycast")
    assert result.returncode == 2, result.stderr
    assert "would overwrite bot_description/robot.urdf" in result.stderr, result.stderr
    assert robot.read_bytes() == before
