"""A control package's YAML is read and parsed once a run: sim's declarations, the
mecanum declarations, the skid-steer multiplier and the stack's comparison each asked
for the same files (four parses of each in one `mcar specs --stack`), the results and
the sentences about a file that cannot be read unchanged."""

from __future__ import annotations

import os

import pytest
from sim.robot_makers import two_wheeler
from specs.stack_package import DIFF_CONTROL, write_package

from mobile_car.config import bounded_yaml


@pytest.fixture
def parses(monkeypatch):
    """The texts compose (ROS's reading: the last of a repeated key) is given, in order."""
    given = []
    original = bounded_yaml.compose

    def counted(text):
        given.append(text)
        return original(text)

    monkeypatch.setattr(bounded_yaml, "compose", counted)
    return given


def _readers(robot, root):
    """What every reader of the control package finds, in the order a run asks."""
    from specs.stack_package import checked_and_model

    from mobile_car.sim.control_config import find_control_config, find_controllers
    from mobile_car.sim.mecanum import yaml_declarations
    from mobile_car.specs.stack_check import find_package_yaml

    checked, _sim = checked_and_model(robot, root)
    loaded = checked.loaded
    controllers, unread, _ = find_controllers(loaded)
    config, unread_too = find_control_config(loaded, ["wheel_left_joint"])
    found = find_package_yaml(loaded)
    return ([(d.kind, d.joints, d.line) for d in controllers], unread, unread_too,
            config and (config.multiplier, config.line), yaml_declarations(loaded)[1],
            [(p.name, sorted(keys)) for p, keys in found.controllers], found.problems)


def test_every_reader_parses_each_control_file_once(tmp_path, parses):
    control = DIFF_CONTROL.format(left="wheel_left_joint", right="wheel_right_joint",
                                  separation=0.16, radius=0.033) \
        + "    wheel_separation_multiplier: 1.5\n"
    robot = write_package(tmp_path, two_wheeler(), {
        "bot_control/config/diff.yaml": control,
        "bot_control/config/broken.yaml": "wheel: [unclosed\n"})
    found = _readers(robot, tmp_path)
    broken = f"{tmp_path}/bot_control/config/broken.yaml: not read (while parsing a flow "
    assert found[0] == [("differential", ["wheel_left_joint", "wheel_right_joint"], 3)]
    assert found[3] == (1.5, 7)
    for problems in (found[1], found[2], found[6]):
        assert len(problems) == 1 and problems[0].startswith(broken), problems
    assert found[4] == []  # the mecanum reader parses only a file naming its controller
    assert found[5] == [("diff.yaml", ["diff_cont"]), ("diff.yaml", ["ros__parameters"]),
                        ("diff.yaml", ["left_wheel_names", "right_wheel_names", "wheel_radius",
                                       "wheel_separation", "wheel_separation_multiplier"])]
    # resting_model's readers, then these: every file parsed once
    assert sorted(parses) == sorted([control, "wheel: [unclosed\n"])


def test_a_file_edited_in_the_same_process_is_read_again(tmp_path, parses):
    from mobile_car.sim.control_config import yaml_mappings

    path = tmp_path / "c.yaml"
    path.write_text("a: 1\n")
    assert [sorted(m) for m in yaml_mappings(path, [])] == [["a"]]
    assert [sorted(m) for m in yaml_mappings(path, [])] == [["a"]]
    path.write_text("b: 2\n")
    os.utime(path, ns=(1, 1))  # its size and time alone would not tell
    assert [sorted(m) for m in yaml_mappings(path, [])] == [["b"]]
    assert parses == ["a: 1\n", "b: 2\n"]
