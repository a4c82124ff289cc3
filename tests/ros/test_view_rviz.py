"""`mcar view --rviz`: a robot outside any package, whose root is not base_footprint (the
view tests' arm: a revolute shoulder, a mimic elbow, a continuous wrist), opened in RViz
through the bundled display.launch, with a configuration fitted to it; Ctrl-C to mcar
stops roslaunch, which runs in a session of its own, and everything it started.

Also, without ROS: the command line and RViz configuration mcar makes."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import yaml
from conftest import MCAR, REPO
from ros.launching import STOP_SECONDS, launched, missing_ros, save_screenshot
from ros.pictures import assert_framed, coloured, slider_bars, view_box
from ros.urdf_facts import expected_transforms, matrix, robot_facts

ARM = REPO / "tests" / "view" / "arm"


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    if missing_ros():
        pytest.skip(missing_ros())
    folder = tmp_path_factory.mktemp("view_rviz")
    shutil.copytree(ARM, folder / "arm")
    robot = folder / "arm" / "arm.urdf.xacro"
    built = subprocess.run([str(MCAR), "build", str(robot), "-o", "-"],
                           capture_output=True, text=True, check=True)
    facts = robot_facts(built.stdout)
    with launched(folder, [str(MCAR), "view", "--rviz", str(robot)], cwd=folder,
                  ros_package_path=folder) as launch:
        graph = launch.probe(facts["root"], facts["links"])
        red = facts["colours"]["red"]

        def drawn(image):
            box = view_box(image)
            return coloured(image, red, box).count > 1000 and slider_bars(image, box[0]) == 2

        picture = launch.screenshot_when(drawn, "the red arm and its two sliders")
        save_screenshot(launch, picture, "rviz-view.png")
        yield {"launch": launch, "urdf": built.stdout, "facts": facts, "graph": graph,
               "picture": picture}


def test_robot_description_is_what_mcar_builds(arm):
    assert arm["graph"]["description"] == arm["urdf"]


def test_every_link_is_where_the_urdf_puts_it_mimic_included(arm):
    expected = expected_transforms(arm["urdf"], arm["facts"]["root"])
    got = arm["graph"]["transforms"]
    assert sorted(got) == sorted(expected) == ["base_link", "forearm", "hand", "upper_arm"]
    for link, pose in got.items():
        assert pose is not None, f"no transform for {link}\n{arm['launch'].log_tail()}"
        assert np.allclose(matrix(pose), expected[link], atol=1e-6), link
    assert arm["graph"]["topics"]["/joint_states"] == ["/joint_state_publisher_gui"]


def test_rviz_is_fitted_to_the_arm(arm):
    # the fixed frame is the arm's root, base_link: with the car's base_footprint RViz
    # would draw nothing
    box = view_box(arm["picture"])
    assert_framed(coloured(arm["picture"], arm["facts"]["colours"]["red"], box), box,
                  least=1000)
    assert slider_bars(arm["picture"], box[0]) == 2  # shoulder, wrist: the elbow mimics


def test_ctrl_c_to_mcar_stops_everything_within_60_seconds(arm):
    launch = arm["launch"]
    seconds, survivors = launch.stop()
    assert not survivors, f"still running after {STOP_SECONDS} s: {survivors}"
    assert seconds < STOP_SECONDS
    assert launch.processes[-1].returncode == 130  # mcar: interrupted
    assert "mcar view: " in launch.log.read_text() and "in RViz" in launch.log.read_text()


# ---- without ROS ---------------------------------------------------------------------

def test_no_roslaunch_is_one_line_and_exit_2(tmp_path):
    shutil.copytree(ARM, tmp_path / "arm")
    bare = os.pathsep.join(p for p in ("/usr/local/bin", "/bin")
                           if not Path(p, "roslaunch").exists())
    done = subprocess.run([str(MCAR), "view", "--rviz", "arm/arm.urdf.xacro"], cwd=tmp_path,
                          env=dict(os.environ, PATH=bare), capture_output=True, text=True)
    assert done.returncode == 2
    assert done.stderr == ("mcar: error: mcar view --rviz needs ROS 1's roslaunch and RViz, "
                           "which are not installed (Debian: apt-get install python3-roslaunch "
                           "ros-robot-state-publisher joint-state-publisher "
                           "joint-state-publisher-gui rviz)\n")


def test_a_mesh_over_the_limit_is_not_handed_to_rviz(tmp_path):
    if missing_ros():
        pytest.skip(missing_ros())
    robot = REPO / "urdf" / "mobile_robot.xacro"
    done = subprocess.run([str(MCAR), "view", "--rviz", str(robot)], cwd=tmp_path,
                          env=dict(os.environ, MCAR_MAX_MESH_FACES="100"),
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    lines = done.stderr.splitlines()
    # motor.stl, once for each call of the motor macro (each names its call)
    warned = [line for line in lines if "[W210]" in line]
    assert len(warned) == 2 and all("motor.xacro:33: warning:" in line for line in warned)
    assert lines[-1].endswith("mobile_robot.xacro: error: not opened in RViz: 2 meshes over "
                              "mcar's limits (W210 above), which RViz would read unbounded")
    assert done.stdout == ""  # roslaunch, which would say "... logging to", never ran


def test_the_launch_passes_build_arguments_and_a_fitted_configuration(tmp_path):
    from mobile_car.load.inputs import RobotInput
    from mobile_car.view import rviz

    args = ["--set", "wheel_radius=40 mm", "--config", "/a b/it's.yaml", "prefix:=left_"]
    launch = rviz.plan("/usr/bin/roslaunch", RobotInput(REPO / "urdf" / "mobile_robot.xacro"),
                       "base_footprint", [[-0.1, -0.15, 0.0], [0.2, 0.15, 0.2]], args, [],
                       tmp_path)
    assert launch.argv[:2] == ["/usr/bin/roslaunch", str(
        Path(rviz.description_dir()) / "launch" / "display.launch")]
    named = dict(arg.split(":=", 1) for arg in launch.argv[2:])
    assert named["model"] == str(REPO / "urdf" / "mobile_robot.xacro")
    # words apart by spaces, %XX for what would split them (and ":", which roslaunch
    # takes for a second :=): scripts/robot_description decodes them back
    assert named["args"] == "--set wheel_radius=40%20mm --config /a%20b/it's.yaml " \
                            "prefix%3A=left_"
    assert launch.env["PATH"].split(os.pathsep)[0] == str(MCAR.parent)
    assert launch.env["ROS_PACKAGE_PATH"].split(os.pathsep)[0] == str(REPO)
    config = yaml.safe_load(Path(named["rvizconfig"]).read_text())
    manager = config["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == "base_footprint"
    view = manager["Views"]["Current"]
    assert view["Distance"] == 0.75  # 2.5 x the largest size, 0.3 m
    assert view["Focal Point"] == {"X": 0.05, "Y": 0.0, "Z": 0.1}
    displays = {display["Class"]: display for display in manager["Displays"]}
    assert displays["rviz/TF"]["Marker Scale"] == 0.15
    assert displays["rviz/Grid"]["Cell Size"] == 0.1
