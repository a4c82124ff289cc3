"""The complete robot stands the way the real car does, checked by forward kinematics of the
BUILT URDF at zero joint positions (yourdfpy), never by re-reading config.xacro: both wheels
and the castor touch the ground, nothing else does, the plates are level, the parts that are
screwed together touch, no two bodies overlap, and the car does not tip over."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

GROUND_TOLERANCE = 1e-3  # m: the "at z = 0 within 1 mm"
TOUCH_TOLERANCE = 1e-9  # m: faces that are meant to meet, up to float rounding
CONTACT_LINKS = {"wheel_left_link", "wheel_right_link", "caster_link"}


@pytest.fixture(scope="module")
def collisions(complete_robot, posed):
    return posed(complete_robot, "collision")


def by_link(elements, link):
    found = [e for e in elements if e.link == link]
    assert found, f"no collision geometry on {link}"
    return found


def lowest(elements, link) -> float:
    return min(e.lowest() for e in by_link(elements, link))


def highest(elements, link) -> float:
    return max(e.highest() for e in by_link(elements, link))


@pytest.mark.parametrize("link", sorted(CONTACT_LINKS))
def test_wheels_and_castor_touch_the_ground(collisions, link):
    assert abs(lowest(collisions, link)) <= GROUND_TOLERANCE


def test_nothing_else_reaches_the_ground(collisions):
    clearance = {e.link: e.lowest() for e in collisions if e.link not in CONTACT_LINKS}
    assert min(clearance.values()) > 0.01, clearance


@pytest.mark.parametrize("link", ["body_link", "top_plate_link"])
def test_plates_are_level(collisions, link):
    (plate,) = by_link(collisions, link)
    assert plate.geometry.box is not None
    # the plate's thin axis is vertical and its faces are at one height everywhere
    assert np.allclose(plate.transform[:3, 2], [0, 0, 1], atol=1e-12)
    assert plate.geometry.box.size[2] == min(plate.geometry.box.size)


def test_second_plate_rests_on_the_standoffs(collisions):
    standoffs = sorted({e.link for e in collisions if e.link.startswith("standoff_")})
    assert len(standoffs) == 4
    for standoff in standoffs:
        assert lowest(collisions, standoff) == pytest.approx(highest(collisions, "body_link"),
                                                             abs=TOUCH_TOLERANCE)
        assert highest(collisions, standoff) == pytest.approx(
            lowest(collisions, "top_plate_link"), abs=TOUCH_TOLERANCE)


def test_castor_is_screwed_under_the_bottom_plate(collisions):
    assert highest(collisions, "caster_link") == pytest.approx(lowest(collisions, "body_link"),
                                                               abs=TOUCH_TOLERANCE)


def test_laser_sits_on_the_second_plate(collisions):
    assert lowest(collisions, "laser_link") == pytest.approx(
        highest(collisions, "top_plate_link"), abs=TOUCH_TOLERANCE)


def test_brackets_hang_from_the_bottom_plate(collisions):
    for side in ("left", "right"):
        assert highest(collisions, f"bracket_{side}_link") == pytest.approx(
            lowest(collisions, "body_link"), abs=TOUCH_TOLERANCE)


def test_scan_plane_sees_over_the_whole_car(complete_robot, collisions):
    scan_height = complete_robot.get_transform("laser_link", "base_footprint")[2, 3]
    others = [e for e in collisions if e.link != "laser_link"]
    assert scan_height > max(e.highest() for e in others)


@pytest.mark.parametrize("side, sign", [("left", 1), ("right", -1)])
def test_wheels_turn_about_the_axle(complete_robot, side, sign):
    joint = complete_robot.joint_map[f"wheel_{side}_joint"]
    assert joint.type == "continuous"
    pose = complete_robot.get_transform(f"wheel_{side}_link", "base_footprint")
    # Both axes +y in the world: a positive speed drives either wheel forwards.
    assert np.allclose(pose[:3, :3] @ joint.axis, [0, 1, 0], atol=1e-12)
    assert np.sign(pose[1, 3]) == sign
    base = complete_robot.get_transform("base_link", "base_footprint")
    assert pose[2, 3] == pytest.approx(base[2, 3], abs=1e-12), "wheel centre off the axle"


def test_motor_shafts_reach_into_their_wheels(complete_robot, posed, collisions):
    visuals = posed(complete_robot, "visual")
    for side, sign in (("left", 1), ("right", -1)):
        (motor,) = [e for e in visuals if e.link == f"motor_{side}_link"]
        shaft_tip = motor.support([0, sign, 0])  # outermost point of the mesh
        (tyre,) = by_link(collisions, f"wheel_{side}_link")
        inner_face, outer_face = -tyre.support([0, -sign, 0]), tyre.support([0, sign, 0])
        assert inner_face < shaft_tip < outer_face, (side, inner_face, shaft_tip, outer_face)


def _adjacent(urdf) -> set[frozenset[str]]:
    return {frozenset((j.parent, j.child)) for j in urdf.robot.joints}


def test_no_two_bodies_overlap(complete_robot, collisions):
    """Axis-aligned bounds of every pair of collision elements on links that are not joined
    directly; faces that only touch (plate on standoff, laser on plate) are allowed."""
    adjacent = _adjacent(complete_robot)
    bounds = [(e.link, e.bounds()) for e in collisions]
    overlaps = []
    for (link_a, a), (link_b, b) in itertools.combinations(bounds, 2):
        if link_a == link_b or frozenset((link_a, link_b)) in adjacent:
            continue
        depth = np.minimum(a[1], b[1]) - np.maximum(a[0], b[0])
        if np.all(depth > TOUCH_TOLERANCE):
            overlaps.append((link_a, link_b, depth.min()))
    assert overlaps == []


def _centre_of_mass(urdf) -> tuple[float, np.ndarray]:
    total, moment = 0.0, np.zeros(3)
    for link in urdf.robot.links:
        if link.inertial is None:
            continue
        origin = np.eye(4) if link.inertial.origin is None else link.inertial.origin
        centre = (urdf.get_transform(link.name, urdf.base_link) @ origin)[:3, 3]
        total += link.inertial.mass
        moment += link.inertial.mass * centre
    return total, moment / total


def test_total_mass_is_plausible_for_the_kit(complete_robot):
    mass, _ = _centre_of_mass(complete_robot)
    assert 0.4 < mass < 1.5, f"{mass:.3f} kg is not a small two-plate kit car"


def test_centre_of_mass_is_inside_the_wheel_castor_triangle(complete_robot, collisions):
    _, centre = _centre_of_mass(complete_robot)
    contacts = []
    for link in sorted(CONTACT_LINKS):
        element = min(by_link(collisions, link), key=lambda e: e.lowest())
        contacts.append(element.transform[:2, 3])
    def turn(p, q, r):  # z of (q - p) x (r - p): which side of p->q the point r is on
        return np.sign((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))

    a, b, c = contacts
    signs = [turn(p, q, centre[:2]) for p, q in ((a, b), (b, c), (c, a))]
    assert len(set(signs)) == 1 and 0 not in signs, (contacts, centre)
