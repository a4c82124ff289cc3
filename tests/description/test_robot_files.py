"""Every robot file of the description builds, passes urdfdom's check_urdf and yourdfpy,
and every body in it is complete (visual, collision, inertial) and physically possible.
The complete robot has exactly the links, joints and tree the rest of ROS expects."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np
from conftest import run_check_urdf
from lxml import etree

from tests.description.conftest import (
    COMPLETE_ROBOT,
    FRAME_ONLY_LINKS,
    URDF,
    built_name,
    description_files,
)

COMPLETE_LINKS = {
    "base_footprint", "base_link", "body_link",
    "bracket_left_link", "bracket_right_link", "motor_left_link", "motor_right_link",
    "standoff_front_left_link", "standoff_front_right_link",
    "standoff_rear_left_link", "standoff_rear_right_link", "top_plate_link",
    "wheel_left_link", "wheel_right_link", "caster_link", "laser_link",
}
COMPLETE_JOINTS = {
    "base_joint": "fixed", "body_joint": "fixed",
    "bracket_left_joint": "fixed", "bracket_right_joint": "fixed",
    "motor_left_joint": "fixed", "motor_right_joint": "fixed",
    "standoff_front_left_joint": "fixed", "standoff_front_right_joint": "fixed",
    "standoff_rear_left_joint": "fixed", "standoff_rear_right_joint": "fixed",
    "top_plate_joint": "fixed",
    "wheel_left_joint": "continuous", "wheel_right_joint": "continuous",
    "caster_joint": "fixed", "laser_joint": "fixed",
}
# urdfdom lists a link's children in the order of their joints' names.
COMPLETE_TREE = """\
robot name is: mobile_robot
---------- Successfully Parsed XML ---------------
root Link: base_footprint has 1 child(ren)
    child(1):  base_link
        child(1):  body_link
            child(1):  bracket_left_link
                child(1):  motor_left_link
            child(2):  bracket_right_link
                child(1):  motor_right_link
            child(3):  standoff_front_left_link
            child(4):  standoff_front_right_link
            child(5):  standoff_rear_left_link
            child(6):  standoff_rear_right_link
            child(7):  top_plate_link
        child(2):  caster_link
        child(3):  laser_link
        child(4):  wheel_left_link
        child(5):  wheel_right_link
"""


def test_discovery_finds_parts_steps_and_the_robot():
    found = {f.as_posix() for f in description_files()}
    for part in ("motor", "wheel", "wheel_castor", "chassis", "laser"):
        assert f"{part}/test_{part}.urdf.xacro" in found
    assert COMPLETE_ROBOT in found
    assert len([f for f in found if "/steps/" in f]) >= 3


def test_check_urdf_accepts(robot_file, built_dir, check_urdf):
    done = run_check_urdf(check_urdf, built_dir / built_name(robot_file))
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Successfully Parsed XML" in done.stdout


def test_yourdfpy_loads_and_validates(robot_file, built_dir, load_urdf):
    urdf = load_urdf(built_dir / built_name(robot_file))
    assert urdf.validate(), urdf.errors
    assert urdf.validate_filenames(), "a mesh file does not resolve"
    # Every visual, meshes included, made it into the trimesh scene, none of them empty.
    visuals = sum(len(link.visuals) for link in urdf.robot.links)
    assert len(urdf.scene.graph.nodes_geometry) == visuals
    for name in urdf.scene.graph.nodes_geometry:
        geometry = urdf.scene.geometry[urdf.scene.graph[name][1]]
        assert len(geometry.faces) > 0, name


def test_every_body_has_visual_collision_inertial(robot_file, built_dir, load_urdf):
    urdf = load_urdf(built_dir / built_name(robot_file))
    for link in urdf.robot.links:
        parts = {"visual": bool(link.visuals), "collision": bool(link.collisions),
                 "inertial": link.inertial is not None}
        if link.name in FRAME_ONLY_LINKS:
            assert not any(parts.values()), f"{link.name} should be a pure frame: {parts}"
        else:
            missing = [k for k, v in parts.items() if not v]
            assert all(parts.values()), f"{link.name} lacks {missing}"


def test_inertials_are_physically_possible(robot_file, built_dir, load_urdf):
    urdf = load_urdf(built_dir / built_name(robot_file))
    for link in urdf.robot.links:
        if link.inertial is None:
            continue
        assert link.inertial.mass > 0, link.name
        tensor = np.asarray(link.inertial.inertia, dtype=float)
        assert np.allclose(tensor, tensor.T), link.name
        principal = np.linalg.eigvalsh(tensor)
        assert principal.min() > 0, f"{link.name}: not positive definite {principal}"
        a, b, c = principal
        assert a + b >= c * (1 - 1e-12), f"{link.name}: triangle inequality fails {principal}"


def test_materials_defined_once_and_only_referenced(robot_file, built_dir):
    tree = etree.parse(str(built_dir / built_name(robot_file)))
    defined = [m.get("name") for m in tree.getroot().findall("material")]
    assert [name for name, n in Counter(defined).items() if n > 1] == []
    for material in tree.getroot().iterfind("link/visual/material"):
        assert len(material) == 0, "a visual redefines a colour instead of naming the palette's"
        assert material.get("name") in defined


def test_complete_robot_uses_the_whole_palette(built_dir):
    tree = etree.parse(str(built_dir / built_name(Path(COMPLETE_ROBOT))))
    defined = {m.get("name") for m in tree.getroot().findall("material")}
    used = {m.get("name") for m in tree.getroot().iterfind("link/visual/material")}
    assert used == defined


def test_complete_robot_links_and_joints(complete_robot):
    assert {link.name for link in complete_robot.robot.links} == COMPLETE_LINKS
    assert {j.name: j.type for j in complete_robot.robot.joints} == COMPLETE_JOINTS
    assert complete_robot.base_link == "base_footprint"


def test_complete_robot_tree_as_check_urdf_prints_it(built_dir, check_urdf):
    done = run_check_urdf(check_urdf, built_dir / built_name(Path(COMPLETE_ROBOT)))
    assert done.stdout == COMPLETE_TREE


def _canonical(path: Path) -> list[bytes]:
    """The robot's links, joints and materials as canonical XML, comments and name aside."""
    parser = etree.XMLParser(remove_comments=True, remove_blank_text=True)
    root = etree.parse(str(path), parser).getroot()
    return sorted(etree.tostring(child, method="c14n") for child in root)


def test_last_chassis_step_is_the_finished_chassis(built_dir):
    steps = sorted((URDF / "chassis" / "steps").glob("*.xacro"))
    last = built_dir / built_name(steps[-1].relative_to(URDF))
    finished = built_dir / "chassis" / "test_chassis.urdf"
    assert _canonical(last) == _canonical(finished)


def test_each_chassis_step_adds_to_the_one_before(built_dir, load_urdf):
    steps = sorted((URDF / "chassis" / "steps").glob("*.xacro"))
    links = [{link.name for link in load_urdf(built_dir / built_name(s.relative_to(URDF)))
              .robot.links} for s in steps]
    for before, after in zip(links, links[1:], strict=False):
        assert before < after
