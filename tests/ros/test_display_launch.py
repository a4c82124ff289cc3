"""The seed's command, as the README writes it, in the repository: roslaunch opens RViz with
the whole car, wheels included, and the joint sliders; everything stops within 60 s.

It runs with the virtualenv's bin first on PATH, as after `. .venv/bin/activate`: the
launch file must still give ROS 1's Python nodes Debian's python3 (the venv's has no
rospy), and robot_description comes from the venv's mcar.
"""

from __future__ import annotations

import re
import shlex
import subprocess

import numpy as np
import pytest
from conftest import MCAR, REPO
from ros.launching import STOP_SECONDS, launched, missing_ros, save_screenshot
from ros.pictures import assert_framed, coloured, slider_bars, view_box
from ros.urdf_facts import expected_transforms, matrix, robot_facts


def seed_command() -> str:
    """The README's roslaunch line (section "Look at it")."""
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    section = readme.split("\n## Look at it", 1)[1].split("\n## ", 1)[0]
    line = re.search(r"^ROS_PACKAGE_PATH=\$PWD roslaunch .*$", section, re.M).group(0)
    return re.sub(r"\s+#.*$", "", line)


@pytest.fixture(scope="module")
def car(tmp_path_factory):
    if missing_ros():
        pytest.skip(missing_ros())
    """The seed's command, launched once for this module; what it published, and RViz."""
    folder = tmp_path_factory.mktemp("display_launch")
    built = subprocess.run([str(MCAR), "build", "urdf/mobile_robot.xacro", "-o", "-"],
                           cwd=REPO, capture_output=True, text=True, check=True)
    facts = robot_facts(built.stdout)
    command = ["bash", "-c", seed_command()]
    with launched(folder, command, cwd=REPO, ros_package_path=REPO) as launch:
        graph = launch.probe(facts["root"], facts["links"])
        acrylic = facts["colours"]["acrylic"]

        def drawn(image):
            box = view_box(image)
            return (coloured(image, acrylic, box).count > 2000
                    and slider_bars(image, box[0]) == len(facts["moving"]))

        picture = launch.screenshot_when(drawn, "the car's acrylic plates and a slider per "
                                                "wheel")
        save_screenshot(launch, picture, "rviz.png", readme=True)
        yield {"launch": launch, "urdf": built.stdout, "facts": facts, "graph": graph,
               "picture": picture}


def test_the_command_is_the_seeds():
    words = shlex.split(seed_command())
    assert words[1:4] == ["roslaunch", "mobile_car_description", "display.launch"]
    assert words[4] == "model:=$(find mobile_car_description)/urdf/mobile_robot.xacro"


def test_robot_description_is_what_mcar_builds(car):
    assert car["graph"]["description"] == car["urdf"]


def test_every_link_is_where_the_urdf_puts_it(car):
    expected = expected_transforms(car["urdf"], car["facts"]["root"])
    got = car["graph"]["transforms"]
    missing = sorted(link for link in car["facts"]["links"] if got.get(link) is None)
    assert not missing, f"no transform for {missing}\n{car['launch'].log_tail()}"
    assert len(got) == len(expected) == len(car["facts"]["links"])
    for link, pose in got.items():
        assert np.allclose(matrix(pose), expected[link], atol=1e-6), link


def test_wheels_move_on_tf_the_rest_is_static(car):
    graph, moving = car["graph"], car["facts"]["moving"]
    assert moving == ["wheel_left_link", "wheel_right_link"]
    assert graph["tf"] == moving
    assert set(graph["tf_static"]) == set(car["facts"]["links"]) - set(moving) - {"base_footprint"}
    # the joint states come from our slider node (gui defaults to true), which runs
    assert graph["topics"]["/joint_states"] == ["/joint_state_publisher_gui"]
    assert "process has died" not in car["launch"].log.read_text(errors="replace")


def test_rviz_shows_the_car_in_the_middle_of_its_view(car):
    picture, colours = car["picture"], car["facts"]["colours"]
    box = view_box(picture)
    assert box[2] - box[0] > 400 and box[3] - box[1] > 400, box  # most of the window
    assert_framed(coloured(picture, colours["acrylic"], box), box)  # the plates
    assert coloured(picture, colours["brass"], box).count > 50  # the standoffs
    # joint_sliders' window, over RViz's (no window manager here): a slider per wheel
    assert slider_bars(picture, box[0]) == 2


def test_everything_stops_within_60_seconds(car):
    seconds, survivors = car["launch"].stop()
    assert not survivors, f"still running after {STOP_SECONDS} s: {survivors}"
    assert seconds < STOP_SECONDS
