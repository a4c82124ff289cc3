"""The same launch in a package `mcar init` wrote (a differential car: two wheels, a
castor), with a spinning part its user added: its own robot in RViz, with gui:=false
(the plain joint_state_publisher) and the launch's config and args arguments (a YAML of
dimensions, a --set), built as `mcar build` builds it. The commands are docs/rviz.md's,
run as written."""

from __future__ import annotations

import os
import re
import shlex
import subprocess

import numpy as np
import pytest
from conftest import MCAR, REPO
from ros.launching import STOP_SECONDS, launched, missing_ros, save_screenshot
from ros.pictures import assert_framed, coloured, slider_bars, view_box
from ros.urdf_facts import expected_transforms, matrix, robot_facts

NAME = "my_robot_description"
# What a user adds to the robot mcar init wrote: a spinning sensor on top, on a
# continuous joint.
SPINNER = """
  <link name="spinner_link">
    <visual>
      <geometry><cylinder radius="0.04" length="0.03"/></geometry>
      <material name="part"/>
    </visual>
  </link>
  <joint name="spinner_joint" type="continuous">
    <parent link="base_link"/>
    <child link="spinner_link"/>
    <origin xyz="0 0 ${base_z + base_height / 2 + 0.015}"/>
    <axis xyz="0 0 1"/>
  </joint>
</robot>"""
LINKS = ["base_footprint", "base_link", "castor_link", "spinner_link", "wheel_left_link",
         "wheel_right_link"]
MOVING = ["spinner_link", "wheel_left_link", "wheel_right_link"]


def doc_commands() -> list[str]:
    """docs/rviz.md's commands for a package of one's own: init, a YAML file, roslaunch."""
    text = (REPO / "docs" / "rviz.md").read_text(encoding="utf-8")
    section = text.split("\n## Your own package", 1)[1]
    return re.search(r"```sh\n(.*?)```", section, re.S).group(1).splitlines()


@pytest.fixture(scope="module")
def robot(tmp_path_factory):
    if missing_ros():
        pytest.skip(missing_ros())
    folder = tmp_path_factory.mktemp("display_launch_init")
    init, write_yaml, launch_line = doc_commands()
    env = dict(os.environ, PATH=f"{MCAR.parent}{os.pathsep}{os.environ['PATH']}")
    subprocess.run(["bash", "-c", init], cwd=folder, env=env, check=True, capture_output=True)
    package = folder / NAME
    robot_file = package / "urdf" / f"{NAME}.urdf.xacro"
    robot_file.write_text(robot_file.read_text().replace("</robot>", SPINNER))
    subprocess.run(["bash", "-c", write_yaml], cwd=package, check=True)
    built = subprocess.run([str(MCAR), "build", str(robot_file), "--config", "wide.yaml",
                            "--set", "base_length=36cm", "-o", "-"],
                           cwd=package, capture_output=True, text=True, check=True)
    facts = robot_facts(built.stdout)
    with launched(folder, ["bash", "-c", launch_line], cwd=package,
                  ros_package_path=package) as launch:
        graph = launch.probe(facts["root"], facts["links"])
        body = facts["colours"]["body"]
        picture = launch.screenshot_when(
            lambda image: coloured(image, body, view_box(image)).count > 2000, "the robot's body")
        save_screenshot(launch, picture, "rviz-init.png")
        yield {"launch": launch, "urdf": built.stdout, "facts": facts, "graph": graph,
               "picture": picture}


def test_the_commands_are_the_docs():
    init, write_yaml, launch_line = doc_commands()
    assert init.startswith(f"mcar init {NAME} ")
    assert shlex.split(launch_line)[1:] == [
        "roslaunch", NAME, "display.launch", "gui:=false", "config:=wide.yaml",
        "args:=--set base_length=36cm"]


def test_robot_description_is_what_mcar_builds_with_the_overrides(robot):
    assert robot["graph"]["description"] == robot["urdf"]
    assert '<box size="0.36 0.22 0.05"/>' in robot["urdf"]


def test_every_link_is_where_the_urdf_puts_it(robot):
    expected = expected_transforms(robot["urdf"], robot["facts"]["root"])
    got = robot["graph"]["transforms"]
    assert sorted(got) == sorted(expected) == LINKS
    for link, pose in got.items():
        assert pose is not None, f"no transform for {link}\n{robot['launch'].log_tail()}"
        assert np.allclose(matrix(pose), expected[link], atol=1e-6), link


def test_the_plain_joint_state_publisher_moves_the_wheels(robot):
    graph = robot["graph"]
    assert graph["tf"] == MOVING and graph["tf_static"] == ["base_link", "castor_link"]
    assert graph["topics"]["/joint_states"] == ["/joint_state_publisher"]
    assert "process has died" not in robot["launch"].log.read_text(errors="replace")


def test_rviz_shows_the_robot_in_the_middle_of_its_view(robot):
    picture, colours = robot["picture"], robot["facts"]["colours"]
    box = view_box(picture)
    assert_framed(coloured(picture, colours["body"], box), box)
    assert coloured(picture, colours["part"], box).count > 200  # the spinner
    assert slider_bars(picture, box[0]) == 0  # gui:=false: no slider window


def test_everything_stops_within_60_seconds(robot):
    seconds, survivors = robot["launch"].stop()
    assert not survivors, f"still running after {STOP_SECONDS} s: {survivors}"
    assert seconds < STOP_SECONDS
