"""``mcar check`` and ``mcar specs`` read the robot's package's ROS YAML (its control
package's controllers, its navigation package's Nav2 parameters: specs/stack_check.py),
files a pull request commits. The attack: ``bot_navigation/params/nav2.yaml`` and
``bot_control/config/control.yaml`` committed as links to files outside the packages (a
credentials file, or numbers planted to steer the verdict). Neither is read: no warning
is made of the planted numbers, and no byte of the secret reaches the output or the
notes. The control commits the same bytes as regular files inside the packages: then the
numbers do make a warning, and the broken YAML's error does quote the secret's line, so
the test can fail."""

from __future__ import annotations

import pytest
from sim.robot_makers import two_wheeler
from specs.stack_package import DIFF_CONTROL, checked_and_model, write_package

MARK = "MCAR-SECRET-7c2f41"
# Names the costmap (so it is parsed), does not parse; its bad line holds the secret.
SECRET = f"local_costmap: robot_radius\n{MARK}: : bad\n"
PLANTED = DIFF_CONTROL.format(left="wheel_left_joint", right="wheel_right_joint",
                              separation=0.5, radius=0.033)


def plant(tmp_path, linked: bool):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.yaml").write_text(SECRET)
    (outside / "planted.yaml").write_text(PLANTED)
    work = tmp_path / "ws"
    nav2 = work / "bot_navigation" / "params" / "nav2.yaml"
    control = work / "bot_control" / "config" / "control.yaml"
    robot = write_package(work, two_wheeler(), {"bot_navigation/params/keep.txt": "",
                                                "bot_control/config/keep.txt": ""})
    for path, source in ((nav2, outside / "secret.yaml"), (control, outside / "planted.yaml")):
        if linked:
            path.symlink_to(source)
        else:
            path.write_bytes(source.read_bytes())
    return work, robot


@pytest.mark.parametrize("linked", [True, False], ids=["link-out", "inside"])
def test_package_yaml_linked_out_of_its_package_is_not_read(run_mcar, tmp_path, linked,
                                                             monkeypatch):
    work, robot = plant(tmp_path, linked)
    result = run_mcar("check", "bot_description/robot.urdf", "--package-path", work, cwd=work)
    assert result.returncode == 0, result.stderr
    assert MARK not in result.stdout + result.stderr
    assert ("[W510]" in result.stderr) is not linked  # the planted separation, 0.5 m
    from mobile_car.specs.stack_check import compare_package

    monkeypatch.chdir(work)
    checked, sim = checked_and_model(robot, work)
    _, notes, read = compare_package(checked, sim, [])
    if linked:
        assert read == []
        assert sorted(notes) == [
            f"bot_control/config/control.yaml: not read (a link to "
            f"{(tmp_path / 'outside' / 'planted.yaml').resolve()}, outside "
            f"{(work / 'bot_control').resolve()})",
            f"bot_navigation/params/nav2.yaml: not read (a link to "
            f"{(tmp_path / 'outside' / 'secret.yaml').resolve()}, outside "
            f"{(work / 'bot_navigation').resolve()})"]
    else:  # the same bytes inside the package: read, and their error quotes the line
        assert any(MARK in note for note in notes)


DEEP = 5_000  # nesting PyYAML's recursive composer cannot follow (1000 frames)


def test_hostile_numbers_and_a_deep_footprint_are_one_line_each(run_mcar, tmp_path):
    """Nav2's footprint is a string Nav2 parses itself: mcar parses it with the bounded
    loader. NaN and 1e999 figures are not numbers to compare."""
    import yaml

    work = tmp_path / "ws"
    deep = "[" * DEEP + "]" * DEEP
    hostile = PLANTED.replace("0.5", ".nan").replace("0.033", "1e999")
    write_package(work, two_wheeler(), {
        "bot_navigation/params/nav2.yaml": f'local_costmap:\n  footprint: "{deep}"\n'
                                           f"  robot_radius: -1e999\n",
        "bot_control/config/control.yaml": hostile})
    result = run_mcar("check", "bot_description/robot.urdf", "--package-path", work, cwd=work)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr and "[W51" not in result.stderr
    # control: what the footprint would do to a plain yaml.safe_load
    with pytest.raises(RecursionError):
        yaml.safe_load(deep)
